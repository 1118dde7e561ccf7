// The prose docs/scenario.md prints for each key of kOutputKeys (render_scenario_docs,
// io/ScenarioSchema.cpp): its meaning, and its default, allowed values and limits in words where its type
// does not say them. Here, not in the header, so that no reader of the keys compiles their prose.
#include "io/schema/OutputKeys.hpp"

#include "io/schema/BoundReasons.hpp"

namespace fw::io::schema {

namespace {

constexpr KeyDocs kDocs[] = {
    {.path = "output.directory",
     .allowed = "non-empty; relative to the **current working directory**",
     .description = "Output folder, created when the run starts. `forestwind run -o DIR` overrides it."},
    {.path = "output.interval",
     .constraint = "`time.end` / `interval` at most {0}",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kIntervals,
     .description = "Simulated time between output frames."},
    {.path = "output.probe_interval",
     .default_note = "`auto`: every solver step with `wind.turbulence`, else `output.interval`",
     .constraint = "`time.end` / `probe_interval` at most {0}",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kIntervals,
     .description = "Simulated time between the rows of `probes.csv`, independent of the frames, so that a "
                    "probe's record is fine enough for spectra (its Nyquist frequency is 1 / (2 "
                    "`probe_interval`))."},
    {.path = "output.vtk", .description = "ParaView output."},
    {.path = "output.vtk.wind", .description = "Write `wind.pvd` with `wind/wind_NNNNNN.vti`."},
    {.path = "output.vtk.trees",
     .description = "Write `trees.pvd` with `trees/trees_NNNNNN.vtp` (when there are trees)."},
    {.path = "output.vtk.wind_every",
     .bounds_why = why::kEvery,
     .description =
         "Write `wind.pvd` on every N-th frame only: the frames K (0, 1, 2, ... every `output.interval`) "
         "with K mod N = 0. A file keeps its frame's number, so that the collections of different "
         "outputs line up in time. To keep the folder small (`forestwind check` predicts its size)."},
    {.path = "output.vtk.trees_every",
     .bounds_why = why::kEvery,
     .description = "As `output.vtk.wind_every`, for `trees.pvd`."},
    {.path = "output.vtk.fields",
     .description = "Arrays in the wind `.vti` files. `pressure` is the kinematic pressure p/rho (m^2/s^2). "
                    "`canopy_density` is the trees' frontal area density (1/m). A domain with solid cells "
                    "(obstacles, terrain) writes `solid` too, listed or not: `export` and `render` find the "
                    "ground by it."},
    {.path = "output.vdb", .description = "OpenVDB output (Houdini, Blender)."},
    {.path = "output.vdb.enabled", .description = "Write `vdb/wind.NNNN.vdb` per frame."},
    {.path = "output.vdb.grids",
     .description =
         "Grids in each VDB file: `vel` (Vec3s, m/s), `speed` (float, m/s), `leaves` (a points grid "
         "of the written leaves with `P`, `N`, `state`, `tree_id` and `pscale`; in runs with "
         "leaves, ignored in runs without)."},
    {.path = "output.vdb.every",
     .bounds_why = why::kEvery,
     .description = "As `output.vtk.wind_every`, for the VDB files."},
    {.path = "output.leaves", .description = "Leaves in the frames (runs whose species have `leaves`)."},
    {.path = "output.leaves.attached",
     .bounds_why = why::kLeafStride,
     .description =
         "Which attached leaves the frames hold (`leaves.pvd` and the VDB `leaves` grid): `all`, "
         "`none`, or the attached leaves whose index among their tree's leaves is a multiple of N "
         "(the same leaves in every frame, however many have been shed and however the run is "
         "split over MPI ranks), to keep the files of a big forest small. Flying and landed leaves "
         "are always written, leaves that left the domain never."},
    {.path = "output.leaves.vtk",
     .description = "Write `leaves.pvd` with `leaves/leaves_NNNNNN.vtp` (when the run has leaves)."},
    {.path = "output.leaves.every",
     .bounds_why = why::kEvery,
     .description =
         "As `output.vtk.wind_every`, for `leaves.pvd` (the VDB `leaves` grid comes with the VDB files)."},
    {.path = "output.probes",
     .description = "Points where `probes.csv` records the wind velocity every `probe_interval`."},
    {.path = "output.probes[].name",
     .allowed = "letters, digits and `_`; unique",
     .description = "Probe name, used in the column names `<name>_u`, `<name>_v`, `<name>_w`."},
    {.path = "output.probes[].position",
     .allowed = "inside the domain, faces included",
     .bounds_why = why::kEarth,
     .description = "Probe location. The velocity there is interpolated trilinearly."},
    {.path = "output.statistics",
     .description =
         "`stats.nc`: profiles against height averaged over each horizontal plane's fluid cells and "
         "over time, and time series, as NetCDF-4 with CF-1.8 attributes (docs/statistics.md)."},
    {.path = "output.statistics.interval",
     .constraint = "`time.end` / `interval` at most {0}",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kIntervals,
     .description = "Simulated time between the profiles' records: a record at each multiple of it."},
    {.path = "output.statistics.averaging",
     .default_note = "`auto`: `interval`, so that the records cover the run without a gap",
     .constraint = "at most `interval`",
     .bounds_why = why::kIntervals,
     .description = "Simulated time each record averages over: the samples taken in the `averaging` seconds "
                    "up to the record's time. 0: the one sample at the record's time."},
    {.path = "output.statistics.sample_every",
     .bounds_why = why::kEvery,
     .description = "Solver steps between the profiles' samples within an averaging window (1: every "
                    "step)."},
    {.path = "output.statistics.series_every",
     .bounds_why = why::kEvery,
     .description = "Solver steps between the time series' rows (1: every step)."},
    {.path = "output.statistics.stands",
     .description = "Also average over each stand's region (`forest.stands`), in the group "
                    "`regions/stand_N` (N from 1 in the file's order)."},
    {.path = "output.statistics.regions",
     .description = "Horizontal boxes averaged on their own, each in the group `regions/<name>` of "
                    "`stats.nc`, besides the whole domain in the root group. A box takes the cells whose "
                    "centres lie in it."},
    {.path = "output.statistics.regions[].name",
     .allowed = "letters, digits and `_`; unique, not `stand_N`",
     .description = "The region's group name."},
    {.path = "output.statistics.regions[].min",
     .allowed = "inside the domain, with at least one cell centre between `min` and `max`",
     .bounds_why = why::kEarth,
     .description = "South-west corner [x, y] of the box."},
    {.path = "output.statistics.regions[].max",
     .allowed = "east and north of `min`",
     .bounds_why = why::kEarth,
     .description = "North-east corner [x, y] of the box."},
    {.path = "output.checkpoint",
     .description = "Checkpoints of the whole state in `checkpoints/`, from which `forestwind run --resume` "
                    "continues bit for bit. Without this key a run still writes one when a signal stops it "
                    "(SIGTERM, SIGUSR1, SIGINT)."},
    {.path = "output.checkpoint.interval",
     .constraint = "`time.end` / `interval` at most {0}",
     .limits = {bounds::kMaxRunSteps},
     .bounds_why = why::kIntervals,
     .description = "Simulated time between checkpoints; the run also writes one when it reaches its end, "
                    "so that it can be extended."},
    {.path = "output.checkpoint.keep",
     .bounds_why = why::kKeep,
     .description = "How many of the newest checkpoints are kept; older ones are removed."},
};

}  // namespace

std::span<const KeyDocs> output_docs() {
  return kDocs;
}

}  // namespace fw::io::schema
