#include <catch2/catch.hpp>

#include "host/runtime/ClError.hpp"
#include "host/runtime/ComputeContext.hpp"
#include "host/runtime/StderrCapture.hpp"
#include "tests/support/ScopedEnv.hpp"
#include "tests/support/TestDevice.hpp"

using fw::host::ComputeContext;
using fw::host::WorkMapping;

TEST_CASE("ComputeContext: reductions run on whole work-groups, one partial per group", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // A level of 130 x 13 x 5 cells: neither axis a multiple of a group.
  const ComputeContext rows(cc->device(), false, WorkMapping::rows);
  const auto r = rows.reduction_rows(130, 13, 5);
  CHECK(rows.row_chunk() >= 130);                                      // a whole row per item
  CHECK((r.global[0] == 1 && r.global[1] == 16 && r.global[2] == 5));  // y padded to two groups of 8 rows
  CHECK((r.local[0] == 1 && r.local[1] == 8 && r.local[2] == 1));
  CHECK(r.groups == 2 * 5);

  const ComputeContext cells(cc->device(), false, WorkMapping::cells);
  const auto c = cells.reduction_rows(130, 13, 5);
  CHECK(cells.row_chunk() == 1);                                         // one cell per item
  CHECK((c.global[0] == 192 && c.global[1] == 13 && c.global[2] == 5));  // x padded to three groups of 64
  CHECK((c.local[0] == 64 && c.local[1] == 1 && c.local[2] == 1));
  CHECK(c.groups == 3 * 13 * 5);
}

TEST_CASE("ComputeContext: FORESTWIND_WORK_MAPPING forces the mapping and refuses other values", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  {
    fw::test::ScopedEnv env("FORESTWIND_WORK_MAPPING", "cells");
    CHECK(ComputeContext(cc->device(), false).mapping() == WorkMapping::cells);
  }
  {
    fw::test::ScopedEnv env("FORESTWIND_WORK_MAPPING", "rows");
    CHECK(ComputeContext(cc->device(), false).mapping() == WorkMapping::rows);
  }
  {
    fw::test::ScopedEnv env("FORESTWIND_WORK_MAPPING", std::nullopt);
    CHECK(ComputeContext(cc->device(), false).mapping() ==
          (cc->is_cpu() ? WorkMapping::rows : WorkMapping::cells));
  }
  fw::test::ScopedEnv env("FORESTWIND_WORK_MAPPING", "diagonal");
  CHECK_THROWS_WITH(
      fw::host::work_mapping_from_env(),
      Catch::Contains("FORESTWIND_WORK_MAPPING: expected rows or cells (or unset), got 'diagonal'"));
}

TEST_CASE(
    "ComputeContext: a build's compiler chatter stays off stderr, and a warning fails the build under "
    "warnings as errors",
    "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // clang (PoCL's compiler) warns of a constant operand of && (-Wconstant-logical-operand, on by default).
  const std::string source = "kernel void chatty(global int* a, int b) { a[0] = b && 4; }\n";
  ComputeContext lenient(cc->device(), false);
  fw::host::StderrCapture stderr_text;
  const cl::Program program = lenient.build_source("chatty.cl", source);
  const std::string printed = stderr_text.release();
  const std::string log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(cc->device().device);
  INFO("build log: " << log);
  // PoCL prints "1 warning generated." to stderr on every such build; other compilers may not warn at all.
  if (cc->is_cpu()) REQUIRE_THAT(log, Catch::Contains("warning"));
  CHECK(printed.empty());

  ComputeContext strict(cc->device(), false);
  strict.set_warnings_as_errors(true);
  if (log.find("warning") == std::string::npos) return;
  try {
    strict.build_source("chatty.cl", source);
    FAIL("a program with a warning built under warnings as errors");
  } catch (const fw::host::KernelBuildError& e) {
    CHECK(e.file() == "chatty.cl");
    CHECK_THAT(e.what(), Catch::Contains("warnings as errors") && Catch::Contains("constant operand"));
  }
}

