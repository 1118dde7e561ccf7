// view.py (viz/ViewScript, viz/ViewScriptWriter): the ParaView script every run writes.
#include "viz/ViewScript.hpp"
#include "viz/ViewScriptWriter.hpp"

#include "tests/support/RunFolders.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/ColourMap.hpp"
#include "viz/FrameRender.hpp"
#include "viz/RunFolder.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using fw::viz::ViewScriptSettings;

namespace {

std::string read_text(const fs::path& path) {
  REQUIRE(fs::is_regular_file(path));
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

ViewScriptSettings settings(bool wind, bool trees, bool leaves) {
  ViewScriptSettings s;
  s.scenario_name = "grove";
  s.wind = wind;
  s.trees = trees;
  s.leaves = leaves;
  s.origin = {-10.0, 5.0, 100.0};
  s.size = {64.0, 32.0, 24.0};
  s.cell_size = 2.0;
  s.slice_height = fw::viz::default_slice_height(s.origin, s.size, s.cell_size);
  s.speed_range = std::array<double, 2>{0.0, 12.5};
  return s;
}

// The numbers of `NAME = [ ... ]` in the script (comments after '#' on a line skipped).
std::vector<double> python_list_of(const std::string& script, const std::string& name) {
  const std::size_t start = script.find("\n" + name + " = [");
  REQUIRE(start != std::string::npos);
  const std::size_t open = script.find('[', start), close = script.find(']', open);
  REQUIRE(close != std::string::npos);
  std::vector<double> values;
  std::string number;
  auto flush = [&] {
    if (!number.empty()) values.push_back(std::stod(number));
    number.clear();
  };
  for (std::size_t i = open + 1; i < close; ++i) {
    const char c = script[i];
    if (c == ',' || c == ' ' || c == '\n')
      flush();
    else
      number += c;
  }
  flush();
  return values;
}

// The RGBPoints of `map_name` on lo..hi, as view_script should write them.
void check_rgb_points(const std::vector<double>& points, const std::string& map_name, double lo, double hi) {
  const auto samples = fw::viz::ColourMap::named(map_name).samples(fw::viz::kViewScriptMapSamples);
  REQUIRE(points.size() == 4 * samples.size());
  for (std::size_t n = 0; n < samples.size(); ++n) {
    INFO(map_name << " sample " << n);
    // Values are written as shortest round-trip decimals (exact to 1e-12 of the range); colour channels
    // (0..1) to 9 significant digits, so within 1e-9, far below an 8-bit step of 1/255.
    CHECK(points[4 * n] == Approx(lo + samples[n].position * (hi - lo)).margin(1e-12));
    CHECK(points[4 * n + 1] == Approx(samples[n].colour.r).margin(1e-9));
    CHECK(points[4 * n + 2] == Approx(samples[n].colour.g).margin(1e-9));
    CHECK(points[4 * n + 3] == Approx(samples[n].colour.b).margin(1e-9));
  }
}

bool has_python3() {
  return fs::exists("/usr/bin/python3");
}

// python3 runs `checker` (a file) on `arguments`; true when it exits 0. `quiet` hides its messages, for the
// checks that it can fail.
bool python3_accepts(const fw::test::TempDir& dir, const std::string& checker, const std::string& arguments,
                     bool quiet = false) {
  const std::string file = dir.write("checker.py", checker);
  const std::string command =
      "/usr/bin/python3 " + file + " " + arguments + (quiet ? " >/dev/null 2>&1" : "");
  return std::system(command.c_str()) == 0;
}

}  // namespace

TEST_CASE("ViewScript: the writer writes view.py atomically into a folder and needs at most the displacement",
          "[viz]") {
  fw::test::TempDir dir("fw_view");
  const fs::path out = fs::path(dir.path()) / "runs" / "grove";  // not there yet: begin() makes it
  fw::viz::ViewScriptWriter writer(out, settings(true, true, false));
  for (const bool trees : {true, false}) {
    const fw::io::FrameNeeds needs = fw::viz::ViewScriptWriter("unused", settings(true, trees, true)).needs();
    CHECK_FALSE(needs.velocity);
    CHECK_FALSE(needs.pressure);
    CHECK(needs.displacement == trees);  // for the trees' displacement scale
    CHECK_FALSE(needs.probe_samples);
    CHECK_FALSE(needs.leaves);
  }
  CHECK(writer.path() == out / "view.py");

  writer.begin();
  const std::string script = read_text(out / "view.py");
  CHECK(script == fw::viz::view_script(settings(true, true, false)));
  // The folder is found from the script's own location, never written into it.
  CHECK(contains(script, "return os.path.dirname(os.path.abspath(__file__))"));
  CHECK(contains(script, "RUN = script_folder()"));
  CHECK_FALSE(contains(script, dir.path()));
  writer.write(fw::io::OutputFrame{});  // a frame without the displacement changes nothing
  writer.finish(fw::io::RunOutcome{});
  CHECK(read_text(out / "view.py") == script);

  // A second run into the folder replaces the file through a temporary name and a rename: none is left.
  std::ofstream(out / "view.py") << "stale";
  fw::viz::ViewScriptWriter again(out, settings(true, false, false));
  again.begin();
  CHECK(read_text(out / "view.py") == fw::viz::view_script(settings(true, false, false)));
  for (const auto& entry : fs::directory_iterator(out)) CHECK(entry.path().filename() == "view.py");

  // A file where the folder should be: the error names the writer.
  std::ofstream(fs::path(dir.path()) / "blocked") << "a file";
  fw::viz::ViewScriptWriter blocked(fs::path(dir.path()) / "blocked", settings(true, false, false));
  CHECK_THROWS_WITH(blocked.begin(), Catch::Contains("ViewScriptWriter: cannot write"));
}

namespace {

// The number after `NAME = ` in the script; NaN for None.
double python_number_of(const std::string& script, const std::string& name) {
  const std::size_t start = script.find("\n" + name + " = ");
  REQUIRE(start != std::string::npos);
  const std::size_t value = start + name.size() + 4, end = script.find('\n', value);
  const std::string text = script.substr(value, end - value);
  return text.rfind("None", 0) == 0 ? std::numeric_limits<double>::quiet_NaN() : std::stod(text);
}

}  // namespace

TEST_CASE("ViewScript: the trees are coloured on render's scale, the 99th percentile of the last frame's",
          "[viz]") {
  // Ten trunks of 21 nodes, trunk k swaying 0.1 (k + 1) m at its top, and the tops of the two last whipping
  // 7 m: the 99th percentile of the 210 nodes (nearest rank, the 208th smallest) is the third largest, 0.95 m
  // (node 19 of the last trunk), far below the 7 m that view.py's scale used to reach.
  std::vector<fw::io::TreesFrame::Tree> forest;
  for (int k = 0; k < 10; ++k)
    forest.push_back(fw::test::trunk(2.0 + 3.0 * k, 10.0, 8.0, 0.3, 21, 0.1 * (k + 1)));
  forest[8].displacement.row(20) << 7.0, 0.0, 0.0;
  forest[9].displacement.row(20) << 0.0, 7.0, 0.0;
  fw::io::OutputFrame frame;  // what the run hands the writers: 3 floats a node, in instance order
  for (const auto& tree : forest)
    for (int n = 0; n < tree.displacement.rows(); ++n)
      for (int c = 0; c < 3; ++c) frame.displacement.push_back(float(tree.displacement(n, c)));

  fw::test::TempDir dir("fw_view");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, forest, 1, 0.5);
  const fw::viz::RunFolder run(dir.path());
  const fw::viz::FrameRender picture(run.load(run.select(std::nullopt, std::nullopt)), run.scenario_name(),
                                     fw::viz::RenderSettings{});

