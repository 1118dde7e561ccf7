#include "io/WindVtk.hpp"

#include "tests/support/OutputFiles.hpp"
#include "tests/support/TempDir.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkType.h>
#include <vtkXMLImageDataReader.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using fw::test::has_temporary;

// A 4x3x2 frame with distinct values in every cell and component, cells 5 and 17 solid.
fw::io::WindFrame sample_frame() {
  fw::io::WindFrame frame;
  frame.dims = {4, 3, 2};
  frame.h = 0.75;
  frame.origin = {-3.0, 10.5, 0.25};
  frame.time = 12.375;
  frame.step = 412;
  const std::size_t cells = frame.cell_count();
  frame.velocity.resize(3 * cells);
  for (std::size_t c = 0; c < 3 * cells; ++c) frame.velocity[c] = float(std::sin(0.37 * double(c)) * 9.0);
  frame.pressure.resize(cells);
  frame.canopy_density.resize(cells);
  frame.solid.assign(cells, 0);
  for (std::size_t c = 0; c < cells; ++c) {
    frame.pressure[c] = float(c) * 0.125f - 1.0f;
    frame.canopy_density[c] = float(c % 5) * 0.1f;
  }
  frame.solid[5] = 1;
  frame.solid[17] = 7;  // any nonzero byte is solid; written as 1
  return frame;
}

vtkSmartPointer<vtkImageData> read_vti(const fs::path& path) {
  REQUIRE(fs::is_regular_file(path));
  vtkNew<vtkXMLImageDataReader> reader;
  REQUIRE(reader->CanReadFile(path.string().c_str()) == 1);
  reader->SetFileName(path.string().c_str());
  reader->Update();
  REQUIRE(reader->GetErrorCode() == 0);
  vtkSmartPointer<vtkImageData> image = reader->GetOutput();
  REQUIRE(image != nullptr);
  return image;
}

template <typename T>
void check_array(vtkCellData* cells, const char* name, int type, int components,
                 const std::vector<T>& expected) {
  INFO("array " << name);
  vtkDataArray* array = cells->GetArray(name);
  REQUIRE(array != nullptr);
  CHECK(array->GetDataType() == type);
  REQUIRE(array->GetNumberOfComponents() == components);
  REQUIRE(std::size_t(array->GetNumberOfTuples()) * std::size_t(components) == expected.size());
  for (std::size_t t = 0; t < expected.size() / std::size_t(components); ++t) {
    for (int c = 0; c < components; ++c) {
      // Exact: float32 and uint8 values travel losslessly through LZ4.
      CHECK(array->GetComponent(vtkIdType(t), c) ==
            double(expected[t * std::size_t(components) + std::size_t(c)]));
    }
  }
}

}  // namespace

TEST_CASE("write_wind_vti: cell arrays, origin, spacing, extent and TimeValue read back", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();
  const fs::path path = fs::path(dir.path()) / "wind_000001.vti";
  fw::io::write_wind_vti(path, frame, fw::io::wind_field_names());
  CHECK_FALSE(has_temporary(dir.path()));

  // Binary appended raw data, LZ4-compressed, 64-bit headers (io/VtkXml).
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(text.find("header_type=\"UInt64\"") != std::string::npos);
  CHECK(text.find("compressor=\"vtkLZ4DataCompressor\"") != std::string::npos);
  CHECK(text.find("format=\"appended\"") != std::string::npos);
  CHECK(text.find("<AppendedData encoding=\"raw\">") != std::string::npos);

  const auto image = read_vti(path);
  double origin[3], spacing[3];
  int extent[6];
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  image->GetExtent(extent);
  CHECK(origin[0] == -3.0);
  CHECK(origin[1] == 10.5);
  CHECK(origin[2] == 0.25);
  CHECK(spacing[0] == 0.75);
  CHECK(spacing[1] == 0.75);
  CHECK(spacing[2] == 0.75);
  CHECK(std::vector<int>(extent, extent + 6) == std::vector<int>{0, 4, 0, 3, 0, 2});
  CHECK(image->GetNumberOfCells() == 24);
  CHECK(image->GetPointData()->GetNumberOfArrays() == 0);

  vtkCellData* cells = image->GetCellData();
  CHECK(cells->GetNumberOfArrays() == 6);
  check_array(cells, "velocity", VTK_FLOAT, 3, frame.velocity);
  check_array(cells, "pressure", VTK_FLOAT, 1, frame.pressure);
  check_array(cells, "speed", VTK_FLOAT, 1, fw::io::wind_speed(frame));
  check_array(cells, "vorticity", VTK_FLOAT, 3, fw::io::wind_vorticity(frame));
  std::vector<std::uint8_t> solid01(frame.cell_count(), 0);
  solid01[5] = solid01[17] = 1;
  check_array(cells, "solid", VTK_UNSIGNED_CHAR, 1, solid01);
  check_array(cells, "canopy_density", VTK_FLOAT, 1, frame.canopy_density);
  REQUIRE(cells->GetVectors() != nullptr);
  CHECK(std::string(cells->GetVectors()->GetName()) == "velocity");

  // VTK's cell (i,j,k) is the frame's cell (i,j,k): compare one by its centre.
  double pcoords[3], centre[3] = {-3.0 + 0.75 * 2.5, 10.5 + 0.75 * 1.5, 0.25 + 0.75 * 1.5};
  int ijk[3];
  REQUIRE(image->ComputeStructuredCoordinates(centre, ijk, pcoords) == 1);
  CHECK(image->ComputeCellId(ijk) == vtkIdType(frame.cell_index(2, 1, 1)));

  vtkDataArray* time = image->GetFieldData()->GetArray("TimeValue");
  REQUIRE(time != nullptr);
  CHECK(time->GetNumberOfTuples() == 1);
  CHECK(time->GetTuple1(0) == 12.375);
}

