// The background output thread: order, the bounded queue, errors and finish.
#include <catch2/catch.hpp>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "io/writers/OutputPipeline.hpp"

namespace {

// Records what it is given; can hold the output thread at a gate, or fail at one frame.
struct Log {
  std::mutex mutex;
  std::condition_variable opened;
  bool gate_open = true;
  std::vector<int> frames;
  int finishes = 0;
  std::string last_status;
};

class RecordingWriter : public fw::io::FrameWriter {
 public:
  RecordingWriter(Log& log, int fail_at = -1) : log_(log), fail_at_(fail_at) {}
  std::string name() const override { return "recorder"; }
  void write(const fw::io::OutputFrame& frame) override {
    std::unique_lock lock(log_.mutex);
    log_.opened.wait(lock, [&] { return log_.gate_open; });
    if (frame.index == fail_at_) throw std::runtime_error("disk full");
    log_.frames.push_back(frame.index);
  }
  void finish(const fw::io::RunOutcome& outcome) override {
    std::lock_guard lock(log_.mutex);
    ++log_.finishes;
    log_.last_status = outcome.status;
  }

 private:
  Log& log_;
  int fail_at_;
};

fw::io::OutputFrame frame(int index) {
  fw::io::OutputFrame f;
  f.index = index;
  f.time = index;
  return f;
}

std::vector<std::unique_ptr<fw::io::FrameWriter>> writers(Log& log, int fail_at = -1) {
  std::vector<std::unique_ptr<fw::io::FrameWriter>> list;
  list.push_back(std::make_unique<RecordingWriter>(log, fail_at));
  return list;
}

}  // namespace

TEST_CASE("OutputPipeline: every frame reaches the writer once, in order, before finish", "[output]") {
  Log log;
  fw::io::OutputPipeline output(writers(log), 2);
  output.begin();
  for (int k = 0; k < 20; ++k) output.push(frame(k));
  output.finish(fw::io::RunOutcome{});
  std::vector<int> expected(20);
  for (int k = 0; k < 20; ++k) expected[std::size_t(k)] = k;
  CHECK(log.frames == expected);
  CHECK(output.frames_written() == 20);
  CHECK(log.finishes == 1);
}

TEST_CASE("OutputPipeline: the queue holds at most its capacity and push waits for room", "[output]") {
  Log log;
  log.gate_open = false;  // the output thread blocks inside the first write
  fw::io::OutputPipeline output(writers(log), 2);
  output.push(frame(0));  // taken by the thread (or queued until it is)
  output.push(frame(1));
  output.push(frame(2));  // the queue is full once frame 0 is being written
  std::atomic<bool> pushed{false};
  std::thread producer([&] {
    output.push(frame(3));
    pushed = true;
  });
  // Not a timing assertion: whatever the delay, push must not return while the gate is closed.
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  CHECK_FALSE(pushed.load());
  {
    std::lock_guard lock(log.mutex);
    log.gate_open = true;
  }
  log.opened.notify_all();
  producer.join();
  CHECK(pushed.load());
  output.drain();
  CHECK(log.frames == std::vector<int>{0, 1, 2, 3});
}

TEST_CASE("OutputPipeline: a writer's error comes back once, names the writer, and stops later frames",
          "[output]") {
  Log log;
  fw::io::OutputPipeline output(writers(log, /*fail_at=*/1), 2);
  output.push(frame(0));
  output.push(frame(1));
  CHECK_THROWS_WITH(output.drain(), "output: recorder: disk full");
  output.check();         // reported once: the run loop is already stopping
  output.push(frame(2));  // dropped
  fw::io::RunOutcome failed;
  failed.status = "failed";
  output.finish(failed);
  CHECK(log.frames == std::vector<int>{0});
  CHECK(log.finishes == 1);
  CHECK(log.last_status == "failed");
  CHECK(output.frames_written() == 1);
}
