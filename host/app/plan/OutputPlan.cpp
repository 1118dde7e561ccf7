// The outputs' part of the plan: the folder, the frame interval, the writers and fields, the probes and
// their interval, the statistics' device memory, and the record of where the run came from (run.json and the
// scenario's copy).
#include <algorithm>
#include <string>
#include <vector>

#include "host/app/plan/PlanBuilders.hpp"
#include "host/stages/PlaneStatistics.hpp"
#include "host/stages/PointWindReadback.hpp"
#include "io/Scenario.hpp"

namespace fw::host {

void plan_outputs(const io::Scenario& scenario, SimulationPlan& plan) {
  plan.scenario = {scenario.name, scenario.file.filename().string(), scenario.text, scenario.seed, {}};
  if (const io::SiteSettings* site = scenario.site()) plan.scenario.site = *site;
  plan.output = scenario.output;
  // A domain with solid cells writes them into its wind frames, asked for or not: `export` and `render`
  // find the ground by them (a terrain-following slice through a hill otherwise reads the hill's inside).
  std::vector<std::string>& fields = plan.output.vtk_fields;
  if (plan.solid_cells > 0 && std::find(fields.begin(), fields.end(), "solid") == fields.end())
    fields.push_back("solid");
  plan.probe_interval = scenario.resolved_probe_interval().value_or(0.0);
  if (!plan.output.probes.empty())
    plan.memory.add("probes", PointWindReadback::estimate_device_bytes(plan.output.probes.size()));
  // The statistics' row partials (host/app/StatisticsRecorder), over the whole grid in one process.
  if (plan.output.statistics)
    plan.memory.add("statistics", PlaneStatistics::estimate_device_bytes(plan.wind.spec));
}

}  // namespace fw::host