  fw::viz::ViewScriptWriter writer(dir.path(), settings(true, true, false));
  writer.begin();
  CHECK(std::isnan(python_number_of(read_text(fs::path(dir.path()) / "view.py"), "DISPLACEMENT_TOP")));
  writer.write(frame);
  const std::string script = read_text(fs::path(dir.path()) / "view.py");
  const double top = python_number_of(script, "DISPLACEMENT_TOP");
  // The same function on the same float32 values (the frame's, and the file's that render reads back): equal.
  CHECK(top == picture.displacement_range());
  CHECK(top == Approx(0.95).epsilon(1e-6));  // float32 of 0.95 m
  ViewScriptSettings expected = settings(true, true, false);
  expected.displacement_top = top;
  CHECK(script == fw::viz::view_script(expected));
  // The script sets the range to it and holds it as the animation plays (the speed scale still grows).
  CHECK(contains(script, "    top = DISPLACEMENT_TOP\n"));
  CHECK(contains(script, "set_range(displacement_lut, 'displacement', 0.0, top, 1e-3)"));
  CHECK(contains(
      script,
      "'displacement (m)', 'Upper Right Corner',\n                                          'Never')"));
  CHECK(contains(script, "'speed (m/s)', 'Lower Right Corner', 'Grow and update every timestep')"));

