#include "host/runtime/Profiler.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace fw::host {

void Profiler::record(const std::string& kernel_name, const cl::Event& event) {
  pending_.emplace_back(kernel_name, event);
  if (pending_.size() > 4096) collect();  // bounds memory on long runs
}

void Profiler::collect() {
  for (auto& [name, event] : pending_) {
    event.wait();
    const auto start = event.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const auto end = event.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    auto& t = totals_[name];
    t.name = name;
    t.calls += 1;
    t.total_ms += static_cast<double>(end - start) * 1e-6;
  }
  pending_.clear();
}

std::vector<KernelTiming> Profiler::timings() {
  collect();
  std::vector<KernelTiming> list;
  for (const auto& [name, t] : totals_) list.push_back(t);
  std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.total_ms > b.total_ms; });
  return list;
}

void Profiler::print(std::ostream& out) {
  const auto list = timings();
  out << fmt::format("{:<28} {:>10} {:>12} {:>10}\n", "kernel", "calls", "total ms", "mean ms");
  for (const auto& t : list)
    out << fmt::format("{:<28} {:>10} {:>12.3f} {:>10.4f}\n", t.name, t.calls, t.total_ms, t.mean_ms());
}

void Profiler::reset() {
  pending_.clear();
  totals_.clear();
}

}  // namespace fw::host
