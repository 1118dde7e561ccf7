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
