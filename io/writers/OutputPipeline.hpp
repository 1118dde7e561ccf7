// Output off the step's critical path: frames go through a bounded queue to one background thread that
// hands each to every writer, while the run loop goes on stepping (docs/design.md, "Data flow").
//
//   fw::io::OutputPipeline output(std::move(writers), /*capacity=*/2);
//   output.begin();
//   for (...) {
//     output.check();                     // rethrows a writer's error at the next step
//     if (frame_due) output.push(capture_frame(output.needs(index)));   // blocks while `capacity` wait
//   }
//   output.finish(outcome);                // every queued frame written, then each writer's finish
//
// Memory stays bounded: at most `capacity` frames wait, plus the one being written. The first error a
// writer throws stops the thread (later frames are dropped, so every file a collection lists stays
// complete) and is rethrown, as std::runtime_error("output: WRITER: message"), by the next check(), push()
// or drain(). Writers run one at a time on the one thread, in frame order, so they need no locks.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class OutputPipeline {
 public:
  static constexpr std::size_t kDefaultCapacity = 2;

  /// Starts the output thread. capacity >= 1, else std::invalid_argument("OutputPipeline: ...").
  explicit OutputPipeline(std::vector<std::unique_ptr<FrameWriter>> writers,
                          std::size_t capacity = kDefaultCapacity);
  /// Stops the thread after the frames already queued (errors are dropped here: call finish()).
  ~OutputPipeline();
  OutputPipeline(const OutputPipeline&) = delete;
  OutputPipeline& operator=(const OutputPipeline&) = delete;

  /// The union of every writer's needs.
  FrameNeeds needs() const;
  /// The union of the needs of the writers that take frame `index` (FrameWriter::takes): what that frame
  /// must carry.
  FrameNeeds needs(int index) const;
  bool empty() const { return writers_.empty(); }
  /// Each writer's begin(), on the calling thread.
  void begin();
  /// Each writer's check_resume: throws std::invalid_argument when one would refuse the folder. Call it
  /// before anything is written, so that a refusal leaves the folder as it was.
  void check_resume(const OutputResume& resume) const;
  /// Each writer's resume(resume) instead of begin(), for a run resumed from a checkpoint.
  void resume(const OutputResume& resume);
  /// Queues a frame; waits while the queue is full. Rethrows a writer's error.
  void push(OutputFrame frame);
  /// Rethrows a writer's error, if one happened; cheap.
  void check();
  /// Waits until every queued frame is written. Rethrows a writer's error.
  void drain();
  /// drain(), then each writer's finish(outcome) on the calling thread. A writer's error from drain is
  /// rethrown after the finishes ran (so run.json still records the run).
  void finish(const RunOutcome& outcome);

  /// Frames written completely by every writer.
  int frames_written() const;
  /// Time the output thread spent writing, ms (overlapped with the steps).
  double write_ms() const;

 private:
  void run();
  void rethrow_locked();

  std::vector<std::unique_ptr<FrameWriter>> writers_;
  std::size_t capacity_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<OutputFrame> queue_;
  bool writing_ = false;  // the thread holds a frame
  bool stopping_ = false;
  std::exception_ptr error_;
  bool error_reported_ = false;
  int frames_written_ = 0;
  double write_ms_ = 0.0;
  std::thread thread_;
};

}  // namespace fw::io
