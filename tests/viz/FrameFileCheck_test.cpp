#include <catch2/catch.hpp>

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/support/RunFolders.hpp"
#include "tests/support/TempDir.hpp"
#include "viz/FrameFileCheck.hpp"
#include "viz/RunFolder.hpp"

namespace fs = std::filesystem;
using fw::viz::check_frame_file;

namespace {

std::string read_all(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

void write_all(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// Replaces the first `from` in the file by `to`; fails the test when there is none.
void replace_in(const fs::path& path, const std::string& from, const std::string& to) {
  std::string text = read_all(path);
  const std::size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  write_all(path, text.replace(at, from.size(), to));
}

// Where the appended bytes of the first array named `name` after `section` begin: after <AppendedData>'s
// '_', at its offset.
std::size_t appended_array_at(const std::string& text, const std::string& name,
                              const std::string& section = "") {
  const std::size_t array = text.find("Name=\"" + name + "\"", text.find(section));
  const std::size_t offset = text.find("offset=\"", array) + std::strlen("offset=\"");
  const std::size_t data = text.find('_', text.find("<AppendedData")) + 1;
  return data + std::stoull(text.substr(offset, text.find('"', offset) - offset));
}

void put_u64(std::string& text, std::size_t at, std::uint64_t value) {
  for (int k = 0; k < 8; ++k) text[at + std::size_t(k)] = char((value >> (8 * k)) & 0xff);
}

// A .vtp of one polyline through three points, in forestwind's encoding with the given compressor.
fs::path write_polyline(const fs::path& dir, const std::string& name, int compressor) {
  vtkNew<vtkPoints> points;
  for (int n = 0; n < 3; ++n) points->InsertNextPoint(0.0, 0.0, double(n));
  vtkNew<vtkCellArray> lines;
  const vtkIdType ids[3] = {0, 1, 2};
  lines->InsertNextCell(3, ids);
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetLines(lines);
  const fs::path path = dir / name;
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(poly);
  writer->SetFileName(path.string().c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  writer->SetHeaderTypeToUInt64();
  writer->SetCompressorType(compressor);
  REQUIRE(writer->Write() == 1);
  return path;
}

}  // namespace

TEST_CASE("FrameFileCheck: the frames a run writes pass, with LZ4, zlib or no compression", "[viz]") {
  fw::test::TempDir dir("fw_frame_check");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {fw::test::trunk(12, 10, 8, 0.4, 5, 0.5)}, 1, 0.5);
  CHECK_NOTHROW(check_frame_file(fs::path(dir.path()) / "wind" / "wind_000000.vti"));
  CHECK_NOTHROW(check_frame_file(fs::path(dir.path()) / "trees" / "trees_000000.vtp"));
  // The last offset of the lines is decoded from each encoding: a wrong decoding would not match the
  // connectivity's three ids.
  CHECK_NOTHROW(check_frame_file(write_polyline(dir.path(), "none.vtp", vtkXMLWriter::NONE)));
  CHECK_NOTHROW(check_frame_file(write_polyline(dir.path(), "zlib.vtp", vtkXMLWriter::ZLIB)));
  CHECK_NOTHROW(check_frame_file(write_polyline(dir.path(), "lz4.vtp", vtkXMLWriter::LZ4)));
}

TEST_CASE("FrameFileCheck: a block header listing no block but a partial last one is refused", "[viz]") {
  // run_folder_fuzz's find: VTK 9.1 computed the array's size as 0 blocks less a block plus the last, a
  // huge number, and read block 0 of none (a null dereference in vtkXMLDataParser::ReadBlock).
  fw::test::TempDir dir("fw_frame_check");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {fw::test::trunk(12, 10, 8, 0.4, 5, 0.5)}, 1, 0.5);
  const fs::path trees = fs::path(dir.path()) / "trees" / "trees_000000.vtp";
  std::string text = read_all(trees);
  put_u64(text, appended_array_at(text, "radius"), 0);
  write_all(trees, text);
  CHECK_THROWS_WITH(check_frame_file(trees),
                    Catch::Contains(trees.string()) && Catch::Contains("block header is inconsistent"));
  // And through render's reader, which names the file instead of crashing.
  const fw::viz::RunFolder run(dir.path());
  CHECK_THROWS_WITH(run.load(run.select(std::nullopt, std::nullopt)), Catch::Contains("trees_000000.vtp"));
}

TEST_CASE("FrameFileCheck: counts that claim more than an array's block holds are refused", "[viz]") {
  fw::test::TempDir dir("fw_frame_check");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {fw::test::trunk(12, 10, 8, 0.4, 5, 0.5)}, 1, 0.5);
  const fs::path wind = fs::path(dir.path()) / "wind" / "wind_000000.vti";
  const fs::path trees = fs::path(dir.path()) / "trees" / "trees_000000.vtp";

