// `forestwind render`: pictures of a run's frames (docs/design.md, "Command line"; viz/FrameRender.hpp), and
// with --field damage the storm damage over the wind (viz/DamageMap.hpp).
#include <fmt/format.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/AtomicFile.hpp"
#include "host/cli/Commands.hpp"
#include "viz/DamageMap.hpp"
#include "viz/DamageTable.hpp"
#include "viz/FrameRender.hpp"
#include "viz/RunFolder.hpp"

namespace fw::cli {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

// A movie plays the run in real time (one frame per output interval) when frames are at most 0.1 s apart;
// sparser frames play at 10 per second rather than as a slide show.
constexpr double kSlowestFps = 10.0, kFastestFps = 30.0;
// --field damage: the trees of damage.csv over the wind speed.
const std::string kDamageField = "damage";

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

viz::RenderSettings settings_of(const RenderOptions& options) {
  viz::RenderSettings s;
  s.view = viz::parse_view(options.view);
  s.field = options.field == kDamageField ? "speed" : options.field;
  s.height = options.height;
  if (!options.range.empty()) {
    if (options.range.size() != 2)
      throw std::invalid_argument("render: --range: expected two numbers, LO HI");
    s.range = std::array<double, 2>{options.range[0], options.range[1]};
  }
  s.arrows = options.arrows;
  s.width = options.width;
  s.height_px = options.height_px;
  return options.field == kDamageField ? viz::damage_map_settings(s) : s;
}

// The first executable `name` on PATH, or empty.
fs::path find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string list = path;
  for (std::size_t start = 0; start <= list.size();) {
    const std::size_t end = std::min(list.find(':', start), list.size());
    const fs::path candidate = fs::path(list.substr(start, end - start)) / name;
    std::error_code ec;
    if (end > start && fs::is_regular_file(candidate, ec) &&
        (fs::status(candidate, ec).permissions() & fs::perms::owner_exec) != fs::perms::none)
      return candidate;
    start = end + 1;
  }
  return {};
}

std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// One frame's picture: with `damage` the damage map over the wind, else the frame itself.
void write_picture(const viz::RunFolder& run, const viz::FrameData& data, const viz::RenderSettings& settings,
                   const viz::DamageTable* damage, const fs::path& png) {
  if (damage)
    viz::DamageMap(data, *damage, run.scenario_name(), settings).canvas().write_png(png);
  else
    viz::FrameRender(data, run.scenario_name(), settings).canvas().write_png(png);
}

int render_one(const viz::RunFolder& run, const RenderOptions& options, const viz::RenderSettings& settings,
               const viz::DamageTable* damage) {
  const auto start = Clock::now();
  const viz::RunFolder::Frame& frame = run.select(options.frame, options.time);
  std::string note;
  // An explicit frame must read; the default (the last) falls back to the last complete one.
  const viz::FrameData data =
      options.frame || options.time ? run.load(frame) : run.load_last_complete(frame, &note);
  if (!note.empty()) std::cerr << "forestwind: " << note << "\n";
  write_picture(run, data, settings, damage, options.output);
  std::string trees;
  if (damage) {
    const std::array<int, 3> counts = damage->counts_at(data.time);
    trees = fmt::format(", {} standing, {} broken, {} overturned", counts[0], counts[1], counts[2]);
  }
  if (!options.quiet)
    std::cout << fmt::format("wrote {} ({} x {} px, frame {}, t = {:g} s{}) in {:.2f} s\n", options.output,
                             settings.width, settings.height_px, data.index, data.time, trees,
                             seconds_since(start));
  return 0;
}

int render_all(const viz::RunFolder& run, const RenderOptions& options, viz::RenderSettings settings,
               const viz::DamageTable* damage) {
  const auto start = Clock::now();
  const auto& frames = run.frames();
  // One colour scale for the whole movie: the last complete frame's (a storm's strongest), unless given.
  std::string note;
  const viz::FrameData last = run.load_last_complete(frames.back(), &note);
  if (!note.empty()) std::cerr << "forestwind: " << note << "\n";
  settings.range = viz::slice_range(last, settings);
  const fs::path folder = options.output;
  fs::create_directories(folder);
  int written = 0;
  auto write = [&](const viz::FrameData& data) {
    write_picture(run, data, settings, damage, folder / fmt::format("frame_{:06d}.png", written++));
  };
  for (const auto& frame : frames) {
    if (frame.index >= last.index) break;
    viz::FrameData data;
    try {
      data = run.load(frame);
    } catch (const viz::FrameReadError& e) {
      std::cerr << "forestwind: skipping frame " << frame.index << ": " << e.what() << "\n";
      continue;
    }
    write(data);
  }
  write(last);  // already read
  const double seconds = seconds_since(start);
  if (!options.quiet)
    std::cout << fmt::format("wrote {} pictures to {} ({:.2f} s each)\n", written, folder.string(),
                             written ? seconds / written : 0.0);
  if (!options.mp4) return 0;
  const fs::path ffmpeg = find_on_path("ffmpeg");
  if (ffmpeg.empty()) {
    std::cout << "ffmpeg is not installed: wrote the PNGs only (apt-get install ffmpeg for the MP4)\n";
    return 0;
  }
  const double interval =
      frames.size() > 1 ? (frames.back().time - frames.front().time) / (frames.size() - 1) : 1.0;
  const double fps = std::clamp(interval > 0.0 ? 1.0 / interval : kFastestFps, kSlowestFps, kFastestFps);
  const fs::path movie = folder / (run.scenario_name().empty() ? "run.mp4" : run.scenario_name() + ".mp4");
  base::AtomicFile file(movie);
  // yuv420p needs even sides; the picture's sides are rounded down to them. The temporary name has no .mp4
  // extension, so the container is named.
  const std::string command = fmt::format(
      "{} -y -loglevel error -framerate {:g} -i {} -vf 'crop=trunc(iw/2)*2:trunc(ih/2)*2' -c:v libx264 "
      "-pix_fmt yuv420p -f mp4 {}",
      shell_quote(ffmpeg.string()), fps, shell_quote((folder / "frame_%06d.png").string()),
      shell_quote(file.temporary_path().string()));
  if (std::system(command.c_str()) != 0) throw std::runtime_error("render: ffmpeg failed: " + command);
  file.commit();
  if (!options.quiet) std::cout << "wrote " << movie.string() << "\n";
  return 0;
}

}  // namespace

std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0, consumed = 0;
  char x = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%n", &w, &x, &h, &consumed) != 3 || consumed != int(text.size()) ||
      (x != 'x' && x != 'X') || w <= 0 || h <= 0)
    throw std::invalid_argument(
        fmt::format("render: --size: expected WxH with positive integers, got '{}'", text));
  return {w, h};
}

int run_render(const RenderOptions& options) {
  const viz::RenderSettings settings = settings_of(options);
  const fs::path damage_csv = fs::path(options.folder) / "damage.csv";
  const bool damage = options.field == kDamageField;
  if (damage && fs::is_directory(options.folder) && !fs::is_regular_file(damage_csv))
    throw std::invalid_argument(fmt::format(
        "render: --field damage: {} has no damage.csv (run with forest.damage.enabled)", options.folder));
  const viz::RunFolder run(options.folder);
  // The folder's damage.csv: the state at the last frame written, drawn at each frame's time.
  const std::optional<viz::DamageTable> table =
      damage ? std::optional(viz::read_damage_table(damage_csv)) : std::nullopt;
  const viz::DamageTable* trees = table ? &*table : nullptr;
  return options.all ? render_all(run, options, settings, trees) : render_one(run, options, settings, trees);
}

}  // namespace fw::cli
