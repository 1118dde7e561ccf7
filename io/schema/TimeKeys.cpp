// The prose docs/scenario.md prints for each key of kTimeKeys (render_scenario_docs, io/ScenarioSchema.cpp):
// its meaning, and its default, allowed values and limits in words where its type does not say them. Here,
// not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/TimeKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "time.end",
     .constraint = "at most {0} steps of the step `forestwind check` plans (`time.dt`, or with `dt: auto` "
                   "the CFL step at the peak wind)",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kRunTime,
     .description =
         "The run covers t = 0 to `end`. `forestwind run --end SECONDS` overrides it for one run."},
    {.path = "time.dt",
     .bounds_why = why::kStep,
     .description =
         "Time step. With a number, the step is fixed; a run stops with exit code 1 when that "
         "step's CFL number exceeds 5 (checked before every step), or with `upwind5` when the sum of "
         "its Courant numbers `(max\\|u\\| + max\\|v\\| + max\\|w\\|) dt / h` exceeds the scheme's "
         "stability limit 1.2; `check` refuses (exit 2) an `upwind5` step past that limit at the peak "
         "wind. With `auto`, each step uses `dt = cfl * h / max\\|u\\|` (h = `domain.cell_size`, max "
         "over the velocity components), capped at 1 s and, with `upwind5`, at `1.2 h / (max\\|u\\| + "
         "max\\|v\\| + max\\|w\\|)`."},
    {.path = "time.cfl",
     .bounds_why = why::kCfl,
     .description = "CFL number for `dt: auto`. With a fixed `dt` it is still validated, but not used."},
    {.path = "time.spin_up",
     .constraint = "at most {0} steps, as `time.end`",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kRunTime,
     .description =
         "Wind spin-up before t = 0, so that the stand's shelter forms before the trees move: for `spin_up` "
         "seconds the wind grid steps (`dt` as in the run) from t = -`spin_up` to 0 with the inputs held at "
         "their t = 0 values (no event fires), trees and leaves still and nothing written; the trees then "
         "take their equilibrium with the wind it ends on. The run then starts at t = 0, step 0, "
         "with the trees at rest in equilibrium with the sheltered wind. A resumed run does not spin up "
         "again. 0: no spin-up, the trees start in equilibrium with the unsheltered inflow profile."},
};

}  // namespace

std::span<const KeyDocs> time_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
