#include "host/app/RunCheckpoint.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string_view>

#include "base/TextNumber.hpp"
#include "io/Checkpoint.hpp"

namespace fw::host {

namespace {

constexpr std::string_view kStepPrefix = "step_";
constexpr std::string_view kPartial = ".partial";
constexpr std::string_view kStagePrefix = "stage.";
constexpr std::string_view kBuffer = ".buffer.";
constexpr std::string_view kNumber = ".number.";
// The numbers of a segment in "run.segments": start and end time, start and end step, wall seconds.
constexpr std::size_t kSegmentValues = 5;
// A part's block in "run.block": extent (3), halo low and high (2 each), origin (2).
constexpr std::size_t kBlockValues = 9;
// Only in the checkpoint a run writes at its end (RunProgress::reached_end).
constexpr const char* kReachedEnd = "run.reached_end";
// Only with output.statistics (RunProgress::statistics).
constexpr const char* kStatistics = "run.statistics";

std::string rank_file(int rank) {
  return fmt::format("rank_{:04d}.fwcheck", rank);
}

std::vector<std::uint8_t> text_bytes(const std::string& text) {
  return {text.begin(), text.end()};
}

std::string bytes_text(const std::vector<std::uint8_t>& bytes) {
  return {bytes.begin(), bytes.end()};
}

io::Checkpoint to_checkpoint(const RunSnapshot& snapshot) {
  io::Checkpoint c;
  c.time = snapshot.time;
  c.step = snapshot.step;
  for (const auto& [stage, state] : snapshot.stages) {
    for (const auto& [name, bytes] : state.buffers)
      c.put(std::string(kStagePrefix) + stage + std::string(kBuffer) + name, bytes);
    for (const auto& [name, numbers] : state.numbers)
      c.put(std::string(kStagePrefix) + stage + std::string(kNumber) + name, numbers);
  }
  const RunProgress& p = snapshot.progress;
  c.put("run.progress", std::vector<double>{double(p.frames), double(p.probe_samples), p.next_frame,
                                            p.next_sample, p.next_checkpoint});
  std::vector<double> segments;
  for (const io::RunSegment& s : p.segments)
    segments.insert(segments.end(),
                    {s.start_time, s.end_time, double(s.start_step), double(s.end_step), s.wall_seconds});
  c.put("run.segments", segments);
  if (p.reached_end) c.put(kReachedEnd, std::vector<double>{*p.reached_end});
  if (!p.statistics.empty()) c.put(kStatistics, p.statistics);
  c.put("run.ranks", std::vector<std::int64_t>{snapshot.ranks});
  c.put("run.decomposition", text_bytes(snapshot.decomposition));
  std::string keys;
  std::vector<std::int64_t> hashes;
  for (const io::StateKey& key : snapshot.state_keys) {
    keys += key.key + "\n";
    hashes.push_back(std::bit_cast<std::int64_t>(key.hash));
  }
  c.put("run.state_keys", text_bytes(keys));
  c.put("run.state_hashes", hashes);
  const BlockArray& b = snapshot.block;
  c.put("run.block",
        std::vector<std::int32_t>{b.extent[0], b.extent[1], b.extent[2], b.halo_low[0], b.halo_low[1],
                                  b.halo_high[0], b.halo_high[1], b.origin[0], b.origin[1]});
  c.put("run.tree_ids", snapshot.tree_ids);
  return c;
}

RunSnapshot from_checkpoint(const io::Checkpoint& c) {
  RunSnapshot snapshot;
  snapshot.time = c.time;
  snapshot.step = long(c.step);
  for (const std::string& name : c.names()) {
    if (!name.starts_with(kStagePrefix)) continue;
    const std::string_view rest = std::string_view(name).substr(kStagePrefix.size());
    const std::size_t dot = rest.find('.');
    if (dot == std::string_view::npos) throw io::CheckpointError("an unknown section \"" + name + "\"");
    StageState& state = snapshot.stages[std::string(rest.substr(0, dot))];
    const std::string_view tail = rest.substr(dot);
    if (tail.starts_with(kBuffer))
      state.buffers[std::string(tail.substr(kBuffer.size()))] = c.get<std::uint8_t>(name);
    else if (tail.starts_with(kNumber))
      state.numbers[std::string(tail.substr(kNumber.size()))] = c.get<double>(name);
    else
      throw io::CheckpointError("an unknown section \"" + name + "\"");
  }
  const std::vector<double>& p = c.get<double>("run.progress");
  if (p.size() != 5) throw io::CheckpointError("the section \"run.progress\" has the wrong size");
  snapshot.progress.frames = int(p[0]);
  snapshot.progress.probe_samples = long(p[1]);
  snapshot.progress.next_frame = p[2];
  snapshot.progress.next_sample = p[3];
  snapshot.progress.next_checkpoint = p[4];
  const std::vector<double>& segments = c.get<double>("run.segments");
  if (segments.size() % kSegmentValues != 0)
    throw io::CheckpointError("the section \"run.segments\" has the wrong size");
  for (std::size_t s = 0; s < segments.size(); s += kSegmentValues)
    snapshot.progress.segments.push_back({segments[s], segments[s + 1], long(segments[s + 2]),
                                          long(segments[s + 3]), segments[s + 4], kStoppedSegment});
  if (c.has(kReachedEnd)) {
    const std::vector<double>& end = c.get<double>(kReachedEnd);
    if (end.size() != 1)
      throw io::CheckpointError(fmt::format("the section \"{}\" has the wrong size", kReachedEnd));
    snapshot.progress.reached_end = end[0];
  }
  if (c.has(kStatistics)) snapshot.progress.statistics = c.get<double>(kStatistics);
  const std::vector<std::int64_t>& ranks = c.get<std::int64_t>("run.ranks");
  if (ranks.size() != 1) throw io::CheckpointError("the section \"run.ranks\" has the wrong size");
  snapshot.ranks = int(ranks[0]);
  snapshot.decomposition = bytes_text(c.get<std::uint8_t>("run.decomposition"));
  const std::string keys = bytes_text(c.get<std::uint8_t>("run.state_keys"));
  const std::vector<std::int64_t>& hashes = c.get<std::int64_t>("run.state_hashes");
  std::size_t from = 0;
  for (const std::int64_t hash : hashes) {
    const std::size_t end = keys.find('\n', from);
    if (end == std::string::npos)
      throw io::CheckpointError("the state keys and their hashes differ in number");
    snapshot.state_keys.push_back({keys.substr(from, end - from), 0, std::bit_cast<std::uint64_t>(hash)});
    from = end + 1;
  }
  const std::vector<std::int32_t>& b = c.get<std::int32_t>("run.block");
  if (b.size() != kBlockValues) throw io::CheckpointError("the section \"run.block\" has the wrong size");
  snapshot.block.extent = {b[0], b[1], b[2]};
  snapshot.block.halo_low = {b[3], b[4]};
  snapshot.block.halo_high = {b[5], b[6]};
  snapshot.block.origin = {b[7], b[8]};
  snapshot.tree_ids = c.get<std::int32_t>("run.tree_ids");
  return snapshot;
}

// The step of a whole checkpoint's folder name ("step_0000000120"), or -1 for anything else.
long step_of(const std::string& name) {
  if (!name.starts_with(kStepPrefix)) return -1;
  const std::string_view digits = std::string_view(name).substr(kStepPrefix.size());
  // Digits only, as folder_of writes them: no sign.
  if (digits.empty() || digits.front() < '0' || digits.front() > '9') return -1;
  return base::parse_number<long>(digits).value_or(-1);
}

bool cut_short(const std::filesystem::path& entry) {
  return entry.filename().string().starts_with(kStepPrefix) && entry.extension() == kPartial;
}

}  // namespace

RunCheckpoints::RunCheckpoints(std::filesystem::path folder, const Communicator& world)
    : folder_(std::move(folder)), world_(world) {}

std::filesystem::path RunCheckpoints::folder_of(long step) const {
  return folder_ / fmt::format("{}{:010d}", kStepPrefix, step);
}

std::map<long, std::filesystem::path> RunCheckpoints::list(const std::filesystem::path& folder) {
  std::map<long, std::filesystem::path> found;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const long step = step_of(entry.path().filename().string());
    if (step >= 0 && std::filesystem::exists(entry.path() / rank_file(0))) found[step] = entry.path();
  }
  return found;
}