TEST_CASE("work_group_shape: 32 rows or items on the rows mapping, warps of 128 items on the cells mapping") {
  using fw::host::work_group_shape;
  auto items = [](const cl::NDRange& r) {
    std::size_t n = 1;
    for (cl_uint a = 0; a < r.dimensions(); ++a) n *= r[a];
    return n;
  };
  // The rows mapping: an item already walks a whole row or a block of values; 32 rows of a sweep, 32 items
  // of a flat range, and a lane kernel's 32 items along one row.
  for (cl_uint dims : {1u, 2u, 3u}) {
    const cl::NDRange rows = work_group_shape(WorkMapping::rows, dims, 8, 4096);
    CHECK(rows.dimensions() == dims);
    CHECK(items(rows) == fw::host::kRowsGroupItems);
    CHECK(rows[dims == 3 ? 1 : 0] == fw::host::kRowsGroupItems);
  }
  const cl::NDRange lanes = work_group_shape(WorkMapping::rows, 3, 8, 4096, fw::host::RowItems::lanes);
  CHECK((lanes[0] == fw::host::kRowsGroupItems && lanes[1] == 1 && lanes[2] == 1));
  // Under the cells mapping the lane kernels take the same groups as the rest.
  const cl::NDRange gpu_lanes = work_group_shape(WorkMapping::cells, 3, 32, 1024, fw::host::RowItems::lanes);
  CHECK((gpu_lanes[0] == 32 && gpu_lanes[1] == 4));
  // The cells mapping: x a warp (NVIDIA's 32) or PoCL's 8, y the rest of the 128 items, z 1.
  const cl::NDRange warp = work_group_shape(WorkMapping::cells, 3, 32, 1024);
  CHECK((warp[0] == 32 && warp[1] == 4 && warp[2] == 1));
  const cl::NDRange pocl = work_group_shape(WorkMapping::cells, 3, 8, 4096);
  CHECK((pocl[0] == 8 && pocl[1] == 16 && pocl[2] == 1));
  CHECK(work_group_shape(WorkMapping::cells, 1, 32, 1024)[0] == fw::host::kCellsGroupItems);
  const cl::NDRange plane = work_group_shape(WorkMapping::cells, 2, 64, 1024);
  CHECK((plane.dimensions() == 2 && plane[0] == 64 && plane[1] == 2));
  // A kernel of many registers that runs at most 48 items a group: halved to 32 (y first), a power of two,
  // so that it divides the full group of any other kernel.
  const cl::NDRange heavy = work_group_shape(WorkMapping::cells, 3, 32, 48);
  CHECK((heavy[0] == 32 && heavy[1] == 1));
  CHECK(work_group_shape(WorkMapping::cells, 1, 32, 48)[0] == 32);
  // A preferred multiple that is no power of two (some devices report 48 or 1) gives x = 1.
  CHECK(work_group_shape(WorkMapping::cells, 3, 48, 1024)[0] == 1);
  CHECK_THROWS_AS(work_group_shape(WorkMapping::cells, 4, 32, 1024), std::invalid_argument);
}

TEST_CASE("Kernel: a launch rounds its range up to whole groups, one group shape a kernel", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // Each item past n writes nothing; each item within writes its index: a range of 37 on groups of 32 or
  // 128 leaves every value written exactly once, and the guard band after the buffer untouched.
  const std::string source =
      "kernel void mark(int n, global int* out) { const int i = get_global_id(0); if (i < n) out[i] = i; }\n";
  for (const auto mapping : {WorkMapping::rows, WorkMapping::cells}) {
    ComputeContext context(cc->device(), false, mapping);
    context.set_guard_bands(true);
    fw::host::Kernel mark(context.build_source("mark.cl", source), "mark");
    const int n = 37;
    cl::Buffer out = context.upload(std::vector<int>(n, -1));
    mark.set_args(n, out).enqueue(context, cl::NDRange(n));
    const cl::NDRange group = mark.group_shape(context, 1);
    CHECK(group[0] ==
          (mapping == WorkMapping::rows ? fw::host::kRowsGroupItems : fw::host::kCellsGroupItems));
    std::vector<int> values(n);
    context.queue().enqueueReadBuffer(out, CL_TRUE, 0, n * sizeof(int), values.data());
    for (int i = 0; i < n; ++i) CHECK(values[i] == i);
    CHECK(context.guard_band_breaches().empty());
    // flat_items: whole groups of any kernel's one-dimensional shape.
    CHECK(context.flat_items(1000) % context.flat_group() == 0);
    CHECK(context.flat_group() % group[0] == 0);
  }
}

TEST_CASE("ComputeContext: a guard band names a buffer a kernel wrote past", "[device]") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  // An unguarded kernel: every item of the rounded range writes, 128 under the cells mapping for 100 values,
  // so the 28 past them write 112 bytes into the 256-byte band (no further: that would be a real overflow).
  const std::string source = "kernel void spill(global int* out) { out[get_global_id(0)] = 1; }\n";
  ComputeContext context(cc->device(), false, WorkMapping::cells);
  context.set_guard_bands(true);
  fw::host::Kernel spill(context.build_source("spill.cl", source), "spill");
  cl::Buffer kept = context.zero_floats(8);
  cl::Buffer out = context.buffer(100 * sizeof(int));
  spill.set_args(out).enqueue(context, cl::NDRange(100));
  const auto breaches = context.guard_band_breaches();
  REQUIRE(breaches.size() == 1);
  CHECK_THAT(breaches[0], Catch::Contains("buffer 2 of 400 bytes"));
  CHECK(context.guard_band_breaches().empty());  // checked once, then forgotten
}
