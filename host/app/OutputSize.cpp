#include "host/app/OutputSize.hpp"

#include "io/DamageCsv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "host/app/OutputWriters.hpp"
#include "host/app/Simulation.hpp"
#include "host/app/StatisticsRecorder.hpp"
#include "host/stages/BranchStages.hpp"
#include "host/stages/ForestStages.hpp"
#include "viz/ViewScript.hpp"

namespace fw::host {

namespace {

using Bytes = std::uint64_t;

// --- VTK XML (io/VtkXml: appended raw data, LZ4 blocks, UInt64 headers) ----------------------------------

constexpr Bytes kVtkBlock = 32768;    // vtkXMLWriter's block size
constexpr Bytes kVtkHeaderWord = 8;   // UInt64 header words: block count, block size, last size, one a block
constexpr Bytes kVtkHeaderWords = 3;  // before the per-block sizes
constexpr Bytes kLz4BoundDivisor = 255;  // LZ4_COMPRESSBOUND(n) = n + n / 255 + 16
constexpr Bytes kLz4BoundExtra = 16;
// An array of long runs of one value: LZ4 stores one match byte per 255 bytes of run, and a literal and a
// token or two a block (measured: 0.5% to 1% of the raw bytes on solid, ids and t = 0's uniform field).
constexpr Bytes kRunBytesPerBlock = 48;
// The XML before the appended data, measured on the examples (array names and offsets): a wind .vti, a
// trees or leaves .vtp.
constexpr Bytes kVtiXmlBytes = 1750;
constexpr Bytes kVtpXmlBytes = 3300;
// The trees' static arrays that compress in part, stored bytes per raw byte, measured on the storm's
// conifers and the calm scenario's broadleaves (radius 0.39 / 0.36, node_id 0.13 / 0.19, connectivity
// 0.54 / 0.59): their mean.
constexpr double kTreeRadiusRatio = 0.375;
constexpr double kTreeNodeIdRatio = 0.16;
constexpr double kTreeConnectivityRatio = 0.565;

Bytes blocks_of(Bytes raw) {
  return (raw + kVtkBlock - 1) / kVtkBlock;
}

Bytes array_header(Bytes raw) {
  return kVtkHeaderWord * (kVtkHeaderWords + blocks_of(raw));
}

// An array whose values change from frame to frame: LZ4 finds no matches.
Bytes incompressible(Bytes raw) {
  const Bytes blocks = blocks_of(raw);
  return array_header(raw) + raw + (raw + kLz4BoundDivisor - 1) / kLz4BoundDivisor + blocks * kLz4BoundExtra;
}

// An array of long runs of one value.
Bytes runs(Bytes raw) {
  return array_header(raw) + raw / kLz4BoundDivisor + blocks_of(raw) * kRunBytesPerBlock;
}

// An array that compresses to `ratio` of its bytes.
Bytes compressed(Bytes raw, double ratio) {
  return array_header(raw) + Bytes(std::llround(double(raw) * ratio));
}

constexpr Bytes kFloat = 4, kInt32 = 4, kVec3 = 12, kByte = 1;
constexpr Bytes kEmptyCellArrays = 6;  // a .vtp's empty connectivity/offsets pairs (verts or lines, strips,
                                       // polys) of 24 bytes each
constexpr Bytes kEmptyArrayBytes = 24;
constexpr Bytes kTimeValueBytes = 41;  // the float64 TimeValue, LZ4-framed

// --- OpenVDB (io/VdbWriter: Blosc over the active voxels) -------------------------------------------------

// Stored bytes per raw byte of the active voxels' floats: 0.87 on the storm's turbulent frames, 0.86 on the
// calm scenario's laminar ones; its uniform first frame 0.11.
constexpr double kVdbFloatRatio = 0.87;
constexpr double kVdbUniformRatio = 0.11;
// A leaf in the points grid: P, N (Vec3f), state, tree_id (int32), pscale (float), as written, stored about
// raw (positions and normals do not compress; the rest is small).
constexpr Bytes kVdbLeafBytes = 36;
constexpr Bytes kVdbFileBytes = 4096;  // file and grid metadata, transforms, the trees' top nodes

// --- probes.csv (io/ProbesCsv)
// ------------------------------------------------------------------------------

// Characters a value takes with its comma, measured on the examples' rows: {:.12g} times, {:.9g} floats
// (12.5 on average: a sign half the time, a leading "0." often), small counts.
// A checkpoint (host/app/RunCheckpoint) holds every stage's state buffers whole (host/stages/StageState):
// per leaf slot its state byte, four float4 (position, velocity, normal, flight) and its flight drag; per
// own leaf its flutter angle and rate; and per slot its tree, leaf and side as doubles. Every per-leaf
// buffer is padded by FW_LANES. Section names, the loop's progress and the state keys: about 4 kB.
constexpr Bytes kLeafSlotBytes = 1 + 4 * 16 + 4;
constexpr Bytes kOwnLeafBytes = 2 * 4;
constexpr Bytes kLeafSlotNumbers = 3 * 8;
constexpr Bytes kCheckpointRestBytes = 4096;
constexpr const char* kEveryLeafShed = "when every leaf is shed";

constexpr double kCsvTimeChars = 15.0;
constexpr double kCsvFloatChars = 12.5;
constexpr double kCsvCountChars = 6.0;
constexpr int kLeafCountColumns = 4;  // shed, flying, landed, exited

// --- the rest -------------------------------------------------------------------------------------------

constexpr Bytes kRunJsonBytes = 1200;  // run.json, measured 0.8 to 1.2 kB on the examples
// damage.csv (io/DamageCsv): a row a tree besides its species' name, measured 91.5 bytes standing and
// 116.7 failed on windthrow.yaml; every tree standing is the prediction, every one failed the bound.
constexpr Bytes kStandingRowBytes = 96, kFailedRowBytes = 120;
constexpr Bytes kPvdBytes = 130;      // a .pvd's XML around its entries
constexpr Bytes kPvdEntryBytes = 88;  // one <DataSet timestep="..." .../> line

// Frames K < frames with K % every == 0.
int frames_taken(int frames, int every) {
  return frames <= 0 ? 0 : (frames - 1) / every + 1;
}

struct WindFrames {
  Bytes later = 0;  // a frame after t = 0
  Bytes first = 0;  // the frame at t = 0
};

// A frame at t = 0 of a laminar start without solids is the inflow profile everywhere: every horizontal
// row of cells alike (the start's projection changes nothing), so that LZ4 and Blosc find runs.
bool uniform_start(const SimulationPlan& plan) {
  return plan.solid_cells == 0 && !plan.turbulence_box;
}

WindFrames wind_vti(const SimulationPlan& plan) {
  const Bytes cells = Bytes(plan.wind.spec.cell_count());
  const Bytes solid = Bytes(plan.solid_cells), fluid = cells - solid;
  // A field of changing values over the fluid cells, zeros in the solid ones.
  const auto field = [&](Bytes per_cell) {
    return incompressible(fluid * per_cell) + runs(solid * per_cell);
  };
  WindFrames out;
  out.later = out.first = kVtiXmlBytes + kTimeValueBytes;
  for (const std::string& name : plan.output.vtk_fields) {
    Bytes later = 0, first = 0;
    if (name == "velocity" || name == "vorticity") {
      later = field(kVec3);
      first = uniform_start(plan) ? runs(cells * kVec3) : later;
    } else if (name == "pressure" || name == "speed") {
      later = field(kFloat);
      first = uniform_start(plan) ? runs(cells * kFloat) : later;
    } else if (name == "solid") {
      later = first = plan.wind.solid.empty() ? 0 : runs(cells * kByte);
    } else if (name == "canopy_density" && plan.forest.instance_count() > 0) {
      const Bytes crowns = Bytes(plan.canopy_cells);
      later = first = incompressible(crowns * kFloat) + runs((cells - crowns) * kFloat);
    }
    out.later += later;
    out.first += first;
  }
  return out;
}

Bytes trees_vtp(const SimulationPlan& plan) {
  const Bytes nodes = Bytes(plan.forest.total_nodes());
  const Bytes lines = nodes - Bytes(plan.forest.instance_count());  // one per element: every node but roots
  return kVtpXmlBytes + kTimeValueBytes + kEmptyCellArrays * kEmptyArrayBytes +
         incompressible(nodes * kVec3) +                           // points
         incompressible(nodes * kVec3) +                           // displacement
         compressed(nodes * kFloat, kTreeRadiusRatio) +            // radius
         runs(nodes * kInt32) + runs(nodes * kInt32) +             // tree_id, species
         compressed(nodes * kInt32, kTreeNodeIdRatio) +            // node_id
         compressed(2 * lines * kInt32, kTreeConnectivityRatio) +  // connectivity
         incompressible(lines * kInt32);                           // offsets
}

// Leaves a frame writes at t = 0: of each tree's leaves, the attached ones whose index is a multiple of
// the stride.
Bytes leaves_at_start(const SimulationPlan& plan) {
  const int stride = plan.output.leaves_attached_stride;
  if (stride <= 0) return 0;
  Bytes written = 0;
  for (int k = 0; k < plan.forest.instance_count(); ++k) {
    const int species = plan.forest.instances()[std::size_t(k)].species;
    const Bytes leaves = Bytes(plan.coupling.leaves[std::size_t(species)].count());
    written += (leaves + Bytes(stride) - 1) / Bytes(stride);
  }
  return written;
}

Bytes leaves_vtp(Bytes leaves) {
  return kVtpXmlBytes + kTimeValueBytes + kEmptyCellArrays * kEmptyArrayBytes +
         incompressible(leaves * kVec3) * 2 +               // points, normal
         incompressible(leaves * kInt32) * 2 +              // the vertices' connectivity and offsets
         runs(leaves * kByte) + runs(leaves * kInt32) * 2;  // state, tree_id, size
}

WindFrames vdb_file(const SimulationPlan& plan, Bytes leaves) {
  const std::vector<std::string>& grids = plan.output.vdb_grids;
  const auto has = [&](const char* grid) {
    return std::find(grids.begin(), grids.end(), grid) != grids.end();
  };
  const Bytes fluid = Bytes(plan.wind.spec.cell_count()) - Bytes(plan.solid_cells);
  const Bytes raw = fluid * ((has("vel") ? kVec3 : 0) + (has("speed") ? kFloat : 0));
  const Bytes points = vdb_holds_leaves(plan) ? leaves * kVdbLeafBytes : 0;
  WindFrames out;
  out.later = kVdbFileBytes + Bytes(std::llround(double(raw) * kVdbFloatRatio)) + points;
  out.first = uniform_start(plan)
                  ? kVdbFileBytes + Bytes(std::llround(double(raw) * kVdbUniformRatio)) + points
                  : out.later;
  return out;
}

// One row of a frame output: `taken` files, the first at t = 0.
OutputSizeRow frame_row(std::string output, std::string path, WindFrames bytes, int taken) {
  OutputSizeRow row{std::move(output), std::move(path), bytes.later, taken, 0, 0, {}};
  if (taken > 0) row.total = bytes.first + Bytes(taken - 1) * bytes.later;
  row.most = row.total;
  return row;
}

// One checkpoint of the run: the sum of every rank's part, without the halos (a few per cent over ranks).
Bytes checkpoint_bytes(const SimulationPlan& plan) {
  const fluid::GridSpec& spec = plan.wind.spec;
  const fluid::WindSettings& settings = plan.wind.settings;
  const Bytes cells = spec.cell_count();
  Bytes floats = spec.u_count() + spec.v_count() + spec.w_count() + cells;  // velocity, pressure solution
  const bool tke = settings.subgrid == fluid::SubgridModel::tke;
  if (tke || settings.smagorinsky_constant > 0.0) floats += cells;  // eddy viscosity
  if (tke) floats += cells;                                         // subgrid energy
  floats += 2 * Bytes(plan.forest.total_modes());                   // q, qdot
  for (int k = 0; k < plan.forest.instance_count(); ++k)            // the element models' joints
    floats += FW_JOINT_FLOATS * Bytes(BranchStages::entries_of(plan.forest, plan.coupling.dynamics, k));
  if (plan.coupling.unresolved.enabled)
    floats += ForestStages::kTravelFloats * Bytes(plan.forest.instance_count());
  Bytes bytes = floats * kFloat + kCheckpointRestBytes;
  if (plan.leaf_count > 0) {
    const Bytes padded = Bytes(plan.leaf_count) + FW_LANES;
    bytes += padded * (kLeafSlotBytes + kOwnLeafBytes) + Bytes(plan.leaf_count) * kLeafSlotNumbers;
  }
  return bytes;
}

Bytes pvd_bytes(int entries) {
  return kPvdBytes + Bytes(entries) * kPvdEntryBytes;
}

}  // namespace

std::uint64_t OutputSize::total() const {
  return std::accumulate(rows.begin(), rows.end(), Bytes(0),
                         [](Bytes sum, const auto& r) { return sum + r.total; });
}

std::uint64_t OutputSize::most() const {
  return std::accumulate(rows.begin(), rows.end(), Bytes(0),
                         [](Bytes sum, const auto& r) { return sum + r.most; });
}

int frame_count(const SimulationPlan& plan, double end_time) {
  // As the run loop's schedule: a multiple of the interval within a hair of the end is reached.
  return 1 + int(std::floor(end_time / plan.output.interval + kScheduleTolerance));
}

namespace {

// stats.nc (io/StatsNetcdf): its doubles, plus NetCDF-4's own bytes, measured on files of 1-3 areas, 0-100
// records, 0-10,000 rows and 16-64 heights (within 2%): a file of one area and no record 27.5 kB, each
// further area 18 kB; the first record 53 kB an area (its chunks' index), and 1 kB an area for each record
// past the tenth; the first row of the time series 26 kB.
constexpr double kEmptyFileBytes = 27.5e3, kAreaBytes = 18e3, kFirstRecordBytes = 53e3,
                 kLaterRecordBytes = 1e3, kFirstRowBytes = 26e3;
constexpr double kRecordsInFirstIndex = 10.0;
constexpr double kSeriesChunkRows = 512.0;  // NetCDF-4's default chunk along an unlimited dimension

OutputSizeRow statistics_row(const SimulationPlan& plan, double end_time) {
  const io::StatisticsSettings& s = *plan.output.statistics;
  const double steps = std::ceil(end_time / planned_dt(plan));
  // A record at each multiple of the interval, but at most one a step (an interval under dt).
  const double records = std::min(std::floor(end_time / s.interval + kScheduleTolerance), steps);
  // The time series grow by chunks of kSeriesChunkRows rows, allocated whole.
  const double rows = std::ceil(std::floor(steps / s.series_every) / kSeriesChunkRows) * kSeriesChunkRows;
  const double areas = double(statistics_areas(plan).size());
  const double heights = plan.wind.spec.nz;
  const double values = areas * (records * (fluid::kProfileCount * heights + 1.0) + heights) +
                        rows * double(series_columns().size() + 1);
  const double netcdf = kEmptyFileBytes + kAreaBytes * (areas - 1.0) +
                        (records > 0.0 ? kFirstRecordBytes * areas : 0.0) +
                        kLaterRecordBytes * areas * std::max(0.0, records - kRecordsInFirstIndex) +
                        (rows > 0.0 ? kFirstRowBytes : 0.0);
  const Bytes bytes = Bytes(std::llround(values * sizeof(double) + netcdf));
  return {"stats.nc", "stats.nc", 0, 1, bytes, bytes, {}};
}

}  // namespace

OutputSize predict_output_size(const SimulationPlan& plan, double end_time) {
  const io::OutputSettings& out = plan.output;
  OutputSize size;
  size.frames = frame_count(plan, end_time);
  const bool trees = plan.forest.instance_count() > 0, leaves = plan.leaf_count > 0;
  const Bytes leaves_first = leaves_at_start(plan), leaves_all = Bytes(plan.leaf_count);
  Bytes pvd = 0;
  if (out.vtk_wind) {
    const int taken = frames_taken(size.frames, out.vtk_wind_every);
    size.rows.push_back(frame_row("wind .vti", "wind", wind_vti(plan), taken));
    pvd += pvd_bytes(taken);
  }
  if (out.vtk_trees && trees) {
    const int taken = frames_taken(size.frames, out.vtk_trees_every);
    // Trees start in equilibrium with the first wind (CoupledStep::start), so every frame moves them.
    const Bytes file = trees_vtp(plan);
    size.rows.push_back(frame_row("trees .vtp", "trees", {file, file}, taken));
    pvd += pvd_bytes(taken);
  }
  if (out.vtk_leaves && leaves) {
    const int taken = frames_taken(size.frames, out.leaves_every);
    const Bytes file = leaves_vtp(leaves_first);
    OutputSizeRow row = frame_row("leaves .vtp", "leaves", {file, file}, taken);
    row.most = Bytes(taken) * leaves_vtp(leaves_all);
    row.bound = kEveryLeafShed;
    size.rows.push_back(row);
    pvd += pvd_bytes(taken);
  }
  if (out.vdb_enabled) {
    const int taken = frames_taken(size.frames, out.vdb_every);
    OutputSizeRow row = frame_row("VDB", "vdb", vdb_file(plan, leaves_first), taken);
    const WindFrames most = vdb_file(plan, leaves_all);
    row.most = taken > 0 ? most.first + Bytes(taken - 1) * most.later : 0;
    if (leaves) row.bound = kEveryLeafShed;
    size.rows.push_back(row);
  }
  const int tips = trees ? std::min(RunOptions{}.tip_trees, plan.forest.instance_count()) : 0;
  if (!out.probes.empty() || tips > 0) {
    const double samples = plan.probe_interval > 0.0 ? std::floor(end_time / plan.probe_interval) + 1.0
                                                     : std::ceil(end_time / planned_dt(plan)) + 1.0;
    const double row = kCsvTimeChars + kCsvFloatChars * 3.0 * double(out.probes.size() + std::size_t(tips)) +
                       (leaves ? kCsvCountChars * kLeafCountColumns : 0.0);
    std::string header = "time_s";
    for (const io::Probe& probe : out.probes) header += fmt::format(",{0}_u,{0}_v,{0}_w", probe.name);
    for (int id = 0; id < tips; ++id)
      header += fmt::format(",tree{0}_tip_dx,tree{0}_tip_dy,tree{0}_tip_dz", id);
    if (leaves) header += ",leaves_shed,leaves_flying,leaves_landed,leaves_exited";
    const Bytes bytes = header.size() + 1 + Bytes(std::llround(samples * row));
    size.rows.push_back({"probes.csv", "probes.csv", 0, 1, bytes, bytes, {}});
  }
  if (out.statistics) size.rows.push_back(statistics_row(plan, end_time));
  // Checkpoints: one at each multiple of the interval and one at the end, of which the newest `keep` stay,
  // with one more while the next is written. Without output.checkpoint, one when a signal stops the run:
  // not part of the run's total, but of the bound the disk check holds free.
  const Bytes checkpoint = checkpoint_bytes(plan);
  if (out.checkpoint_interval > 0.0) {
    // As the run loop's schedule: each multiple reached, and the end unless it is one of them.
    const int multiples = int(std::floor(end_time / out.checkpoint_interval + kScheduleTolerance));
    const bool end_extra = end_time - multiples * out.checkpoint_interval > kScheduleTolerance * end_time;
    const int written = multiples + (end_extra ? 1 : 0);
    const Bytes kept = Bytes(std::min(written, out.checkpoints_kept));
    size.rows.push_back({"checkpoints", "checkpoints", checkpoint, written, kept * checkpoint,
                         (kept + 1) * checkpoint, "while the next is written"});
  } else {
    size.rows.push_back({"checkpoint on a signal", "checkpoints", checkpoint, 0, 0, checkpoint,
                         "when a signal stops the run"});
  }
  if (plan.coupling.damage.enabled && plan.forest.instance_count() > 0) {
    Bytes standing = io::damage_csv_header().size() + 1, failed = standing;
    for (const trees::TreeInstance& tree : plan.forest.instances()) {
      const Bytes name = plan.species[std::size_t(tree.species)].species.size();
      standing += kStandingRowBytes + name;
      failed += kFailedRowBytes + name;
    }
    size.rows.push_back({"damage.csv", "damage.csv", 0, 1, standing, failed, "when every tree has failed"});
  }
  size.rows.push_back({"run.json", "run.json", 0, 1, kRunJsonBytes, kRunJsonBytes, {}});
  const Bytes rest = viz::view_script(view_settings(plan)).size() + plan.scenario.text.size() + pvd;
  size.rows.push_back({"view.py, .pvd, scenario copy", "", 0, 1, rest, rest, {}});
  return size;
}

std::string human_bytes(std::uint64_t bytes) {
  constexpr double kKilo = 1e3, kMega = 1e6, kGiga = 1e9;
  const double b = double(bytes);
  if (b >= kGiga) return fmt::format("{:.2f} GB", b / kGiga);
  if (b >= kMega) return fmt::format("{:.1f} MB", b / kMega);
  if (b >= kKilo) return fmt::format("{:.1f} kB", b / kKilo);
  return fmt::format("{} B", bytes);
}

void print_output_size(const OutputSize& size, std::ostream& out) {
  out << fmt::format("output size over {} frames (predicted; docs/design.md, \"Long runs\"):\n", size.frames);
  out << fmt::format("  {:<30} {:>10} {:>7} {:>10}\n", "output", "per frame", "files", "total");
  for (const OutputSizeRow& row : size.rows) {
    out << fmt::format("  {:<30} {:>10} {:>7} {:>10}", row.output,
                       row.per_frame > 0 ? human_bytes(row.per_frame) : "-", row.files,
                       human_bytes(row.total));
    if (row.most > row.total) out << fmt::format("   (up to {} {})", human_bytes(row.most), row.bound);
    out << "\n";
  }
  out << fmt::format("  {:<30} {:>10} {:>7} {:>10}   ({} bytes", "total", "", "", human_bytes(size.total()),
                     size.total());
  if (size.most() > size.total()) out << fmt::format("; at most {} bytes", size.most());
  out << ")\n";
}

}  // namespace fw::host
