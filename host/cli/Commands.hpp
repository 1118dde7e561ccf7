// The subcommands of `forestwind`, each a function from parsed options to an exit code.
// Exit codes (DESIGN.md): 0 ok, 1 runtime failure, 2 bad input or usage, 3 no usable OpenCL device.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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

int run_bench(const BenchOptions& options, const GlobalOptions& global);

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

struct RunOptions {
  std::string scenario;    // SCENARIO.yaml
  std::string output_dir;  // -o: overrides output.directory
  double end_time = 0.0;   // --end: s, > 0 overrides time.end
  bool quiet = false;
};

/// `forestwind run`: 0 completed, 130 interrupted by SIGINT (frames so far kept), exceptions otherwise.
int run_scenario(const RunOptions& options, const GlobalOptions& global);
/// `forestwind check`: validates and summarises without a device.
int run_check(const std::string& scenario_path);

/// Parses "NXxNYxNZ" (e.g. "128x128x64"). Throws std::invalid_argument naming the text.
std::array<int, 3> parse_grid(const std::string& text);

}  // namespace fw::cli
