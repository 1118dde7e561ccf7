// Small run output folders for the tests of viz/: what a run would have written (wind.pvd and its .vti
// frames, trees.pvd and its .vtp frames), made with the io/ writers, without a device.
#pragma once

#include <Eigen/Core>

#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "io/PvdCollection.hpp"
#include "io/TreesVtk.hpp"
#include "io/WindFrame.hpp"
#include "io/WindVtk.hpp"

namespace fw::test {

/// A box of nx x ny x nz cells of 1 m at the origin, with a uniform wind (u, 0, 0) m/s everywhere; cells in
/// [x0, x1) along x (all y, z) get `slow_u` instead, and cells of `solid_box` (i0, i1, j0, j1, k0, k1, half
/// open) are solid and still.
struct UniformWind {
  std::array<int, 3> cells{40, 20, 10};
  float u = 6.0f;
  int slow_x0 = 0, slow_x1 = 0;
  float slow_u = 0.0f;
  std::array<int, 6> solid_box{0, 0, 0, 0, 0, 0};

  io::WindFrame frame(double time) const {
    io::WindFrame f;
    f.dims = cells;
    f.h = 1.0;
    f.time = time;
    f.velocity.assign(3 * f.cell_count(), 0.0f);
    f.solid.assign(f.cell_count(), 0);
    for (int k = 0; k < cells[2]; ++k)
      for (int j = 0; j < cells[1]; ++j)
        for (int i = 0; i < cells[0]; ++i) {
          const std::size_t c = f.cell_index(i, j, k);
          const bool solid = i >= solid_box[0] && i < solid_box[1] && j >= solid_box[2] && j < solid_box[3] &&
                             k >= solid_box[4] && k < solid_box[5];
          f.solid[c] = solid;
          f.velocity[3 * c] = solid ? 0.0f : (i >= slow_x0 && i < slow_x1 ? slow_u : u);
        }
    return f;
  }
};

/// One straight vertical trunk of `nodes` nodes from (x, y, 0) to height `height` (m), radius `radius` (m),
/// every node displaced by `sway` m along x times its height fraction.
inline io::TreesFrame::Tree trunk(double x, double y, double height, double radius, int nodes, double sway) {
  io::TreesFrame::Tree t;
  t.rest.resize(nodes, 3);
  t.displacement.resize(nodes, 3);
  for (int n = 0; n < nodes; ++n) {
    const double f = double(n) / (nodes - 1);
    t.rest.row(n) << x, y, f * height;
    t.displacement.row(n) << sway * f, 0.0, 0.0;
    t.radius.push_back(radius);
    t.parent.push_back(n - 1);
  }
  return t;
}

/// Writes `frames` frames at t = 0, interval, 2 interval ... into `folder` as a run does (wind and, when
/// `trees` is not empty, trees), the .pvd files listing each.
inline void write_run(const std::filesystem::path& folder, const UniformWind& wind,
                      const std::vector<io::TreesFrame::Tree>& trees, int frames, double interval) {
  std::filesystem::create_directories(folder / "wind");
  std::filesystem::create_directories(folder / "trees");
  io::PvdCollection wind_pvd(folder / "wind.pvd"), trees_pvd(folder / "trees.pvd");
  for (int n = 0; n < frames; ++n) {
    const double t = n * interval;
    const std::string wind_file = fmt::format("wind/wind_{:06d}.vti", n);
    io::write_wind_vti(folder / wind_file, wind.frame(t), {"velocity", "speed", "solid"});
    wind_pvd.add(t, wind_file);
    if (trees.empty()) continue;
    const std::string trees_file = fmt::format("trees/trees_{:06d}.vtp", n);
    io::TreesFrame forest;
    forest.time = t;
    forest.trees = trees;
    io::write_trees_vtp(folder / trees_file, forest);
    trees_pvd.add(t, trees_file);
  }
}

/// A damage.csv as a run with forest.damage.enabled writes it: the header line, then `rows` (each without
/// its line end), e.g. "0,spruce,6,10,8,0.3,standing,,,,1e4,5e4,6e4,0.5".
inline std::string damage_csv(const std::vector<std::string>& rows) {
  std::string text =
      "tree_id,species,x,y,height_m,dbh_m,state,time_s,break_height_m,top_wind_m_s,max_base_moment_Nm,"
      "critical_breakage_Nm,critical_overturning_Nm,max_utilisation\n";
  for (const std::string& row : rows) text += row + "\n";
  return text;
}

}  // namespace fw::test