std::filesystem::path RunCheckpoints::write(const RunSnapshot& snapshot, int keep) {
  const std::filesystem::path whole = folder_of(snapshot.step);
  std::filesystem::path partial = whole;
  partial += std::string(kPartial);
  if (world_.rank() == 0) {
    std::filesystem::remove_all(partial);
    std::filesystem::create_directories(partial);
  }
  world_.barrier();
  try {
    to_checkpoint(snapshot).write(partial / rank_file(world_.rank()));
  } catch (const std::exception&) {
    // A failed write (a full disk) leaves no partial folder behind in one process; over ranks the others
    // are stopped with this one, and the next checkpoint or resume removes it.
    if (world_.size() == 1) {
      std::error_code ignored;
      std::filesystem::remove_all(partial, ignored);
    }
    throw;
  }
  world_.barrier();
  if (world_.rank() == 0) {
    // Only now is the checkpoint whole: a crash before the rename leaves the previous ones as they were.
    std::filesystem::remove_all(whole);
    std::filesystem::rename(partial, whole);
    const std::map<long, std::filesystem::path> kept = list(folder_);
    int newer = 0;
    for (auto it = kept.rbegin(); it != kept.rend(); ++it)
      if (++newer > keep) std::filesystem::remove_all(it->second);
    for (const auto& entry : std::filesystem::directory_iterator(folder_))
      if (cut_short(entry.path())) std::filesystem::remove_all(entry.path());
  }
  world_.barrier();
  return whole;
}

