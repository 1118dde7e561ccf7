// forestwind: a forest in a resolved wind field. The command line (docs/design.md "Command line").
#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "base/TextNumber.hpp"
#include "host/cli/Commands.hpp"
#include "host/runtime/ClError.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/runtime/Device.hpp"

namespace {

// Prints the error, naming the rank when there are several, and returns its exit code. An error on one rank
// of several would leave the others waiting in a collective: it stops them all (MPI_Abort) with that code.
int failed(const fw::host::Communicator& world, const std::exception& error, int code) {
  if (world.size() == 1) {
    std::cerr << "forestwind: " << error.what() << "\n";
    return code;
  }
  std::cerr << "forestwind: rank " << world.rank() << " of " << world.size() << ": " << error.what() << "\n";
  world.abort(code);
}

// FORESTWIND_FAKE_FREE_BYTES: the free space `run`'s disk check assumes (a test hook). Throws
// std::invalid_argument (exit 2) for anything but a whole number of bytes.
std::optional<std::uint64_t> fake_free_bytes() {
  const char* text = std::getenv("FORESTWIND_FAKE_FREE_BYTES");
  if (text == nullptr) return std::nullopt;
  const std::optional<std::uint64_t> bytes = fw::base::parse_number<std::uint64_t>(text);
  if (!bytes)
    throw std::invalid_argument(
        fmt::format("FORESTWIND_FAKE_FREE_BYTES: \"{}\": expected a whole number of bytes", text));
  return bytes;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace fw;
  host::MpiSession mpi(argc, argv);
  const host::Communicator& world = mpi.world();
  host::share_cpu_cores(world.node_size());  // before any OpenCL call: PoCL reads it once
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
  auto* bench_cmd = app.add_subcommand(
      "bench",
      "benchmarks: wind (the wind-tunnel case), trees (modal analysis), coupled (wind + forest), models (the "
      "three tree models)");
  bench_cmd->add_option("what", bench.what, "which benchmark")
      ->required()
      ->check(CLI::IsMember({"wind", "trees", "coupled", "models"}));
  bench_cmd->add_option("--grid", grids,
                        "grid size NXxNYxNZ (repeatable; default 128x128x64, 64x64x32, 256x256x16)");
  bench_cmd->add_option("--steps", bench.steps, "timed steps per solver")->check(CLI::PositiveNumber);
  bench_cmd->add_option("--trees", bench.trees, "trees in the coupled and models benchmarks (default 1000)")
      ->check(CLI::PositiveNumber);
  bench_cmd->add_flag("--json", bench.json, "one JSON object on stdout");

  cli::RunCommandOptions run;
  auto* run_cmd = app.add_subcommand("run", "run a scenario: wind grid and forest on the OpenCL device");
  run_cmd->add_option("scenario", run.scenario, "SCENARIO.yaml")->required();
  run_cmd->add_option("-o,--output", run.output_dir,
                      "output folder (default: the scenario's output.directory)");
  run_cmd->add_option("--end", run.run.end_time, "stop at this simulated time, s (default: time.end)")
      ->check(CLI::PositiveNumber);
  run_cmd->add_flag("--quiet", run.quiet, "no progress line or summary");
  run_cmd->add_option(
      "--resume", run.resume,
      "go on from a checkpoint: DIR (a run's output folder or its checkpoints/: the newest) or "
      "one checkpoint's folder");
  run_cmd->add_flag("--force", run.force,
                    "start even when the output folder's disk lacks the predicted output plus a margin");

  std::string check_path, check_resume;
  auto* check_cmd = app.add_subcommand("check", "validate a scenario and summarise it (no device needed)");
  check_cmd->add_option("scenario", check_path, "SCENARIO.yaml")->required();
  check_cmd->add_option("--resume", check_resume, "also say what `run --resume` would continue, from when");

  auto* tree = app.add_subcommand("tree", "tree species: generate skeletons, compute vibration modes");
  tree->require_subcommand(1);
  cli::TreeGenerateOptions generate;
  auto* tree_generate = tree->add_subcommand("generate", "write a stochastic L-system tree as a .tree file");
  tree_generate->add_option("--preset", generate.preset, "broadleaf | conifer | palm | weeping")
      ->required()
      ->check(CLI::IsMember({"broadleaf", "conifer", "palm", "weeping"}));
  tree_generate->add_option("--height", generate.height, "tree height, m (default: the preset's)")
      ->check(CLI::PositiveNumber);
  tree_generate->add_option("--seed", generate.seed, "random seed (default 1)");
  tree_generate
      ->add_option("--max-element-length", generate.max_element_length,
                   "longest FEM element, m (default: the preset's, about height/40)")
      ->check(CLI::PositiveNumber);
  tree_generate->add_option("-o,--output", generate.output, "FILE.tree")->required();

  cli::TreeModesOptions modes;
  auto* tree_modes =
      tree->add_subcommand("modes", "the lowest vibration modes of a .tree file or TreeQSM table");
  tree_modes->add_option("file", modes.file, "FILE.tree, or a TreeQSM cylinder table (.txt)")->required();
  tree_modes->add_option("--modes", modes.modes, "number of modes")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  tree_modes->add_option("--youngs-modulus", modes.youngs_modulus, "E, Pa")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  tree_modes->add_option("--shear-modulus", modes.shear_modulus, "G, Pa")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  tree_modes->add_option("--density", modes.density, "rho, kg/m^3")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  tree_modes->add_option("--damping-ratio", modes.damping_ratio, "zeta of every mode")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  tree_modes->add_flag("--json", modes.json, "one JSON object on stdout");
  tree_modes->add_option("-o,--output", modes.output_dir, "folder for skeleton.vtp and modes.vtp");

  cli::RenderOptions render;
  std::string render_size;
  auto* render_cmd = app.add_subcommand(
      "render", "a picture of a run's frame: a wind slice, the trees, the leaves and the solids (PNG)");
  render_cmd->add_option("folder", render.folder, "DIR: the run's output folder")->required();
  auto* render_frame =
      render_cmd->add_option("--frame", render.frame, "frame number, 0-based (default: the last)");
  render_cmd->add_option("--time", render.time, "simulated time, s: the nearest frame")
      ->excludes(render_frame);
  render_cmd->add_option("--view", render.view, "top | side | perspective")->capture_default_str();
  render_cmd
      ->add_option("--field", render.field,
                   "wind field: speed, velocity_x, pressure, vorticity, ...; or damage: the trees of "
                   "damage.csv over the wind speed")
      ->capture_default_str();
  render_cmd->add_option("--height", render.height,
                         "height of the horizontal slice, m (default: 10 m above the floor)");
  render_cmd->add_option("--range", render.range, "colour range of the field: LO HI")->expected(2);
  render_cmd->add_flag("--arrows", render.arrows, "draw the wind in the slice's plane as arrows");
  auto* render_all =
      render_cmd->add_flag("--all", render.all, "every frame: -o names a folder of frame_NNNNNN.png");
  render_cmd->add_flag("--mp4", render.mp4, "with --all: also an MP4 when ffmpeg is installed")
      ->needs(render_all);
  render_cmd->add_option("--size", render_size, "picture size WxH, px (default 1280x800)");
  render_cmd->add_option("-o,--output", render.output, "FILE.png, or DIR with --all")->required();
  render_cmd->add_flag("--quiet", render.quiet, "no summary line");

  cli::ExportOptions export_options;
  auto* export_cmd = app.add_subcommand(
      "export", "a wind field at a height above the ground as a GeoTIFF, for QGIS and other GIS (TIF)");
  export_cmd->add_option("folder", export_options.folder, "DIR: the run's output folder")->required();
  export_cmd->add_option("--field", export_options.field, "wind field: speed, velocity_x, pressure, ...")
      ->capture_default_str();
  export_cmd->add_option("--height", export_options.height, "height above the ground, m")
      ->capture_default_str();
  auto* export_frame =
      export_cmd->add_option("--frame", export_options.frame, "frame number, 0-based (default: the last)");
  export_cmd->add_option("--time", export_options.time, "simulated time, s: the nearest frame")
      ->excludes(export_frame);
  export_cmd->add_option("-o,--output", export_options.output, "FILE.tif")->required();
  export_cmd->add_flag("--quiet", export_options.quiet, "no summary line");

  cli::PlotOptions plot;
  auto* plot_cmd = app.add_subcommand(
      "plot", "a run's probes and tracked tree tips over time, and spectra, or its profiles (PNG)");
  plot_cmd->add_option("folder", plot.folder, "DIR: the run's output folder")->required();
  plot_cmd->add_flag("--spectrum", plot.spectrum, "add the power spectrum of each probe's wind speed");
  plot_cmd->add_flag("--profiles", plot.profiles,
                     "stats.nc's profiles against height instead: mean, fluxes, variances, skewness");
  plot_cmd->add_option("--region", plot.region, "NAME: a region's profiles (with --profiles)");
  plot_cmd->add_option("-o,--output", plot.output, "FILE.png")->required();
  plot_cmd->add_flag("--quiet", plot.quiet, "no summary line");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (devices->parsed()) return cli::run_devices(devices_json);
    if (run_cmd->parsed()) {
      run.free_bytes = fake_free_bytes();
      return cli::run_scenario(run, global, world);
    }
    if (check_cmd->parsed()) return cli::run_check(check_path, check_resume, world);
    if (tree_generate->parsed()) return cli::run_tree_generate(generate);
    if (tree_modes->parsed()) return cli::run_tree_modes(modes);
    if (plot_cmd->parsed()) return cli::run_plot(plot);
    if (export_cmd->parsed()) return cli::run_export(export_options);
    if (render_cmd->parsed()) {
      if (!render_size.empty()) std::tie(render.width, render.height_px) = cli::parse_size(render_size);
      return cli::run_render(render);
    }
    if (bench_cmd->parsed()) {
      for (const auto& g : grids) bench.grids.push_back(cli::parse_grid(g));
      return cli::run_bench(bench, global, world);
    }
  } catch (const host::NoDeviceError& e) {
    return failed(world, e, 3);
  } catch (const std::invalid_argument& e) {
    return failed(world, e, 2);
  } catch (const std::exception& e) {
    return failed(world, e, 1);
  }
  return 2;
}
