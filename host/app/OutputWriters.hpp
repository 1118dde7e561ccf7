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
#include "io/writers/FrameWriter.hpp"

namespace fw::host {

/// In order: the manifest (run.json, scenario copy), wind VTK, trees VTK, VDB, probes, view.py; each only
/// when the settings enable it (probes when there are probe points or tracked trees: tip_trees, the instance
/// ids).
std::vector<std::unique_ptr<io::FrameWriter>> make_writers(const SimulationPlan& plan,
                                                           const std::filesystem::path& directory,
                                                           const DeviceInfo& device,
                                                           const std::vector<int>& tip_trees);

}  // namespace fw::host
