// forestwind: a forest in a resolved wind field. The command line (DESIGN.md "Command line").
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <iostream>
#include <stdexcept>

#include "host/ClError.hpp"
#include "host/cli/Commands.hpp"

int main(int argc, char** argv) {
  using namespace fw;
  CLI::App app{"forestwind: a forest in a resolved wind field (OpenCL)"};
  app.require_subcommand(1);
  app.fallthrough();  // --device and --profile may follow the subcommand
  cli::GlobalOptions global;
  app.add_option(
      "--device", global.device_filter,
      "OpenCL device: substring of the platform or device name (default: FORESTWIND_DEVICE, else the "
      "first GPU, else the first CPU)");
  app.add_flag("--profile", global.profile, "print the time spent per kernel (calls, total ms, mean ms)");

  bool devices_json = false;
  auto* devices = app.add_subcommand("devices", "list OpenCL platforms and devices");
  devices->add_flag("--json", devices_json, "one JSON object on stdout");

  cli::BenchOptions bench;
  std::vector<std::string> grids;
  auto* bench_cmd = app.add_subcommand("bench", "benchmarks: wind (the wind-tunnel case)");
  bench_cmd->add_option("what", bench.what, "which benchmark")->required()->check(CLI::IsMember({"wind"}));
  bench_cmd->add_option("--grid", grids,
                        "grid size NXxNYxNZ (repeatable; default 128x128x64, 64x64x32, 256x256x16)");
  bench_cmd->add_option("--steps", bench.steps, "timed steps per solver")->check(CLI::PositiveNumber);
  bench_cmd->add_flag("--json", bench.json, "one JSON object on stdout");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (devices->parsed()) return cli::run_devices(devices_json);
    if (bench_cmd->parsed()) {
      for (const auto& g : grids) bench.grids.push_back(cli::parse_grid(g));
      return cli::run_bench(bench, global);
    }
  } catch (const host::NoDeviceError& e) {
    std::cerr << "forestwind: " << e.what() << "\n";
    return 3;
  } catch (const std::invalid_argument& e) {
    std::cerr << "forestwind: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "forestwind: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
