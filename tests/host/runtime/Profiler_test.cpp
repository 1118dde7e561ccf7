// host/runtime/Profiler: per-kernel calls, totals and means from OpenCL profiling events (`--profile`).
#include "host/runtime/Profiler.hpp"

#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "host/runtime/ComputeContext.hpp"
#include "tests/support/TestDevice.hpp"

using fw::host::KernelTiming;
using fw::host::Profiler;

namespace {

// A finished command with profiling times: filling a 16 MiB buffer, which takes well over a nanosecond.
cl::Event timed_fill(fw::host::ComputeContext& profiling, cl::Buffer& buffer) {
  cl::Event event;
  profiling.queue().enqueueFillBuffer(buffer, 1.0f, 0, 16u << 20, nullptr, &event);
  event.wait();
  return event;
}

// The event's own duration, ms, as the OpenCL runtime reports it.
double duration_ms(const cl::Event& event) {
  return double(event.getProfilingInfo<CL_PROFILING_COMMAND_END>() -
                event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
         1e-6;
}

const KernelTiming* find(const std::vector<KernelTiming>& list, const std::string& name) {
  for (const auto& t : list)
    if (t.name == name) return &t;
  return nullptr;
}

}  // namespace

TEST_CASE("Profiler: calls, totals and means add up from the events' times, each name apart", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::ComputeContext profiling(cc->device(), true);
  cl::Buffer buffer = profiling.buffer(16u << 20);
  const cl::Event a = timed_fill(profiling, buffer), b = timed_fill(profiling, buffer);
  const double da = duration_ms(a), db = duration_ms(b);
  REQUIRE(da > 0.0);
  REQUIRE(db > 0.0);

  Profiler profiler;
  CHECK(profiler.timings().empty());
  // "advect" three times event a; "project" event b twice and a once; "advect_x" once: a name that
  // begins like another is its own entry.
  for (int n = 0; n < 3; ++n) profiler.record("advect", a);
  profiler.record("project", b);
  profiler.record("project", a);
  profiler.record("project", b);
  profiler.record("advect_x", b);
  const auto list = profiler.timings();
  REQUIRE(list.size() == 3);
  const KernelTiming* advect = find(list, "advect");
  const KernelTiming* project = find(list, "project");
  const KernelTiming* advect_x = find(list, "advect_x");
  REQUIRE(advect);
  REQUIRE(project);
  REQUIRE(advect_x);
  // Sums of a few doubles: exact to a few ulps.
  CHECK(advect->calls == 3);
  CHECK(advect->total_ms == Approx(3 * da).epsilon(1e-12));
  CHECK(advect->mean_ms() == Approx(da).epsilon(1e-12));
  CHECK(project->calls == 3);
  CHECK(project->total_ms == Approx(2 * db + da).epsilon(1e-12));
  CHECK(project->mean_ms() == Approx((2 * db + da) / 3).epsilon(1e-12));
  CHECK(advect_x->calls == 1);
  CHECK(advect_x->total_ms == Approx(db).epsilon(1e-12));
  // Largest total first.
  for (std::size_t i = 1; i < list.size(); ++i) CHECK(list[i - 1].total_ms >= list[i].total_ms);

  // Collecting again adds nothing: each recorded event counts once. New records add to the totals.
  CHECK(profiler.timings().size() == 3);
  CHECK(find(profiler.timings(), "advect")->calls == 3);
  profiler.record("advect", b);
  // timings() returns a copy: `more` points into `after`, which must outlive it (ASan found a pointer into
  // a destroyed temporary here, make sanitize).
  const std::vector<KernelTiming> after = profiler.timings();
  const KernelTiming* more = find(after, "advect");
  CHECK(more->calls == 4);
  CHECK(more->total_ms == Approx(3 * da + db).epsilon(1e-12));

  profiler.reset();
  CHECK(profiler.timings().empty());
  CHECK(KernelTiming{}.mean_ms() == 0.0);  // no calls: no division by zero
}

TEST_CASE("Profiler: a long run's records, collected every 4096 events on the way, all count", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::ComputeContext profiling(cc->device(), true);
  cl::Buffer buffer = profiling.buffer(16u << 20);
  const cl::Event a = timed_fill(profiling, buffer);
  const double da = duration_ms(a);
  Profiler profiler;
  constexpr int kRecords = 10000;  // two automatic collects and a rest of 1808 pending
  for (int n = 0; n < kRecords; ++n) profiler.record("step", a);
  const auto list = profiler.timings();
  REQUIRE(list.size() == 1);
  CHECK(list[0].calls == kRecords);
  // 10^4 additions of one double: the rounding grows to ~1e-12 of the total at most.
  CHECK(list[0].total_ms == Approx(kRecords * da).epsilon(1e-10));
}

TEST_CASE("Profiler: print writes a header and one aligned row per kernel, largest total first", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::ComputeContext profiling(cc->device(), true);
  cl::Buffer buffer = profiling.buffer(16u << 20);
  const cl::Event a = timed_fill(profiling, buffer);
  Profiler profiler;
  std::ostringstream empty;
  profiler.print(empty);
  const std::string header = "kernel                            calls     total ms    mean ms\n";
  CHECK(empty.str() == header);  // no kernels: the header alone

  for (int n = 0; n < 5; ++n) profiler.record("pressure_residual", a);
  profiler.record("divergence_rhs", a);
  const std::string long_name = "a_kernel_name_longer_than_the_column";  // 36 characters, not cut
  for (int n = 0; n < 2; ++n) profiler.record(long_name, a);
  std::ostringstream out;
  profiler.print(out);
  const auto timings = profiler.timings();
  std::istringstream lines(out.str());
  std::string line;
  REQUIRE(std::getline(lines, line));
  CHECK(line + "\n" == header);
  for (const KernelTiming& t : timings) {  // the rows, in the order of timings(): largest total first
    INFO(t.name);
    REQUIRE(std::getline(lines, line));
    // Columns: the name left-aligned in 28, calls right-aligned in 10, total (3 decimals) in 12, mean (4
    // decimals) in 10, one space between: 63 characters, or more for a name past its column.
    const std::size_t past = t.name.size() > 28 ? t.name.size() - 28 : 0;  // a long name pushes the rest
    CHECK(line.size() == 63 + past);
    std::istringstream fields(line);
    std::string name;
    std::uint64_t calls = 0;
    double total = 0.0, mean = 0.0;
    fields >> name >> calls >> total >> mean;
    CHECK(name == t.name);
    CHECK(calls == t.calls);
    CHECK(total == Approx(t.total_ms).margin(0.0005));   // printed to 3 decimals: half a unit of the last
    CHECK(mean == Approx(t.mean_ms()).margin(0.00005));  // 4 decimals
    if (past == 0) CHECK(line.substr(0, 28).find_last_not_of(' ') == t.name.size() - 1);
    // The decimal points: the total's 3 places before the end of its column (28 + 1 + 10 + 1 + 12 = 52),
    // the mean's 4 before the end of the line.
    CHECK(line.find('.') == 48 + past);
    CHECK(line.rfind('.') == 58 + past);
  }
  CHECK_FALSE(std::getline(lines, line));
  CHECK(timings.front().name == "pressure_residual");
  CHECK(timings.back().name == "divergence_rhs");
}

TEST_CASE("Profiler: a profiling ComputeContext records every kernel launch under the kernel's name",
          "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  fw::host::ComputeContext profiling(cc->device(), true);
  REQUIRE(profiling.profiling());
  REQUIRE(profiling.profiler() != nullptr);
  CHECK_FALSE(fw::host::ComputeContext(cc->device(), false).profiling());
  const cl::Program program = profiling.build("bench_stream.cl");
  fw::host::Kernel triad(program, "stream_triad");
  constexpr cl_ulong kCount = 1 << 16;
  cl::Buffer a = profiling.buffer(kCount * 4), b = profiling.zero_floats(kCount),
             c = profiling.zero_floats(kCount);
  for (int n = 0; n < 7; ++n)
    triad.set_args(kCount, a, b, c, 2.0f).enqueue(profiling, cl::NDRange(profiling.flat_items(kCount)));
  profiling.finish();
  const auto list = profiling.profiler()->timings();
  REQUIRE(list.size() == 1);
  CHECK(list[0].name == "stream_triad");
  CHECK(list[0].calls == 7);
  CHECK(list[0].total_ms > 0.0);
}
