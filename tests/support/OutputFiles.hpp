// Reading back what the writers left in a test's folder (tests/io/): VTK XML polydata, .pvd collections,
// and leftover temporaries of the atomic writes (base/AtomicFile: "NAME.tmp-...").
//
//   CHECK_FALSE(fw::test::has_temporary(dir.path()));
//   const auto data = fw::test::read_vtp(dir / "trees_000000.vtp");
#pragma once

#include <catch2/catch.hpp>

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>
#include <utility>
#include <vector>

namespace fw::test {

/// Whether `folder` holds a file under an atomic write's temporary name.
inline bool has_temporary(const std::filesystem::path& folder) {
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) return true;
  }
  return false;
}

/// The whole file as text (bytes as they are).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A .vtp read back with VTK's reader; REQUIREs that it exists and reads without error.
inline vtkSmartPointer<vtkPolyData> read_vtp(const std::filesystem::path& path) {
  REQUIRE(std::filesystem::is_regular_file(path));
  vtkNew<vtkXMLPolyDataReader> reader;
  REQUIRE(reader->CanReadFile(path.string().c_str()) == 1);
  reader->SetFileName(path.string().c_str());
  reader->Update();
  REQUIRE(reader->GetErrorCode() == 0);
  vtkSmartPointer<vtkPolyData> data = reader->GetOutput();
  REQUIRE(data != nullptr);
  return data;
}

/// The (timestep, file) attributes of every <DataSet> in a .pvd's text, in file order.
inline std::vector<std::pair<double, std::string>> pvd_datasets(const std::string& text) {
  const std::regex dataset(R"re(<DataSet timestep="([^"]*)" group="" part="0" file="([^"]*)"/>)re");
  std::vector<std::pair<double, std::string>> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), dataset); it != std::sregex_iterator(); ++it)
    out.emplace_back(std::stod((*it)[1].str()), (*it)[2].str());
  return out;
}

}  // namespace fw::test