TEST_CASE("write_wind_vti: writes only the requested fields and skips empty ones", "[output]") {
  fw::test::TempDir dir("fw_out");
  fw::io::WindFrame frame = sample_frame();
  frame.pressure.clear();
  frame.solid.clear();
  const fs::path path = fs::path(dir.path()) / "wind.vti";
  fw::io::write_wind_vti(path, frame, {"speed", "pressure", "solid", "speed"});
  auto image = read_vti(path);
  CHECK(image->GetCellData()->GetNumberOfArrays() == 1);
  check_array(image->GetCellData(), "speed", VTK_FLOAT, 1, fw::io::wind_speed(frame));

  fw::io::write_wind_vti(path, frame, {});  // replaces the file: geometry and time only
  image = read_vti(path);
  CHECK(image->GetCellData()->GetNumberOfArrays() == 0);
  CHECK(image->GetFieldData()->GetArray("TimeValue")->GetTuple1(0) == 12.375);

  CHECK_THROWS_WITH(
      fw::io::write_wind_vti(path, frame, {"velocity", "temperature"}),
      "write_wind_vti: unknown field \"temperature\" (expected one of velocity, pressure, speed, "
      "vorticity, solid, canopy_density)");
  frame.velocity.pop_back();
  CHECK_THROWS_AS(fw::io::write_wind_vti(path, frame, {"velocity"}), std::invalid_argument);
  CHECK_FALSE(has_temporary(dir.path()));
}

TEST_CASE("write_wind_vti: a missing or unusable folder throws runtime_error naming the path", "[output]") {
  fw::test::TempDir dir("fw_out");
  const fw::io::WindFrame frame = sample_frame();

  const fs::path missing = fs::path(dir.path()) / "no" / "wind.vti";
  CHECK_THROWS_MATCHES(
      fw::io::write_wind_vti(missing, frame, {"velocity"}), std::runtime_error,
      Catch::Matchers::Message("write_wind_vti: cannot write " + missing.string() + ": the folder " +
                               missing.parent_path().string() + " does not exist"));

  // A folder nobody may create files in, root included: VTK's open failure becomes the message.
  if (fs::is_directory("/proc")) {
    const fs::path target = "/proc/fw_wind_test.vti";
    CHECK_THROWS_WITH(fw::io::write_wind_vti(target, frame, {"velocity"}),
                      Catch::Matchers::StartsWith("write_wind_vti: cannot write " + target.string() + ": "));
  }

  // The writer cannot open its temporary (a folder is in the way): the VTK failure becomes the message.
  const fs::path path = fs::path(dir.path()) / "wind.vti";
  const fs::path blocker = fs::path(path.string() + ".tmp-" + std::to_string(::getpid()));
  fs::create_directory(blocker);
  CHECK_THROWS_WITH(fw::io::write_wind_vti(path, frame, {"velocity"}),
                    Catch::Matchers::StartsWith("write_wind_vti: cannot write " + path.string() + ": "));
  CHECK_FALSE(fs::exists(path));
  CHECK_FALSE(has_temporary(dir.path()));
}
