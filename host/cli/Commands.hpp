// The subcommands of `forestwind`, each a function from parsed options to an exit code.
// Exit codes (DESIGN.md): 0 ok, 1 runtime failure, 2 bad input or usage, 3 no usable OpenCL device.
#pragma once

#include <array>
#include <string>
#include <vector>

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
  bool json = false;
};

int run_bench(const BenchOptions& options, const GlobalOptions& global);

/// Parses "NXxNYxNZ" (e.g. "128x128x64"). Throws std::invalid_argument naming the text.
std::array<int, 3> parse_grid(const std::string& text);

}  // namespace fw::cli
