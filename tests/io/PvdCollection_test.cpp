#include "io/PvdCollection.hpp"

#include "io/WindVtk.hpp"
#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkXMLImageDataReader.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace {

using fw::test::file_text;
using fw::test::has_temporary;
using fw::test::pvd_datasets;

// The (timestep, file) attributes of every <DataSet> of a .pvd, in file order; checks the envelope too.
std::vector<std::pair<double, std::string>> datasets(const fs::path& path) {
  REQUIRE(fs::is_regular_file(path));
  const std::string text = file_text(path);
  CHECK(text.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"", 0) == 0);
  CHECK(text.find("<Collection>") != std::string::npos);
  REQUIRE(text.size() >= 25);
  CHECK(text.substr(text.size() - 25) == "</Collection>\n</VTKFile>\n");
  return pvd_datasets(text);
}

using List = std::vector<std::pair<double, std::string>>;

}  // namespace

TEST_CASE("PvdCollection: every add leaves a valid file listing the frames in time order", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "wind.pvd";
  fw::io::PvdCollection pvd(path);
  CHECK_FALSE(fs::exists(path));  // nothing before the first add or write

  pvd.write();
  CHECK(datasets(path).empty());

  pvd.add(0.5, "wind/wind_000001.vti");
  CHECK(datasets(path) == List{{0.5, "wind/wind_000001.vti"}});
  pvd.add(0.0, "wind/wind_000000.vti");
  CHECK(datasets(path) == List{{0.0, "wind/wind_000000.vti"}, {0.5, "wind/wind_000001.vti"}});
  pvd.add(1.0000000000000002, "wind/wind_000002.vti");  // shortest round-trip text keeps every bit
  pvd.add(0.5, "wind/wind_000001b.vti");                // equal time: after the earlier one
  CHECK(datasets(path) == List{{0.0, "wind/wind_000000.vti"},
                               {0.5, "wind/wind_000001.vti"},
                               {0.5, "wind/wind_000001b.vti"},
                               {1.0000000000000002, "wind/wind_000002.vti"}});
  // Re-adding a file replaces its entry instead of listing it twice.
  pvd.add(0.25, "wind/wind_000001b.vti");
  CHECK(datasets(path) == List{{0.0, "wind/wind_000000.vti"},
                               {0.25, "wind/wind_000001b.vti"},
                               {0.5, "wind/wind_000001.vti"},
                               {1.0000000000000002, "wind/wind_000002.vti"}});
  CHECK(pvd.entries().size() == 4);
  CHECK_FALSE(has_temporary(dir.path()));

  // Special characters are escaped in the attribute.
  pvd.add(2.0, "a&b<\"c\">.vti");
  CHECK(file_text(path).find("file=\"a&amp;b&lt;&quot;c&quot;&gt;.vti\"") != std::string::npos);

  CHECK_THROWS_AS(pvd.add(std::nan(""), "x.vti"), std::invalid_argument);
  CHECK_THROWS_AS(pvd.add(1.0, ""), std::invalid_argument);
}

TEST_CASE("PvdCollection: the listed .vti files open relative to the .pvd with matching TimeValue",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path root(dir.path());
  fs::create_directory(root / "wind");
  fw::io::PvdCollection pvd(root / "wind.pvd");
  fw::io::WindFrame frame;
  frame.dims = {2, 2, 1};
  frame.h = 1.0;
  frame.velocity.assign(12, 1.0f);
  for (int n = 0; n < 3; ++n) {
    frame.time = 0.75 * n;
    const std::string name = "wind/wind_00000" + std::to_string(n) + ".vti";
    fw::io::write_wind_vti(root / name, frame, {"velocity"});
    pvd.add(frame.time, name);
  }
  const auto list = datasets(root / "wind.pvd");
  REQUIRE(list.size() == 3);
  for (const auto& [time, file] : list) {
    vtkNew<vtkXMLImageDataReader> reader;
    reader->SetFileName((root / file).string().c_str());
    reader->Update();
    REQUIRE(reader->GetErrorCode() == 0);
    CHECK(reader->GetOutput()->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == time);
  }
}