  SECTION("components: VTK would allocate a billion per tuple") {
    replace_in(trees, "NumberOfComponents=\"3\"", "NumberOfComponents=\"1000000000\"");
    CHECK_THROWS_WITH(check_frame_file(trees), Catch::Contains("from 0 to 1024"));
    replace_in(trees, "NumberOfComponents=\"1000000000\"", "NumberOfComponents=\"1024\"");
    CHECK_THROWS_WITH(check_frame_file(trees), Catch::Contains("its piece's counts give"));
  }
  SECTION("points: a piece claiming more points than its arrays hold") {
    replace_in(trees, "NumberOfPoints=\"5\"", "NumberOfPoints=\"500000000\"");
    CHECK_THROWS_WITH(check_frame_file(trees), Catch::Contains("its piece's counts give"));
  }
  SECTION("extent: a whole extent larger than the pieces, which VTK allocates") {
    replace_in(wind, "WholeExtent=\"0 40 0 20 0 10\"", "WholeExtent=\"0 40000 0 20000 0 10\"");
    CHECK_THROWS_WITH(check_frame_file(wind), Catch::Contains("its piece's extent is not its whole extent"));
  }
  SECTION("extent: a piece other than the whole extent") {
    replace_in(wind, "<Piece Extent=\"0 40 0 20 0 10\"", "<Piece Extent=\"0 40 0 20 0 11\"");
    CHECK_THROWS_WITH(check_frame_file(wind), Catch::Contains("its piece's extent is not its whole extent"));
  }
  SECTION("pieces: a second piece, whose arrays VTK would size by the first's") {
    replace_in(trees, "</Piece>", "</Piece><Piece NumberOfPoints=\"0\"></Piece>");
    CHECK_THROWS_WITH(check_frame_file(trees), Catch::Contains("more than one <Piece>"));
  }
  SECTION("encoding: an ascii array, which VTK 9.1 reads past when short") {
    replace_in(wind, "format=\"appended\"", "format=\"ascii\"");
    CHECK_THROWS_WITH(check_frame_file(wind), Catch::Contains("format appended expected"));
  }
  SECTION("names: two arrays of one name, the second of which VTK reads into an array it does not have") {
    replace_in(wind, "Name=\"speed\"", "Name=\"velocity\"");
    CHECK_THROWS_WITH(check_frame_file(wind),
                      Catch::Contains("<CellData>: two data arrays named 'velocity'"));
  }
  SECTION("encoding: UInt32 headers, another layout of the blocks") {
    replace_in(wind, "header_type=\"UInt64\"", "header_type=\"UInt32\"");
    CHECK_THROWS_WITH(check_frame_file(wind), Catch::Contains("header_type UInt64 expected"));
  }
}

TEST_CASE("FrameFileCheck: a last offset past the connectivity's ids is refused before VTK allocates it",
          "[viz]") {
  // VTK sizes a cell array's connectivity by its last offset, read from the file: 2^39 ids is 4 TiB.
  fw::test::TempDir dir("fw_frame_check");
  const fs::path path = write_polyline(dir.path(), "line.vtp", vtkXMLWriter::NONE);
  std::string text = read_all(path);
  REQUIRE(text.find("type=\"Int64\" Name=\"offsets\"", text.find("<Lines>")) !=
          std::string::npos);  // 8 bytes an offset
  // Uncompressed, an array is [bytes] then its values: the one offset (Int64) follows its header.
  put_u64(text, appended_array_at(text, "offsets", "<Lines>") + 8, std::uint64_t(1) << 39);
  write_all(path, text);
  CHECK_THROWS_WITH(check_frame_file(path), Catch::Contains("data array 'connectivity'") &&
                                                Catch::Contains("its piece's counts give 4398046511104"));
}

