// A run's checkpoints (docs/design.md "Long runs"): the run loop writes them every
// output.checkpoint.interval, when a signal stops the run and when it reaches its end; `forestwind run
// --resume` reads one back and goes on as if the run had never stopped.
//
//   fw::host::RunCheckpoints checkpoints(output_folder / "checkpoints", world);
//   checkpoints.write(snapshot, /*keep=*/2);       // collective: every rank writes its part
//   std::filesystem::path newest = fw::host::find_checkpoint("out/storm");   // or a checkpoints/ folder,
//                                                                             // or one checkpoint's folder
//   fw::host::RunSnapshot back = fw::host::read_checkpoint(newest, world);
//
// Layout: checkpoints/step_NNNNNNNNNN/rank_RRRR.fwcheck, one io::Checkpoint file per MPI rank (one file in
// one process) holding that rank's block of the wind, its trees and its leaves, byte for byte as the device
// had them, with the loop's progress and the scenario's state keys (io/ScenarioStateKeys). The ranks write
// into step_N.partial/, and rank 0 renames it to step_N/ once every rank's file is complete: a folder
// without ".partial" is a whole checkpoint, and one a crash cut short is never read (the next checkpoint
// removes it). A run over other ranks or blocks reads every part and redistributes them
// (host/app/CheckpointRedistribution).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "host/runtime/Communicator.hpp"
#include "host/stages/BlockGrid.hpp"
#include "host/stages/StageState.hpp"
#include "io/ScenarioStateKeys.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::host {

/// How a segment in a checkpoint ended (io::RunSegment::status): the run after it resumed from that
/// checkpoint.
inline constexpr const char* kStoppedSegment = "stopped";

/// Where the run loop stands, besides the stages: what its output and its schedules need to go on.
struct RunProgress {
  int frames = 0;                ///< frames handed out so far: the next frame's index
  long probe_samples = 0;        ///< probes.csv rows written so far
  double next_frame = 0.0;       ///< s: when the next frame is due
  double next_sample = 0.0;      ///< s: when the next probe sample is due
  double next_checkpoint = 0.0;  ///< s: when the next checkpoint is due
  /// The run's segments up to this checkpoint, the current one last (ending here).
  std::vector<io::RunSegment> segments;
  /// s: set on the checkpoint a run writes at its end. It holds the state before the run's last step,
  /// which was cut short to land on the end time: an extension goes on from the last whole step and takes
  /// the step the longer run took, bit for bit; a resume to the same end takes the cut step again.
  std::optional<double> reached_end;
  /// The statistics' averaging window (StatisticsRecorder::saved); empty without statistics.
  std::vector<double> statistics;
};

/// One rank's part of a checkpoint.
struct RunSnapshot {
  double time = 0.0;                         ///< s
  long step = 0;                             ///< solver steps taken
  std::map<std::string, StageState> stages;  ///< CoupledStep::save_state
  RunProgress progress;
  std::vector<io::StateKey> state_keys;  ///< of the scenario that wrote it
  int ranks = 1;                         ///< the MPI ranks that wrote it
  std::string decomposition;             ///< their blocks (fluid::Decomposition::describe)
  /// This part's cells of the wind grid, its halo included (WindGrid::block): what its arrays cover.
  BlockArray block;
  std::vector<std::int32_t> tree_ids;  ///< the trees it stepped (Forest::id), in its order
};

/// A checkpoint read back for this rank: its own part when the run has the ranks and blocks that wrote it;
/// else every part, which the run redistributes over its own blocks (host/app/CheckpointRedistribution).
struct CheckpointParts {
  std::filesystem::path folder;
  std::vector<RunSnapshot> parts;
  bool own = true;  ///< parts holds this rank's part alone
  /// What every part shares: the time, step, progress and state keys.
  const RunSnapshot& any() const { return parts.front(); }
};

class RunCheckpoints {
 public:
  /// folder: the output folder's checkpoints/ (created by the first write).
  RunCheckpoints(std::filesystem::path folder, const Communicator& world);

  /// Writes this rank's snapshot into the checkpoint of its step, then (rank 0) makes the checkpoint whole
  /// and keeps the newest `keep`. Collective. Returns the checkpoint's folder. Throws std::runtime_error
  /// naming the path when a file cannot be written (an earlier checkpoint is untouched).
  std::filesystem::path write(const RunSnapshot& snapshot, int keep);
  /// Rank 0 removes the checkpoints after `step` (a run resumed from an earlier one replaces what they
  /// describe) and any cut short. Collective.
  void remove_after(long step);

  /// The folder of the checkpoint of `step`.
  std::filesystem::path folder_of(long step) const;
  /// The whole checkpoints in `folder`, by step.
  static std::map<long, std::filesystem::path> list(const std::filesystem::path& folder);

 private:
  std::filesystem::path folder_;
  const Communicator& world_;
};

/// The checkpoint `given` names: a checkpoint's folder, a checkpoints/ folder or a run's output folder (its
/// newest whole checkpoint). Throws std::invalid_argument naming the path when there is none.
std::filesystem::path find_checkpoint(const std::filesystem::path& given);

/// The checkpoint in `folder` for this rank of a run whose blocks `decomposition` describes
/// (fluid::Decomposition::describe): this rank's part when the checkpoint was written by the same ranks and
/// blocks, else every part. Throws io::CheckpointError (a std::invalid_argument) naming the file and the
/// reason when a part is missing, damaged or of another format version.
CheckpointParts read_checkpoint(const std::filesystem::path& folder, const Communicator& world,
                                const std::string& decomposition);

}  // namespace fw::host
