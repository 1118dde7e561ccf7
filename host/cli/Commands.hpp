// The subcommands of `forestwind`, each a function from parsed options to an exit code.
// Exit codes (docs/design.md): 0 ok, 1 runtime failure, 2 bad input or usage, 3 no usable OpenCL device.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host/app/Simulation.hpp"
#include "host/runtime/Communicator.hpp"
#include "trees/Material.hpp"
#include "trees/ModalBasis.hpp"

namespace fw::cli {

struct GlobalOptions {
  std::string device_filter;  // --device; FORESTWIND_DEVICE when empty
  bool profile = false;       // --profile: per-kernel times from OpenCL events
};

int run_devices(bool json);

struct BenchOptions {
  std::string what;                       // "wind"
  std::vector<std::array<int, 3>> grids;  // --grid (empty: the benchmark's defaults)
  int steps = 0;                          // --steps (0: default)
  int trees = 0;                          // --trees (0: default), bench coupled
  bool json = false;
};

/// `forestwind bench`: in one process, or under mpirun the wind and coupled cases over the ranks (rank 0
/// prints).
int run_bench(const BenchOptions& options, const GlobalOptions& global, const host::Communicator& world);

struct TreeGenerateOptions {
  std::string preset;   // broadleaf | conifer | palm | weeping
  double height = 0.0;  // m; 0: the preset's default
  std::uint64_t seed = 1;
  double max_element_length = 0.0;  // m; 0: the preset's default
  std::string output;               // FILE.tree
};

int run_tree_generate(const TreeGenerateOptions& options);

struct TreeModesOptions {
  std::string file;  // FILE.tree, or a TreeQSM cylinder table
  // The defaults of a species (trees/Material.hpp, trees/ModalBasis.hpp), so that the command and a
  // scenario agree.
  int modes = trees::ModalSettings{}.mode_count;
  double youngs_modulus = trees::kDefaultWood.youngs_modulus;  // Pa
  double shear_modulus = trees::kDefaultWood.shear_modulus;    // Pa
  double density = trees::kDefaultWood.density;                // kg/m^3
  double damping_ratio = trees::Damping{}.ratios.front();
  bool json = false;
  std::string output_dir;  // -o: skeleton.vtp and modes.vtp
};

int run_tree_modes(const TreeModesOptions& options);

struct RunCommandOptions {
  std::string scenario;    // SCENARIO.yaml
  std::string output_dir;  // -o: overrides output.directory
  std::string resume;      // --resume DIR|CHECKPOINT: go on from a checkpoint
  bool quiet = false;
  host::RunOptions run;  // --end: run.end_time, s, > 0 overrides time.end
  bool force = false;    // --force: start even when the output may not fit its disk
  /// The free space the disk check assumes instead of measuring it: FORESTWIND_FAKE_FREE_BYTES, a test hook.
  std::optional<std::uint64_t> free_bytes;
};

/// `forestwind run`: 0 completed; stopped by a signal after a checkpoint, 128 + the signal's number (130
/// SIGINT, 138 SIGUSR1, 143 SIGTERM), the frames so far kept; exceptions otherwise.
int run_scenario(const RunCommandOptions& options, const GlobalOptions& global,
                 const host::Communicator& world);
/// `forestwind check`: validates and summarises without a device; with `resume` (a --resume argument) also
/// says what would continue, from which time.
int run_check(const std::string& scenario_path, const std::string& resume, const host::Communicator& world);

struct RenderOptions {
  std::string folder;                 // DIR: a run's output folder
  std::optional<int> frame;           // --frame K (0-based); default: the last complete frame
  std::optional<double> time;         // --time T, s: the nearest frame
  std::string view = "top";           // --view top|side|perspective
  std::string field = "speed";        // --field NAME, or damage: damage.csv over the speed
  std::optional<double> height;       // --height Z, m: the slice's height (world z)
  std::vector<double> range;          // --range LO HI: the field's colour range
  bool arrows = false;                // --arrows
  bool all = false;                   // --all: every frame, -o is a folder
  bool mp4 = false;                   // --mp4 (with --all): also a movie, when ffmpeg is installed
  int width = 1280, height_px = 800;  // --size WxH, px
  std::string output;                 // -o FILE.png (or DIR with --all)
  bool quiet = false;
};

/// `forestwind render`: 0 written, 2 bad input (folder, frame, field, view; --field damage: no damage.csv, a
/// bad row, a view other than top), 1 a frame that does not read.
int run_render(const RenderOptions& options);

struct ExportOptions {
  std::string folder;           // DIR: a run's output folder
  std::string field = "speed";  // --field NAME: any field of the wind frames
  double height = 10.0;         // --height Z, m above the ground
  std::optional<int> frame;     // --frame K (0-based); default: the last complete frame
  std::optional<double> time;   // --time T, s: the nearest frame
  std::string output;           // -o FILE.tif
  bool quiet = false;
};

/// `forestwind export`: a wind field at a height above the ground as a GeoTIFF (viz/GroundSlice.hpp). 0
/// written, 2 bad input (folder, frame, field, height; a run without wind frames), 1 a frame that does not
/// read or a file that cannot be written.
int run_export(const ExportOptions& options);

struct PlotOptions {
  std::string folder;     // DIR: a run's output folder
  bool spectrum = false;  // --spectrum: add the probes' power spectra
  bool profiles = false;  // --profiles: stats.nc's profiles instead of the probes
  std::string region;     // --region NAME: a region's profiles (with --profiles); default the domain's
  std::string output;     // -o FILE.png
  bool quiet = false;
};

/// `forestwind plot`: 0 written, 2 bad input (no probes.csv, too few samples for spectra; with --profiles no
/// stats.nc, no record yet, no such region).
int run_plot(const PlotOptions& options);

/// Parses "WxH" (e.g. "1280x800"), px. Throws std::invalid_argument naming the text.
std::pair<int, int> parse_size(const std::string& text);

/// Parses "NXxNYxNZ" (e.g. "128x128x64"). Throws std::invalid_argument naming the text.
std::array<int, 3> parse_grid(const std::string& text);

}  // namespace fw::cli