  // A later frame replaces it; a run without trees writes no scale and needs no displacement.
  for (float& d : frame.displacement) d *= 2.0f;
  writer.write(frame);
  CHECK(python_number_of(read_text(fs::path(dir.path()) / "view.py"), "DISPLACEMENT_TOP") == 2 * top);
  CHECK_FALSE(contains(fw::viz::view_script(settings(true, false, false)), "\nDISPLACEMENT_TOP = "));
  ViewScriptSettings bad = settings(true, true, false);
  bad.displacement_top = -1.0;
  CHECK_THROWS_WITH(fw::viz::view_script(bad), Catch::Contains("displacement scale must be >= 0"));
  bad.displacement_top = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(fw::viz::view_script(bad), Catch::Contains("not a finite number"));
}

TEST_CASE("ViewScript: the script names exactly the collections the run writes", "[viz]") {
  for (int mask = 0; mask < 8; ++mask) {
    const bool wind = mask & 1, trees = mask & 2, leaves = mask & 4;
    const std::string script = fw::viz::view_script(settings(wind, trees, leaves));
    INFO("wind " << wind << ", trees " << trees << ", leaves " << leaves);
    CHECK(contains(script, "open_collection('wind')") == wind);
    CHECK(contains(script, "wind.pvd") == wind);
    CHECK(contains(script, "Slice(") == wind);
    CHECK(contains(script, "SPEED_RGB_POINTS") == wind);
    CHECK(contains(script, "open_collection('trees')") == trees);
    CHECK(contains(script, "trees.pvd") == trees);
    CHECK(contains(script, "Tube(") == trees);
    CHECK(contains(script, "DISPLACEMENT_RGB_POINTS") == trees);
    CHECK(contains(script, "open_collection('leaves')") == leaves);
    CHECK(contains(script, "leaves.pvd") == leaves);
    // Every script guards each collection (a partly written folder opens) and links the times.
    CHECK(contains(script, "os.path.exists(path)"));
    CHECK(contains(script, "UpdateAnimationUsingDataTimeSteps()"));
    CHECK(contains(script, "scene.AnimationTime = times[-1]"));
  }
  const std::string all = fw::viz::view_script(settings(true, true, true));
  CHECK(contains(all, "'speed (m/s)'"));
  CHECK(contains(all, "'displacement (m)'"));
  CHECK(contains(all, "tubes.VaryRadius = 'By Absolute Scalar'"));
  CHECK(contains(all, "SLICE_Z = 110\n"));  // 10 m above a floor at z = 100 m
}

TEST_CASE("ViewScript: a scenario name with quotes, backslashes and newlines is one escaped literal",
          "[viz]") {
  using fw::viz::python_string_literal;
  CHECK(python_string_literal("storm") == "'storm'");
  CHECK(python_string_literal("it's \"a\" \\ test\nline\r\t") == R"('it\'s "a" \\ test\nline\r\t')");
  CHECK(python_string_literal(std::string("nul\0bell\x07", 9)) == R"('nul\x00bell\x07')");
  CHECK(python_string_literal("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8c\xb2") ==
        R"('caf\xe9 \u20ac \U0001f332')");
  // Bytes that are not UTF-8 (a stray continuation, a cut sequence, an overlong form): one U+FFFD each.
  CHECK(python_string_literal("a\x80"
                              "b\xe2\x82") == R"('a\ufffdb\ufffd\ufffd')");
  CHECK(python_string_literal("\xc0\xaf") == R"('\ufffd\ufffd')");

  const std::string name = "o'ak\\\"grove\"\nline two '''";
  ViewScriptSettings s = settings(true, true, true);
  s.scenario_name = name;
  const std::string script = fw::viz::view_script(s);
  CHECK(contains(script, "\nSCENARIO = " + python_string_literal(name) + "\n"));
  CHECK_FALSE(contains(script, "\nline two"));  // escaped: no raw newline ends the header comment early
  for (unsigned char c : script) CHECK((c == '\n' || (c >= 0x20 && c < 0x7f)));  // ASCII, LF only

  REQUIRE(has_python3());  // installed with the build's libvtk9-dev (python3-vtk9)
  // Python reads the literal back as the name, byte for byte (in UTF-8).
  fw::test::TempDir dir("fw_view");
  const std::string script_file = dir.write("view.py", script);
  const std::string name_file = dir.write("name.txt", name + " \xe2\x82\xac");
  s.scenario_name = name + " \xe2\x82\xac";
  const std::string unicode_file = dir.write("unicode.py", fw::viz::view_script(s));
  const std::string checker = R"PY(import ast, sys
tree = ast.parse(open(sys.argv[1], encoding='ascii').read())
values = [n.value.value for n in tree.body
          if isinstance(n, ast.Assign) and getattr(n.targets[0], 'id', None) == 'SCENARIO']
sys.exit(0 if values == [open(sys.argv[2], 'rb').read().decode('utf-8')] else 1)
)PY";
  CHECK(python3_accepts(dir, checker, unicode_file + " " + name_file));
  CHECK_FALSE(python3_accepts(dir, checker, script_file + " " + name_file, true));  // the checker can fail
}

