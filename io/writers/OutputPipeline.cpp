#include "io/writers/OutputPipeline.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <utility>

#include "base/WallClock.hpp"

namespace fw::io {

namespace {

using Clock = base::WallClock;
using base::ms_since;

}  // namespace

OutputPipeline::OutputPipeline(std::vector<std::unique_ptr<FrameWriter>> writers, std::size_t capacity)
    : writers_(std::move(writers)), capacity_(capacity) {
  if (capacity_ < 1) throw std::invalid_argument("OutputPipeline: the queue needs a capacity of at least 1");
  thread_ = std::thread([this] { run(); });
}

OutputPipeline::~OutputPipeline() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

FrameNeeds OutputPipeline::needs() const {
  FrameNeeds all;
  for (const auto& writer : writers_) all |= writer->needs();
  return all;
}

FrameNeeds OutputPipeline::needs(int index) const {
  FrameNeeds all;
  for (const auto& writer : writers_)
    if (writer->takes(index)) all |= writer->needs();
  return all;
}

void OutputPipeline::begin() {
  for (auto& writer : writers_) writer->begin();
}

void OutputPipeline::check_resume(const OutputResume& resume) const {
  for (const auto& writer : writers_) writer->check_resume(resume);
}

void OutputPipeline::resume(const OutputResume& resume) {
  for (auto& writer : writers_) writer->resume(resume);
}

void OutputPipeline::rethrow_locked() {
  if (error_ && !error_reported_) {
    error_reported_ = true;
    std::rethrow_exception(error_);
  }
}

void OutputPipeline::check() {
  std::lock_guard lock(mutex_);
  rethrow_locked();
}

void OutputPipeline::push(OutputFrame frame) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return error_ || queue_.size() < capacity_; });
  rethrow_locked();
  if (error_) return;  // already reported: the run is stopping, drop the frame
  queue_.push_back(std::move(frame));
  lock.unlock();
  changed_.notify_all();
}

void OutputPipeline::drain() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return error_ || (queue_.empty() && !writing_); });
  rethrow_locked();
}

void OutputPipeline::finish(const RunOutcome& outcome) {
  std::exception_ptr failure;
  try {
    drain();
  } catch (...) {
    failure = std::current_exception();
  }
  for (auto& writer : writers_) writer->finish(outcome);
  if (failure) std::rethrow_exception(failure);
}

int OutputPipeline::frames_written() const {
  std::lock_guard lock(mutex_);
  return frames_written_;
}

double OutputPipeline::write_ms() const {
  std::lock_guard lock(mutex_);
  return write_ms_;
}

void OutputPipeline::run() {
  for (;;) {
    OutputFrame frame;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty() || error_) return;  // stopping with nothing left, or after a failure
      frame = std::move(queue_.front());
      queue_.pop_front();
      writing_ = true;
    }
    changed_.notify_all();  // room in the queue

    const auto start = Clock::now();
    std::exception_ptr failure;
    for (auto& writer : writers_) {
      // A last batch of probe samples is not a frame: its index says nothing.
      if (frame.probe_samples_only ? !writer->needs().probe_samples : !writer->takes(frame.index)) continue;
      try {
        writer->write(frame);
      } catch (const std::exception& e) {
        failure = std::make_exception_ptr(
            std::runtime_error(fmt::format("output: {}: {}", writer->name(), e.what())));
        break;
      }
    }
    {
      std::lock_guard lock(mutex_);
      write_ms_ += ms_since(start);
      writing_ = false;
      if (failure) {
        error_ = failure;
        queue_.clear();  // later frames would be listed after a gap; the run stops instead
      } else if (!frame.probe_samples_only) {
        ++frames_written_;
      }
    }
    changed_.notify_all();
    if (failure) return;
  }
}

}  // namespace fw::io
