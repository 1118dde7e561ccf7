// print_plan: what `forestwind check` shows of a plan, read from the plan alone.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "host/app/OutputSize.hpp"
#include "host/app/SimulationPlan.hpp"

namespace fw::host {

namespace {

// MB, or kB for the small parts (a few probes), so that no part reads 0.0.
std::string megabytes(std::size_t bytes) {
  constexpr double kMega = 1e6, kKilo = 1e3;
  return bytes >= kMega / 10 ? fmt::format("{:.1f} MB", double(bytes) / kMega)
                             : fmt::format("{:.1f} kB", double(bytes) / kKilo);
}

// A rough ground is a slip wall for the grid plus the log-law stress (fluid::WindSettings).
std::string boundaries_line(const WindGridSetup& wind) {
  static const char* faces[6] = {"west", "east", "south", "north", "ground", "top"};
  std::string line;
  for (int f = 0; f < 6; ++f) {
    const bool rough = f == FW_FACE_GROUND && wind.settings.wall_roughness_length > 0.0;
    line += fmt::format("{}{} {}", f ? ", " : "", faces[f],
                        rough ? fmt::format("rough (z0 {} m)", wind.settings.wall_roughness_length)
                              : fluid::to_string(wind.spec.boundary[std::size_t(f)]));
  }
  return line;
}

// The subgrid model with its constant: a scenario that names none may still get one (upwind5's
// Smagorinsky constant), and a constant of 0 runs no subgrid stage at all.
std::string subgrid_words(const fluid::WindSettings& settings) {
  if (settings.subgrid != fluid::SubgridModel::smagorinsky) return fluid::to_string(settings.subgrid);
  if (settings.smagorinsky_constant <= 0.0) return "none (smagorinsky, C_s 0)";
  return fmt::format("smagorinsky, C_s {:.3g}", settings.smagorinsky_constant);
}

// The inventory (docs/gis.md): what was placed, what lies outside, and the girth classes per species.
void print_inventory(const SimulationPlan& plan, std::ostream& out) {
  const InventoryPlan& inventory = *plan.inventory;
  out << fmt::format("inventory {}: {} trees, {} in the domain, {} outside it (not placed){}\n",
                     inventory.file, inventory.placed + inventory.outside.size(), inventory.placed,
                     inventory.outside.size(), inventory.outside.empty() ? "" : ":");
  constexpr std::size_t kListed = 5;  // the first few by name; the rest counted
  for (std::size_t k = 0; k < std::min(inventory.outside.size(), kListed); ++k) {
    const io::InventoryTree& tree = inventory.outside[k];
    out << fmt::format("  {} (line {}) at x {}, y {}\n", tree.id, tree.line, tree.x, tree.y);
  }
  if (inventory.outside.size() > kListed)
    out << fmt::format("  and {} more\n", inventory.outside.size() - kListed);
  // Per scenario species: its inventory trees over its girth classes.
  std::vector<std::string> names;
  for (const io::SpeciesSummary& s : plan.species)
    if (s.girth == 1.0 && std::find(names.begin(), names.end(), s.species) == names.end())
      names.push_back(s.species);
  for (const std::string& name : names) {
    int classes = 0, trees = 0;
    double low = 1.0, high = 1.0, low_hz = 0.0, high_hz = 0.0;
    for (const io::SpeciesSummary& s : plan.species) {
      if (s.species != name || s.girth == 1.0) continue;
      if (classes++ == 0) low_hz = high_hz = s.first_hz;
      trees += s.trees;
      low = std::min(low, s.girth);
      high = std::max(high, s.girth);
      low_hz = std::min(low_hz, s.first_hz);
      high_hz = std::max(high_hz, s.first_hz);
    }
    if (classes == 0) continue;
    out << fmt::format(
        "  {}: {} trees in {} girth classes of their own, radii {:.2f} to {:.2f} times the "
        "template's, f1 {:.3f} to {:.3f} Hz at the template's height\n",
        name, trees, classes, low, high, low_hz, high_hz);
  }
  out << fmt::format("  each tree its measured height, and its dbh within {:.2f}%\n",
                     100.0 * inventory.largest_dbh_error);
}

// A stand's density as foresters give it (trees/StandDensity.hpp): LAI over its region, with the leaf area
// index of each crown that makes it, and FAI over its grid columns.
std::string stand_line(std::size_t index, const StandPlan& stand) {
  const trees::StandDensity& d = stand.density;
  const Eigen::Vector2d extent = stand.max - stand.min;
  const std::string crowns = stand.leaf_area_index
                                 ? fmt::format("given; {:.3g} a crown", stand.crown_leaf_area_index)
                                 : fmt::format("the species' {:.3g} a crown", stand.crown_leaf_area_index);
  const std::string frontal =
      d.columns > 0
          ? fmt::format("frontal area index {:.2f} over {} grid columns", d.frontal_area_index(), d.columns)
          : std::string("no grid column centre in the region for a frontal area index");
  // 6 digits: a region given as 2.4 .. 93.6 m is 91.2 m wide, not its binary rounding.
  return fmt::format("stand {}: {} {} trees on {:.6g} x {:.6g} m, leaf area index {:.2f} ({}), {}", index,
                     d.trees, stand.species, extent.x(), extent.y(), d.leaf_area_index(), crowns, frontal);
}

// The blocks over the ranks, and each rank's block of the wind grid with its halo.
void print_decomposition(const SimulationPlan& plan, std::ostream& out) {
  const fluid::Decomposition& d = plan.decomposition;
  out << fmt::format("decomposition: {} over {} ranks, halo {} cells ({} halo cells per exchanged field)\n",
                     d.describe(), d.ranks(), d.halo(), d.halo_cells());
  for (int r = 0; r < d.ranks(); ++r) {
    const fluid::Block b = d.block(r);
    const BlockShare share{&d, r};
    const fluid::GridSpec local = share.local(plan.wind.spec);
    out << fmt::format("  rank {}: cells x {}-{}, y {}-{}; wind grid with its halo {} x {} x {}: {}\n", r,
                       b.first[0], b.first[0] + b.count[0] - 1, b.first[1], b.first[1] + b.count[1] - 1,
                       local.nx, local.ny, local.nz,
                       megabytes(WindGrid::estimate_device_bytes(plan.wind, share)));
  }
}

// A species' strength and critical winds at scale 1 (host/app/plan/DamagePlan.cpp). The section whose M_b
// is least is the top's, where nothing bends: what breaks first is the section a load brings to its M_b
// first, which the uniform wind finds.
std::string strength_line(const SpeciesStrength& s) {
  constexpr double kKilo = 1e3;
  const auto& wind = s.static_wind;
  return fmt::format(
      "strength {}: breaks at {:.1f} kN m at the base, overturns at {:.1f} kN m; a uniform wind {} first, at "
      "{:.1f} m/s (the model, static); Hale's critical mean wind at the canopy top {:.1f} m/s (h {:.1f} m, "
      "dbh {:.2f} m, lean 1.14)",
      s.source, s.critical.breaking.front() / kKilo, s.critical.overturning / kKilo,
      wind.breaks ? fmt::format("breaks it {:.1f} m up", s.static_break_height) : std::string("overturns it"),
      wind.speed, s.hale_wind, s.height, s.dbh);
}

}  // namespace

void print_plan(const SimulationPlan& plan, std::ostream& out) {
  const fluid::GridSpec& spec = plan.wind.spec;
  out << fmt::format("grid: {} x {} x {} = {} cells of {:.6g} m, domain {:.6g} x {:.6g} x {:.6g} m\n",
                     spec.nx, spec.ny, spec.nz, spec.cell_count(), spec.h, spec.nx * spec.h, spec.ny * spec.h,
                     spec.nz * spec.h);
  out << "boundaries at t = 0: " << boundaries_line(plan.wind) << "\n";
  out << fmt::format("solid cells: {}, gusts: {}, advection: {}, subgrid: {}, pressure: {}\n",
                     plan.solid_cells, plan.wind.gusts.size(), fluid::to_string(plan.wind.settings.advection),
                     subgrid_words(plan.wind.settings), fluid::to_string(plan.wind.settings.pressure.solver));
  if (const auto& box = plan.turbulence_box) {
    const auto& n = box->cells;
    const auto period = box->period();
    out << fmt::format(
        "turbulence: von Karman, L_u {} m, box {} x {} x {} points {} m apart ({} x {} x {} m), {}\n",
        box->spectrum.integral_length, n[0], n[1], n[2], box->spacing, period[0], period[1], period[2],
        plan.coupling.unresolved.enabled ? "unresolved eddies force the trees" : "no unresolved forcing");
  }
  for (std::size_t i = 0; i < plan.species.size(); ++i) {
    const io::SpeciesSummary& s = plan.species[i];
    if (s.girth != 1.0) continue;  // an inventory's girth class: summed up below
    const int leaves = plan.coupling.leaves[i].count();
    out << fmt::format(
        "species {}: {}, {} nodes, {} modes from {:.3f} Hz, {} wind samples, {} trees{} (basis {})\n", s.name,
        s.dynamics, s.nodes, s.modes, s.first_hz, s.samples, s.trees,
        leaves > 0 ? fmt::format(", {} leaves a tree", leaves) : "", s.cache);
    if (plan.strengths[i]) out << "  " << strength_line(*plan.strengths[i]) << "\n";
  }
  if (plan.inventory) print_inventory(plan, out);
  if (plan.coupling.damage.enabled)
    out << fmt::format("damage: on; {}\n",
                       plan.coupling.damage.consequences
                           ? "a failed tree falls, takes no load and leaves the air's drag"
                           : "failures recorded, failed trees stay up (consequences: false)");
  out << fmt::format("trees: {}, leaves: {}, two-way coupling: {}\n", plan.forest.instance_count(),
                     plan.leaf_count, plan.two_way_coupling ? "on" : "off");
  for (std::size_t k = 0; k < plan.stands.size(); ++k) out << stand_line(k, plan.stands[k]) << "\n";
  std::string parts;
  for (const auto& part : plan.memory.parts())
    parts += fmt::format("{}{} {}", parts.empty() ? "" : ", ", part.name, megabytes(part.bytes));
  out << fmt::format("estimated device memory: {} ({})\n", megabytes(plan.memory.total()), parts);
  if (plan.decomposition.splits()) print_decomposition(plan, out);
  const fluid::WindSettings& settings = plan.wind.settings;
  if (!(settings.cfl > 0.0)) {
    out << fmt::format("steps: {} (dt {} s to t = {} s)\n", long(std::ceil(plan.end_time / settings.dt)),
                       settings.dt, plan.end_time);
  } else {
    const double peak = plan.peak_wind;
    const double dt = planned_dt(plan);
    out << fmt::format(
        "steps: about {} or more (dt auto, CFL {}{}: {:.3f} s at the peak wind plus gusts, {:.1f} m/s, to t "
        "= "
        "{} s)\n",
        long(std::ceil(plan.end_time / dt)), settings.cfl,
        std::isfinite(advection_method(settings.advection).courant_limit)
            ? fmt::format(", {} limit {}", advection_method(settings.advection).name(),
                          advection_method(settings.advection).courant_limit)
            : "",
        dt, peak, plan.end_time);
  }
  if (plan.spin_up > 0.0)
    out << fmt::format(
        "spin-up: {}{} steps before t = 0 ({} s of wind at the t = 0 inputs, trees held in equilibrium, "
        "nothing written)\n",
        settings.cfl > 0.0 ? "at most about " : "", planned_spin_up_steps(plan), plan.spin_up);
  out << fmt::format("output: {} every {} s, {} probes\n", plan.output.directory.string(),
                     plan.output.interval, plan.output.probes.size());
  print_output_size(predict_output_size(plan, plan.end_time), out);
}

}  // namespace fw::host