void RunCheckpoints::remove_after(long step) {
  if (world_.rank() == 0 && std::filesystem::is_directory(folder_)) {
    for (const auto& [later, path] : list(folder_))
      if (later > step) std::filesystem::remove_all(path);
    for (const auto& entry : std::filesystem::directory_iterator(folder_))
      if (cut_short(entry.path())) std::filesystem::remove_all(entry.path());
  }
  world_.barrier();
}

std::filesystem::path find_checkpoint(const std::filesystem::path& given) {
  if (std::filesystem::exists(given / rank_file(0))) return given;
  const std::filesystem::path folder =
      std::filesystem::is_directory(given / "checkpoints") ? given / "checkpoints" : given;
  const std::map<long, std::filesystem::path> found = RunCheckpoints::list(folder);
  if (found.empty())
    throw std::invalid_argument(fmt::format(
        "{}: no checkpoint there (a run writes them with output.checkpoint, and when a signal stops it)",
        given.string()));
  return found.rbegin()->second;
}

namespace {

// One rank's part of the checkpoint in `folder`.
RunSnapshot read_part(const std::filesystem::path& folder, int rank) {
  const std::filesystem::path file = folder / rank_file(rank);
  const io::Checkpoint c = io::Checkpoint::read(file);
  try {
    return from_checkpoint(c);
  } catch (const io::CheckpointError& e) {
    throw io::CheckpointError(fmt::format("{}: {}", file.string(), e.what()));
  }
}

}  // namespace

CheckpointParts read_checkpoint(const std::filesystem::path& folder, const Communicator& world,
                                const std::string& decomposition) {
  int files = 0;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error))
    files += entry.path().extension() == ".fwcheck" ? 1 : 0;
  CheckpointParts read;
  read.folder = folder;
  RunSnapshot first = read_part(folder, 0);
  if (first.ranks != files)
    throw io::CheckpointError(
        fmt::format("{}: holds the parts of {} MPI ranks, and was written by {}: a part "
                    "is missing",
                    folder.string(), files, first.ranks));
  read.own = first.ranks == world.size() && first.decomposition == decomposition;
  if (read.own) {
    read.parts.push_back(world.rank() == 0 ? std::move(first) : read_part(folder, world.rank()));
    return read;
  }
  read.parts.push_back(std::move(first));
  for (int rank = 1; rank < files; ++rank) read.parts.push_back(read_part(folder, rank));
  return read;
}

}  // namespace fw::host
