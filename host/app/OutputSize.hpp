// How many bytes a run writes into its output folder, output by output, predicted from the plan alone
// (docs/design.md, "Long runs"): `forestwind check` prints it and `forestwind run` refuses to start when the
// disk lacks it (host/app/OutputSpace.hpp).
//
//   fw::host::OutputSize size = fw::host::predict_output_size(plan, plan.end_time);
//   size.total();                                  // bytes over the whole run
//   for (const auto& row : size.rows) row.per_frame, row.files, row.total;
//   fw::host::print_output_size(size, std::cout);  // the table `check` shows
//
// The model knows each writer's encoding (io/WindVtk, io/TreesVtk, io/LeavesVtk, io/VdbWriter, io/ProbesCsv):
// - VTK XML (.vti, .vtp): each array is cut into 32 KiB blocks, each compressed with LZ4, behind a header
//   of 8 bytes a block. Values that change from frame to frame (velocity, pressure, speed, vorticity, the
//   trees' points and displacements, the leaves' points and normals, counting ids) are taken as
//   incompressible: LZ4's bound, n + n/255 + 16 bytes a block (measured 1.004 x raw). Arrays of long runs
//   of one value (solid, the zeros of canopy_density outside the crowns, tree and species ids, a species'
//   leaf size, a leaf's state) cost about 1/255 of their bytes. The trees' static arrays that fall between
//   (radius, node_id, the lines' connectivity) take ratios measured on the example forests (a conifer and a
//   broadleaf). At t = 0 a laminar start without solids is horizontally uniform and compresses like runs.
// - OpenVDB: Blosc (LZ4 with byte shuffle) over the active voxels (the fluid cells): a ratio measured on the
//   examples' turbulent and laminar frames.
// - Leaves: the count a frame writes varies: flying and landed leaves are always written, attached ones by
//   output.leaves.attached's stride. The prediction assumes none are shed (the count at t = 0); `most` is
//   the bound where every leaf is written, which the disk check uses.
// - probes.csv: one row per sample, numbers of {:.9g} (12.5 characters each on average, measured); with
//   samples every step the step count of planned_dt, a bound for a steady wind.
// - stats.nc: its doubles (each area's records, at most one a step; the time series' rows at planned_dt, as
//   probes.csv's) and
//   NetCDF-4's own bytes, measured on files of every size a run writes (within 2%). The canopy's 600 s wrote
//   556 kB for a prediction of 487 kB: its turbulence took 4,298 steps where planned_dt gives 3,610.
// - Checkpoints (host/app/RunCheckpoint): every state buffer whole, from the grid, the modes and the leaves
//   (within a per cent of the storm's 16.29 MB); the newest `keep` stay, and one more while the next is
//   written (the bound). Without output.checkpoint a signal still writes one: the bound holds room for it.
// - run.json, view.py (its text, exact), the scenario's copy (exact) and the .pvd collections.
// Over MPI ranks the pieces add a few kB of headers a frame, which the model leaves out.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "host/app/SimulationPlan.hpp"

namespace fw::host {

/// One output of the folder.
struct OutputSizeRow {
  std::string output;           ///< what it is, for the table ("wind .vti")
  std::string path;             ///< its place in the folder: a folder ("wind"), a file ("probes.csv"), or ""
                                ///< for what the other rows leave (view.py, .pvd files, the scenario copy)
  std::uint64_t per_frame = 0;  ///< bytes of one file of a later frame; 0 for files written once
  int files = 0;                ///< files over the run (frames it takes), 1 for files written once
  std::uint64_t total = 0;      ///< bytes over the run
  std::uint64_t most = 0;       ///< total's upper bound (leaves: every leaf shed); total elsewhere
  std::string bound;            ///< when `most` is reached, for the table ("when every leaf is shed")
};

struct OutputSize {
  int frames = 0;  ///< frames of output.interval over the run, t = 0 included
  std::vector<OutputSizeRow> rows;
  std::uint64_t total() const;
  std::uint64_t most() const;
};

/// Frames a run to `end_time` (s) captures: t = 0 and the first step reaching each multiple of
/// output.interval (the last step ends on end_time).
int frame_count(const SimulationPlan& plan, double end_time);

/// The folder a run of `plan` to `end_time` (s) writes, output by output.
OutputSize predict_output_size(const SimulationPlan& plan, double end_time);

/// The table `check` prints: output, per frame, files, total; the total and the bound.
void print_output_size(const OutputSize& size, std::ostream& out);

/// "1.2 GB", "734 MB", "12.5 kB": bytes for people (decimal units, as du -h --si).
std::string human_bytes(std::uint64_t bytes);

}  // namespace fw::host
