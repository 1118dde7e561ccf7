#include "host/runtime/KernelSources.hpp"

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "tests/support/ScopedEnv.hpp"
#include "tests/support/TempDir.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "host/runtime/ClError.hpp"
#include "tests/support/TestDevice.hpp"

namespace {

using fw::test::ScopedEnv;
using fw::test::TempDir;

// kernels/ of the source tree this test was compiled from.
std::filesystem::path source_kernel_dir() {
  // tests/host/runtime/ -> the repository root.
  return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "kernels";
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + part.size())) ++n;
  return n;
}

}  // namespace

TEST_CASE("KernelSources: every file of kernels/ is embedded") {
  const ScopedEnv no_override("FORESTWIND_KERNEL_DIR", std::nullopt);
  const auto embedded = fw::host::embedded_kernel_files();
  auto has = [&](const std::string& name) {
    return std::find(embedded.begin(), embedded.end(), name) != embedded.end();
  };
  for (const char* name :
       {"common.cl", "shared_types.h", "fluid_advect.cl", "fluid_forces.cl", "fluid_project.cl",
        "fluid_pressure.cl", "fluid_boundaries.cl", "bench_stream.cl"}) {
    INFO(name);
    CHECK(has(name));
  }
  const auto dir = source_kernel_dir();
  REQUIRE(std::filesystem::is_directory(dir));
  int on_disk = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto ext = entry.path().extension();
    if (ext != ".cl" && ext != ".h") continue;
    ++on_disk;
    const std::string name = entry.path().filename().string();
    INFO(name);
    CHECK(has(name));
    // Each one is readable through kernel_source, starting at its own line 1.
    CHECK_THAT(fw::host::kernel_source(name), Catch::StartsWith(fmt::format("#line 1 \"{}\"\n", name)));
  }
  CHECK(on_disk >= 8);
  CHECK(embedded.size() == std::size_t(on_disk));
}

TEST_CASE("KernelSources: #include \"...\" lines are replaced by the named file") {
  const ScopedEnv no_override("FORESTWIND_KERNEL_DIR", std::nullopt);
  const std::string text = fw::host::kernel_source("fluid_advect.cl");
  // common.cl includes shared_types.h, so both are pulled in, each once.
  CHECK(count(text, "typedef struct FwGrid") == 1);
  CHECK(count(text, "#line 1 \"common.cl\"") == 1);
  CHECK(count(text, "#line 1 \"shared_types.h\"") == 1);
  CHECK_THAT(text, Catch::StartsWith("#line 1 \"fluid_advect.cl\""));
  CHECK_THAT(text, !Catch::Contains("#include \""));
  // The host-only include in shared_types.h is left alone (it sits in an #else branch of __OPENCL_VERSION__).
  CHECK_THAT(text, Catch::Contains("#include <cstdint>"));
  // A file without includes comes back whole.
  CHECK_THAT(fw::host::kernel_source("shared_types.h"), Catch::Contains("typedef struct FwGust"));
}

TEST_CASE("KernelSources: FORESTWIND_KERNEL_DIR loads the files from that folder instead") {
  TempDir dir;
  dir.write("fluid_advect.cl",
            "// override of fluid_advect\n#include \"common.cl\"\nkernel void marker(void) {}\n");
  dir.write("common.cl", "// override of common\n");
  {
    const ScopedEnv override_dir("FORESTWIND_KERNEL_DIR", dir.path());
    const std::string text = fw::host::kernel_source("fluid_advect.cl");
    CHECK_THAT(text, Catch::Contains("// override of fluid_advect"));
    CHECK_THAT(text, Catch::Contains("// override of common"));
    CHECK_THAT(text, Catch::Contains("kernel void marker(void) {}"));
    CHECK_THAT(text, !Catch::Contains("typedef struct FwGrid"));
    // The line after the include is numbered as in the including file.
    CHECK_THAT(text, Catch::Contains("#line 3 \"fluid_advect.cl\"\nkernel void marker"));
  }
  // Restored: the embedded text again.
  const char* left = std::getenv("FORESTWIND_KERNEL_DIR");
  if (left == nullptr || *left == '\0')
    CHECK_THAT(fw::host::kernel_source("fluid_advect.cl"), Catch::Contains("typedef struct FwGrid"));
}

TEST_CASE("KernelSources: a file included twice, directly or indirectly, is expanded once") {
  TempDir dir;
  dir.write("main.cl", "#include \"a.h\"\n#include \"b.h\"\n  #include \"a.h\"\nmain body\n");
  dir.write("a.h", "a body\n");
  dir.write("b.h", "#include \"a.h\"\nb body\n");
  const ScopedEnv override_dir("FORESTWIND_KERNEL_DIR", dir.path());
  const std::string text = fw::host::kernel_source("main.cl");
  CHECK(count(text, "a body") == 1);
  CHECK(count(text, "b body") == 1);
  CHECK(count(text, "main body") == 1);
  CHECK(text.find("a body") < text.find("b body"));
  CHECK(text.find("b body") < text.find("main body"));
}

TEST_CASE("KernelSources: a missing file throws naming it") {
  SECTION("embedded") {
    const ScopedEnv no_override("FORESTWIND_KERNEL_DIR", std::nullopt);
    CHECK_THROWS_AS(fw::host::kernel_source("no_such_kernel.cl"), std::runtime_error);
    CHECK_THROWS_WITH(fw::host::kernel_source("no_such_kernel.cl"), Catch::Contains("no_such_kernel.cl"));
  }
  SECTION("from FORESTWIND_KERNEL_DIR") {
    TempDir dir;
    dir.write("includer.cl", "#include \"gone.h\"\n");
    const ScopedEnv override_dir("FORESTWIND_KERNEL_DIR", dir.path());
    CHECK_THROWS_WITH(fw::host::kernel_source("absent.cl"), Catch::Contains("absent.cl"));
    // An include that does not exist names the included file.
    CHECK_THROWS_WITH(fw::host::kernel_source("includer.cl"), Catch::Contains("gone.h"));
    // Embedded files are not a fallback when the override folder lacks them.
    CHECK_THROWS_WITH(fw::host::kernel_source("common.cl"), Catch::Contains("common.cl"));
  }
}

TEST_CASE("KernelSources: a kernel with a syntax error gives KernelBuildError naming the file with the log") {
  auto* cc = fw::test::device_or_skip();
  if (!cc) return;
  TempDir dir;
  dir.write("broken.cl",
            "kernel void broken(global float* x) {\n"
            "  x[0] = fw_undeclared_identifier + ;\n"
            "}\n");
  const ScopedEnv override_dir("FORESTWIND_KERNEL_DIR", dir.path());
  try {
    cc->build("broken.cl");
    FAIL("broken.cl built without an error");
  } catch (const fw::host::KernelBuildError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(e.file() == "broken.cl");
    CHECK_FALSE(e.log().empty());
    CHECK_THAT(what, Catch::Contains("broken.cl"));
    CHECK_THAT(what, Catch::Contains(e.log()));
    // The compiler's own words: the log points into the file through the #line directive.
    CHECK_THAT(e.log(), Catch::Contains("broken.cl") && Catch::Contains("error", Catch::CaseSensitive::No) &&
                            Catch::Contains("fw_undeclared_identifier"));
  }
}