TEST_CASE("RunFolder: a trees frame whose lines name points it lacks is refused", "[viz]") {
  // The picture indexes the trees' points by these ids: one past the points would be read out of bounds.
  fw::test::TempDir dir("fw_frame_check");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {}, 1, 0.5);
  const fs::path trees = fs::path(dir.path()) / "trees" / "trees_000000.vtp";
  fs::create_directories(trees.parent_path());
  fs::copy_file(write_polyline(dir.path(), "line.vtp", vtkXMLWriter::NONE), trees);
  fw::io::PvdCollection(fs::path(dir.path()) / "trees.pvd").add(0.0, "trees/trees_000000.vtp");
  {
    const fw::viz::RunFolder run(dir.path());
    CHECK(run.load(run.select(std::nullopt, std::nullopt)).trees->segments.size() == 2);
  }
  std::string text = read_all(trees);
  REQUIRE(text.find("type=\"Int64\" Name=\"connectivity\"", text.find("<Lines>")) !=
          std::string::npos);  // 8 bytes an id
  put_u64(text, appended_array_at(text, "connectivity", "<Lines>") + 8 + 2 * 8,
          7);  // the third id: point 7 of 3
  write_all(trees, text);
  const fw::viz::RunFolder run(dir.path());
  CHECK_THROWS_WITH(run.load(run.select(std::nullopt, std::nullopt)),
                    Catch::Contains("line 0 names point 7 of 3"));
}

TEST_CASE("FrameFileCheck: a .pvti's pieces hold its whole extent and every array it declares", "[viz]") {
  // VTK's parallel reader allocates each declared array over the whole extent, with the summary's type and
  // components, and fills it from the pieces.
  fw::test::TempDir dir("fw_frame_check");
  fw::test::write_run(dir.path(), fw::test::UniformWind{}, {}, 1, 0.5);
  const fs::path summary = fs::path(dir.path()) / "wind" / "wind_000000.pvti";
  const auto write_summary = [&](const std::string& whole, const std::string& declared,
                                 const std::string& piece) {
    write_all(summary,
              "<VTKFile type=\"PImageData\" version=\"1.0\" byte_order=\"LittleEndian\" "
              "header_type=\"UInt64\">\n  <PImageData WholeExtent=\"" +
                  whole + "\" GhostLevel=\"0\" Origin=\"0 0 0\" Spacing=\"1 1 1\">\n    <PCellData>" +
                  declared + "</PCellData>\n    <Piece Extent=\"" + piece +
                  "\" Source=\"wind_000000.vti\"/>\n  </PImageData>\n</VTKFile>\n");
  };
  const std::string velocity = R"(<PDataArray type="Float32" Name="velocity" NumberOfComponents="3"/>)";
  write_summary("0 40 0 20 0 10", velocity, "0 40 0 20 0 10");
  CHECK_NOTHROW(check_frame_file(summary));
  write_summary("0 40 0 20 0 10", R"(<PDataArray type="Float32" Name="velocity" NumberOfComponents="1000"/>)",
                "0 40 0 20 0 10");
  CHECK_THROWS_WITH(check_frame_file(summary), Catch::Contains("wind_000000.vti") &&
                                                   Catch::Contains("declares CellData array 'velocity'"));
  write_summary("0 40 0 20 0 10", velocity + R"(<PDataArray type="Float32" Name="temperature"/>)",
                "0 40 0 20 0 10");
  CHECK_THROWS_WITH(check_frame_file(summary), Catch::Contains("'temperature'"));
  write_summary("0 80 0 20 0 10", velocity, "0 40 0 20 0 10");
  CHECK_THROWS_WITH(check_frame_file(summary),
                    Catch::Contains("do not cover its whole extent 0 80 0 20 0 10"));
  write_summary("0 40 0 20 0 10", velocity, "0 40 0 20 0 9");
  CHECK_THROWS_WITH(check_frame_file(summary), Catch::Contains("is not the extent 0 40 0 20 0 9"));
}