TEST_CASE("ViewScript: the RGBPoints are the ColourMap samples on the speed range and on 0..1 m", "[viz]") {
  ViewScriptSettings s = settings(true, true, false);
  check_rgb_points(python_list_of(fw::viz::view_script(s), "SPEED_RGB_POINTS"), "wind", 0.0, 12.5);
  check_rgb_points(python_list_of(fw::viz::view_script(s), "DISPLACEMENT_RGB_POINTS"), "displacement", 0.0,
                   1.0);
  s.speed_range = std::array<double, 2>{2.0, 30.0};
  check_rgb_points(python_list_of(fw::viz::view_script(s), "SPEED_RGB_POINTS"), "wind", 2.0, 30.0);
  s.speed_range.reset();  // no hint: 0..1 m/s until the data rescales it
  const std::string script = fw::viz::view_script(s);
  check_rgb_points(python_list_of(script, "SPEED_RGB_POINTS"), "wind", 0.0, 1.0);
  CHECK(contains(script, "\nSPEED_RANGE = None"));
  CHECK(contains(script, "lut.ColorSpace = 'Lab'"));
  CHECK(contains(script, "lut.RGBPoints = rgb_points"));
}

TEST_CASE("ViewScript: the slice is 10 m above the domain floor, clamped into the cell centres", "[viz]") {
  using fw::viz::default_slice_height;
  // Exact: sums and clamps of small multiples of 0.5 m.
  CHECK(default_slice_height({0, 0, 0}, {128, 64, 32}, 2.0) == 10.0);
  CHECK(default_slice_height({5, 5, -40}, {128, 64, 32}, 2.0) == -30.0);
  CHECK(default_slice_height({0, 0, 0}, {64, 64, 8}, 2.0) == 7.0);  // a low domain: the top cell's centre
  CHECK(default_slice_height({0, 0, 0}, {64, 64, 2}, 4.0) == 1.0);  // thinner than a cell: its middle
  CHECK_THROWS_AS(default_slice_height({0, 0, 0}, {64, 64, 0}, 2.0), std::invalid_argument);
  CHECK_THROWS_WITH(default_slice_height({0, 0, 0}, {64, 64, 8}, -1.0),
                    Catch::Contains("default_slice_height"));
}

TEST_CASE("ViewScript: settings that are not finite or outside the domain are refused", "[viz]") {
  ViewScriptSettings s = settings(true, true, true);
  s.slice_height = s.origin[2] + s.size[2] + 1.0;
  CHECK_THROWS_WITH(fw::viz::view_script(s), Catch::Contains("view_script: the slice height"));
  s = settings(true, true, true);
  s.size[1] = 0.0;
  CHECK_THROWS_AS(fw::viz::view_script(s), std::invalid_argument);
  s = settings(true, true, true);
  s.origin[0] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(fw::viz::view_script(s), Catch::Contains("not a finite number"));
  s = settings(true, true, true);
  s.speed_range = std::array<double, 2>{5.0, 5.0};
  CHECK_THROWS_WITH(fw::viz::view_script(s), Catch::Contains("lo < hi"));
  // The writer refuses them when it is made, before a run starts.
  CHECK_THROWS_AS(fw::viz::ViewScriptWriter("unused", s), std::invalid_argument);
}

TEST_CASE("ViewScript: every combination of collections is valid Python (python3's ast)", "[viz]") {
  REQUIRE(has_python3());  // installed with the build's libvtk9-dev (python3-vtk9)
  fw::test::TempDir dir("fw_view");
  const std::string checker = "import ast, sys\nfor f in sys.argv[1:]: ast.parse(open(f).read(), f)\n";
  std::string files;
  for (int mask = 0; mask < 8; ++mask) {
    ViewScriptSettings s = settings(mask & 1, mask & 2, mask & 4);
    if (mask == 5) s.speed_range.reset();
    if (mask == 6) s.displacement_top = 0.95;
    files += ' ';
    files += dir.write("view" + std::to_string(mask) + ".py", fw::viz::view_script(s));
  }
  CHECK(python3_accepts(dir, checker, files));
  CHECK_FALSE(
      python3_accepts(dir, checker, dir.write("broken.py", "if True\n    pass\n"), true));  // it can fail
}
