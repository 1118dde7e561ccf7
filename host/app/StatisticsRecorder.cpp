#include "host/app/StatisticsRecorder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "base/WallClock.hpp"
#include "fluid/SubgridStress.hpp"

namespace fw::host {

namespace {

using Clock = base::WallClock;
using base::ms_since;

// The time series' columns, in series_columns()'s order.
enum Series {
  u_star,
  kinetic_energy,
  max_speed,
  dt,
  cfl,
  pressure_iterations,
  leaves_shed,
  leaves_landed,
  trees_broken,
  trees_overturned,
  series_count
};

// A checkpoint's numbers: the next record's time and the window's samples, then the window's sums, then
// each area's scales (whether known, and an exponent a term).
constexpr std::size_t kSavedHead = 2;
constexpr std::size_t kSavedScales = 1 + FW_PLANE_TERMS;

// The area `name` of `spec`'s cells `cells`, with the box those whole cells fill (m).
StatisticsArea area_of(const fluid::GridSpec& spec, std::string name, const PlaneRegion& cells) {
  StatisticsArea area{std::move(name), cells, {}, {}};
  for (std::size_t a = 0; a < 2; ++a) {
    const int end = cells.end[a] > 0 ? cells.end[a] : spec.cells_along(int(a));
    area.min[a] = spec.origin[a] + cells.first[a] * spec.h;
    area.max[a] = spec.origin[a] + end * spec.h;
  }
  return area;
}

// The area `name` of the cells whose centres lie in the box min .. max (m).
StatisticsArea area_in(const fluid::GridSpec& spec, std::string name, const std::array<double, 2>& min,
                       const std::array<double, 2>& max) {
  PlaneRegion cells;
  for (std::size_t a = 0; a < 2; ++a) {
    const std::array<int, 2> span =
        io::statistics_cells(min[a], max[a], spec.origin[a], spec.h, spec.cells_along(int(a)));
    cells.first[a] = span[0];
    cells.end[a] = span[1];
  }
  return area_of(spec, std::move(name), cells);
}

}  // namespace

std::vector<io::StatsVariable> series_columns() {
  return {
      {"u_star", "m s-1", "friction velocity at the ground", ""},
      {"ke", "m2 s-2", "resolved kinetic energy per unit mass, mean over the fluid cells", ""},
      {"max_speed", "m s-1", "largest wind speed at a cell centre", ""},
      {"dt", "s", "time step", ""},
      {"cfl", "1", "Courant number of the step", ""},
      {"pressure_iterations", "1", "iterations of the step's pressure solve", ""},
      {"leaves_shed", "1", "leaves shed so far", ""},
      {"leaves_landed", "1", "leaves landed so far", ""},
      {"trees_broken", "1", "trees broken so far", ""},
      {"trees_overturned", "1", "trees overturned so far", ""},
  };
}

std::vector<StatisticsArea> statistics_areas(const SimulationPlan& plan) {
  const fluid::GridSpec& spec = plan.wind.spec;
  std::vector<StatisticsArea> areas{area_of(spec, "", PlaneRegion{})};
  if (!plan.output.statistics) return areas;
  for (const io::StatisticsRegion& region : plan.output.statistics->regions)
    areas.push_back(area_in(spec, region.name, region.min, region.max));
  if (plan.output.statistics->stands)
    for (std::size_t n = 0; n < plan.stands.size(); ++n) {
      const StandPlan& stand = plan.stands[n];
      StatisticsArea area = area_in(spec, fmt::format("{}{}", io::kStandRegionPrefix, n + 1),
                                    {stand.min.x(), stand.min.y()}, {stand.max.x(), stand.max.y()});
      // A stand outside the domain, or narrower than a cell, averages nothing: left out.
      if (area.cells.end[0] > area.cells.first[0] && area.cells.end[1] > area.cells.first[1])
        areas.push_back(std::move(area));
    }
  return areas;
}

StatisticsRecorder::StatisticsRecorder(ComputeContext& cc, const SimulationPlan& plan, CoupledStep& coupled,
                                       const Communicator& world, std::filesystem::path file)
    : plan_(plan), coupled_(coupled), world_(world), file_(std::move(file)) {
  if (!plan.output.statistics) return;
  const WindGrid& wind = coupled.wind();
  statistics_.emplace(cc, wind.spec(), wind.local_spec(), wind.block(), world);
  areas_ = statistics_areas(plan);
  scales_.assign(areas_.size(), PlaneScales{});
  records_ = Schedule(plan.output.statistics->interval);
  const fluid::GridSpec& spec = plan.wind.spec;
  window_.assign(areas_.size() * fluid::kProfileCount * std::size_t(spec.nz), 0.0);
  out_.title = plan.scenario.name;
  out_.history = "forestwind run " + plan.scenario.file_name;
  out_.interval = plan.output.statistics->interval;
  out_.averaging = plan.output.statistics->averaging;
  for (int k = 0; k < spec.nz; ++k) out_.z.push_back(spec.origin[2] + (k + 0.5) * spec.h);
  out_.profiles.variables = io::profile_columns();
  out_.series.variables = series_columns();
  for (std::size_t n = 1; n < areas_.size(); ++n)
    out_.regions.push_back({areas_[n].name, areas_[n].min, areas_[n].max, {}});
}

fluid::PlaneProfiles StatisticsRecorder::sample_window(double speed_bound) {
  const WindStatisticsFields fields = coupled_.wind().statistics_fields();
  const std::size_t nz = out_.z.size();
  fluid::PlaneProfiles domain;
  for (std::size_t a = 0; a < areas_.size(); ++a) {
    const fluid::PlaneProfiles p = statistics_->sample(fields, speed_bound, areas_[a].cells, &scales_[a]);
    for (std::size_t v = 0; v < fluid::kProfileCount; ++v)
      for (std::size_t k = 0; k < nz; ++k) window_[(a * fluid::kProfileCount + v) * nz + k] += p.values[v][k];
    if (a == 0) domain = p;
  }
  ++samples_;
  return domain;
}

double StatisticsRecorder::ground_friction_velocity(const fluid::PlaneProfiles& p, int k) const {
  using fluid::Profile;
  const double z0 = plan_.wind.settings.wall_roughness_length;
  if (z0 > 0.0) {
    // The log law the wall stage imposes (fluid/SubgridStress.hpp), on the plane's mean wind.
    const double c_w = fluid::wall_drag_coefficient(plan_.wind.spec.h, z0);
    return std::sqrt(c_w) * std::hypot(p.at(Profile::u, k), p.at(Profile::v, k));
  }
  return std::sqrt(std::hypot(p.at(Profile::u_flux, k), p.at(Profile::v_flux, k)));
}

std::vector<double> StatisticsRecorder::series_row(const fluid::PlaneProfiles& p,
                                                   const CoupledStepReport& report) {
  using fluid::Profile;
  std::vector<double> row(series_count, 0.0);
  // u*: the total flux at the lowest height with fluid; the kinetic energy: the planes' means of |u|^2 / 2
  // (mean flow and resolved fluctuation), weighted by their fluid cells.
  double weight = 0.0, energy = 0.0;
  bool lowest = true;
  for (int k = 0; k < p.nz; ++k) {
    const double area = p.at(Profile::area, k);
    if (!(area > 0.0)) continue;
    if (lowest) {
      row[u_star] = ground_friction_velocity(p, k);
      lowest = false;
    }
    const double u = p.at(Profile::u, k), v = p.at(Profile::v, k), w = p.at(Profile::w, k);
    energy += area * (0.5 * (u * u + v * v + w * w) + p.at(Profile::tke, k));
    weight += area;
  }
  row[kinetic_energy] = weight > 0.0 ? energy / weight : 0.0;
  row[max_speed] = statistics_->largest_speed();
  row[dt] = report.wind.dt;
  row[cfl] = report.cfl;
  row[pressure_iterations] = report.wind.pressure.iterations;
  if (coupled_.has_leaves()) {
    const trees::LeafCounts leaves = coupled_.leaves().counts();  // collective
    row[leaves_shed] = double(leaves.shed);
    row[leaves_landed] = double(leaves.landed);
  }
  const trees::DamageCounts damage = coupled_.damage_counts();  // collective; zero without damage
  row[trees_broken] = double(damage.broken);
  row[trees_overturned] = double(damage.overturned);
  return row;
}

void StatisticsRecorder::close_record(double time) {
  const std::size_t nz = out_.z.size();
  const auto record = [&](std::size_t a) {
    std::vector<std::vector<double>> values(fluid::kProfileCount, std::vector<double>(nz, 0.0));
    for (std::size_t v = 0; v < fluid::kProfileCount; ++v)
      for (std::size_t k = 0; k < nz; ++k)
        values[v][k] = window_[(a * fluid::kProfileCount + v) * nz + k] / double(samples_);
    return values;
  };
  out_.profiles.time.push_back(time);
  out_.profiles.values.push_back(record(0));
  for (std::size_t a = 1; a < areas_.size(); ++a) out_.regions[a - 1].values.push_back(record(a));
  std::fill(window_.begin(), window_.end(), 0.0);
  samples_ = 0;
}

void StatisticsRecorder::after_step(const CoupledStepReport& report) {
  if (!on()) return;
  const auto start = Clock::now();
  const io::StatisticsSettings& s = *plan_.output.statistics;
  const double t = report.wind.time;
  const long step = report.wind.step;
  const bool record = records_.reached(t);
  const bool in_window =
      s.averaging > 0.0 && t > records_.next() - s.averaging + kScheduleTolerance * s.interval;
  const bool series = step % s.series_every == 0;
  std::optional<fluid::PlaneProfiles> domain;
  if (record || (in_window && step % s.sample_every == 0)) domain = sample_window(report.max_speed_component);
  if (series) {
    if (!domain)
      domain = statistics_->sample(coupled_.wind().statistics_fields(), report.max_speed_component,
                                   areas_[0].cells, &scales_[0]);
    out_.series.time.push_back(t);
    out_.series.values.push_back(series_row(*domain, report));
  }
  if (record) {
    records_.due(t);
    close_record(t);
    write();
  }
  ms_ += ms_since(start);
}

void StatisticsRecorder::write() {
  if (!on() || world_.rank() != 0) return;
  const auto start = Clock::now();
  io::write_stats_netcdf(file_, out_);
  ms_ += ms_since(start);
}

std::vector<double> StatisticsRecorder::saved() const {
  if (!on()) return {};
  std::vector<double> numbers{records_.next(), double(samples_)};
  numbers.insert(numbers.end(), window_.begin(), window_.end());
  for (const PlaneScales& s : scales_) {
    numbers.push_back(s.known ? 1.0 : 0.0);
    numbers.insert(numbers.end(), s.exponents.begin(), s.exponents.end());
  }
  return numbers;
}

void StatisticsRecorder::resume(double time, const std::vector<double>& saved) {
  if (!on()) return;
  if (!saved.empty()) {
    const std::size_t expected = kSavedHead + window_.size() + kSavedScales * scales_.size();
    if (saved.size() != expected)
      throw std::invalid_argument(fmt::format(
          "output.statistics: the checkpoint's averaging window holds {} numbers, this run's regions and "
          "heights take {}: a resume keeps output.statistics as it was",
          saved.size(), expected));
    records_.resume(saved[0]);
    samples_ = long(saved[1]);
    const auto window_end = saved.begin() + long(kSavedHead + window_.size());
    std::copy(saved.begin() + kSavedHead, window_end, window_.begin());
    for (std::size_t a = 0; a < scales_.size(); ++a) {
      const auto at = window_end + long(kSavedScales * a);
      scales_[a].known = at[0] != 0.0;
      for (std::size_t t = 0; t < FW_PLANE_TERMS; ++t) scales_[a].exponents[t] = int(at[long(1 + t)]);
    }
  } else {
    records_.resume(plan_.output.statistics->interval *
                    (std::floor(time / plan_.output.statistics->interval + kScheduleTolerance) + 1.0));
  }
  if (!std::filesystem::exists(file_)) return;
  // What the file holds up to the checkpoint: a run killed after it wrote more, which the resumed run writes
  // again. Every rank reads it, so that every rank's copy is rank 0's.
  const io::StatsFile read = io::read_stats_netcdf(file_);
  const double tolerance = kScheduleTolerance * plan_.output.statistics->interval;
  const auto kept = [&](const std::vector<double>& times) {
    return std::size_t(std::upper_bound(times.begin(), times.end(), time + tolerance) - times.begin());
  };
  const auto refuse = [&](const std::string& what) {
    throw std::invalid_argument(
        fmt::format("{}: not this run's statistics ({}): a resume keeps output.statistics "
                    "as it was",
                    file_.string(), what));
  };
  if (read.z != out_.z) refuse("other heights");
  if (read.regions.size() != out_.regions.size()) refuse("other regions");
  // The file lists its variables by name (io/StatsNetcdf): each of this run's, found by its name there.
  const auto positions = [&](const std::vector<io::StatsVariable>& theirs,
                             const std::vector<io::StatsVariable>& ours) {
    std::vector<std::size_t> at;
    for (const io::StatsVariable& v : ours) {
      const auto found = std::find(theirs.begin(), theirs.end(), v);
      if (found == theirs.end()) refuse("no variable " + v.name);
      at.push_back(std::size_t(found - theirs.begin()));
    }
    if (theirs.size() != ours.size()) refuse("other variables");
    return at;
  };
  const std::vector<std::size_t> profile_at = positions(read.profiles.variables, out_.profiles.variables);
  const std::vector<std::size_t> series_at = positions(read.series.variables, out_.series.variables);
  const auto in_our_order = [](const auto& record, const std::vector<std::size_t>& at) {
    std::decay_t<decltype(record)> ours;
    for (const std::size_t n : at) ours.push_back(record[n]);
    return ours;
  };
  const std::size_t records = kept(read.profiles.time), rows = kept(read.series.time);
  out_.profiles.time.assign(read.profiles.time.begin(), read.profiles.time.begin() + long(records));
  out_.profiles.values.clear();
  for (std::size_t r = 0; r < records; ++r)
    out_.profiles.values.push_back(in_our_order(read.profiles.values[r], profile_at));
  for (io::StatsRegion& region : out_.regions) {
    const auto theirs = std::find_if(read.regions.begin(), read.regions.end(),
                                     [&](const io::StatsRegion& r) { return r.name == region.name; });
    if (theirs == read.regions.end()) refuse("no region " + region.name);
    region.values.clear();
    for (std::size_t r = 0; r < records; ++r)
      region.values.push_back(in_our_order(theirs->values[r], profile_at));
  }
  out_.series.time.assign(read.series.time.begin(), read.series.time.begin() + long(rows));
  out_.series.values.clear();
  for (std::size_t r = 0; r < rows; ++r)
    out_.series.values.push_back(in_our_order(read.series.values[r], series_at));
}

}  // namespace fw::host