TEST_CASE("PvdCollection: a missing folder throws runtime_error naming the path", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "out" / "trees.pvd";
  fw::io::PvdCollection pvd(path);
  CHECK_THROWS_MATCHES(
      pvd.add(0.0, "trees/trees_000000.vtp"), std::runtime_error,
      Catch::Matchers::Message("PvdCollection: cannot write " + path.string() + ": the folder " +
                               path.parent_path().string() + " does not exist"));
  CHECK(pvd.entries().size() == 1);  // kept: a later write() (once the folder exists) lists it
  fs::create_directory(path.parent_path());
  pvd.write();
  CHECK(datasets(path) == List{{0.0, "trees/trees_000000.vtp"}});
  CHECK_FALSE(has_temporary(path.parent_path()));
}

TEST_CASE("PvdCollection: read_pvd gives back what add wrote, times bit for bit and names unescaped",
          "[output]") {
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "trees.pvd";
  fw::io::PvdCollection pvd(path);
  pvd.add(0.1, "trees/a&b<'\">.vtp");
  pvd.add(1.0 / 3.0, "trees/trees_000001.vtp");
  const auto entries = fw::io::read_pvd(path);
  REQUIRE(entries.size() == 2);
  CHECK(entries[0].time == 0.1);  // exact: the shortest round-trip text
  CHECK(entries[0].file == "trees/a&b<'\">.vtp");
  CHECK(entries[1].time == 1.0 / 3.0);
  CHECK(entries[1].file == "trees/trees_000001.vtp");

  std::ofstream(path)
      << "<VTKFile><Collection><DataSet timestep=\"soon\" file=\"x.vti\"/></Collection></VTKFile>";
  CHECK_THROWS_WITH(fw::io::read_pvd(path),
                    Catch::Contains("timestep: expected a finite number, got 'soon'"));
  CHECK_THROWS_WITH(fw::io::read_pvd(fs::path(dir.path()) / "none.pvd"), Catch::Contains("cannot open"));
}

TEST_CASE(
    "PvdCollection: a resumed run keeps the frames up to its checkpoint's time and drops the later ones",
    "[output]") {
  fw::test::TempDir dir("fw_pvd_resume");
  const fs::path path = fs::path(dir.path()) / "wind.pvd";
  {
    fw::io::PvdCollection wind(path);
    for (int k = 0; k < 5; ++k) wind.add(0.1 * k, "wind/wind_00000" + std::to_string(k) + ".vti");
  }
  fw::io::PvdCollection resumed(path);
  resumed.continue_existing(0.2);  // 0.1 * 2 as the run computed it: the same double
  CHECK(datasets(path) ==
        List{{0.0, "wind/wind_000000.vti"}, {0.1, "wind/wind_000001.vti"}, {0.2, "wind/wind_000002.vti"}});
  resumed.add(0.3, "wind/wind_000003.vti");  // written again: listed once
  CHECK(datasets(path).size() == 4);
  // No file yet (a resume into a new folder): an empty collection.
  fw::io::PvdCollection fresh(fs::path(dir.path()) / "trees.pvd");
  fresh.continue_existing(0.2);
  CHECK(datasets(fresh.path()).empty());
}

TEST_CASE("PvdCollection: read_pvd reads a DataSet with megabytes of attributes without deep recursion",
          "[output]") {
  // A std::regex over the attributes recursed once a character: 21 KB overflowed the stack under ASan
  // (run_folder_fuzz), 2 MB in a release build. 8 MB here is past any stack a regex could take it in.
  fw::test::TempDir dir("fw_out");
  const fs::path path = fs::path(dir.path()) / "wind.pvd";
  const std::string padding(std::size_t(8) << 20, 'x');
  std::ofstream(path) << "<VTKFile><Collection>\n<DataSet timestep=\"0.5\" part=\"" << padding
                      << "\" file=\"wind/wind_000000.vti\"/>\n<DataSet " << padding
                      << "/>\n</Collection></VTKFile>";
  CHECK_THROWS_WITH(fw::io::read_pvd(path),
                    Catch::Contains("DataSet 1: expected timestep and file attributes"));
  std::ofstream(path) << "<VTKFile><Collection>\n<DataSet timestep=\"0.5\" part=\"" << padding
                      << "\" file=\"wind/wind_000000.vti\"/>\n<DataSet notimestep=\"1\" timestep=\"2\" "
                         "file=\"b.vti\"/></Collection></VTKFile>";
  const auto entries = fw::io::read_pvd(path);
  REQUIRE(entries.size() == 2);
  CHECK(entries[0].time == 0.5);
  CHECK(entries[0].file == "wind/wind_000000.vti");
  CHECK(entries[1].time == 2.0);  // the attribute named timestep, not the one ending in it
}
