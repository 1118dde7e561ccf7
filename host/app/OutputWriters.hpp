// The writers a run's output settings ask for, each created from them (docs/design.md, "Outputs"). A new
// output is a new io::FrameWriter class and one line here; the run loop does not change.
//
//   auto writers = fw::host::make_writers(plan, "out/storm", cc.device(), /*tip_trees=*/{0, 1, 2, 3});
//   fw::io::OutputPipeline output(std::move(writers));
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "host/app/SimulationPlan.hpp"
#include "host/runtime/Device.hpp"
#include "host/stages/BlockGrid.hpp"
#include "io/writers/FrameWriter.hpp"
#include "viz/ViewScript.hpp"

namespace fw::host {

/// A run over MPI ranks: what this rank writes (docs/parallel.md, "Output"). Every rank writes its piece of
/// the wind and its trees' piece; rank 0 also writes what stays one file (run.json, probes.csv, view.py, the
/// summaries that list the pieces).
struct OutputShare {
  int rank = 0, ranks = 1;
  fluid::GridSpec local;  ///< this rank's grid: its block with the halo (WindGrid::local_spec)
  BlockArray block;       ///< its layout (WindGrid::block)
  fluid::Decomposition decomposition;
  const trees::Forest* own_forest = nullptr;  ///< the trees it holds (CoupledStep::own_forest)
};

/// Whether the VDB frames hold the leaves' points grid: VDB on, a forest with leaves, and "leaves" among
/// output.vdb.grids.
bool vdb_holds_leaves(const SimulationPlan& plan);

/// view.py's settings: the domain, slice and speed scale, and which collections it opens.
viz::ViewScriptSettings view_settings(const SimulationPlan& plan);

/// In order: the manifest (run.json, scenario copy), wind VTK, trees VTK, VDB, probes, view.py; each only
/// when the settings enable it (probes when there are probe points or tracked trees: tip_trees, the instance
/// ids), the frame writers with their every-N (output.vtk.wind_every, ...). Over ranks (share given), each
/// rank only its part.
std::vector<std::unique_ptr<io::FrameWriter>> make_writers(const SimulationPlan& plan,
                                                           const std::filesystem::path& directory,
                                                           const DeviceInfo& device,
                                                           const std::vector<int>& tip_trees,
                                                           const OutputShare* share = nullptr);

}  // namespace fw::host
