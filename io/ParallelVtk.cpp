#include "io/ParallelVtk.hpp"

#include <fmt/format.h>
#include <vtkAbstractArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkType.h>

#include <stdexcept>

#include "base/AtomicFile.hpp"
#include "io/PvdCollection.hpp"

namespace fw::io {

namespace {

// The VTK XML name of a VTK data type.
std::string xml_type(int vtk_type, const char* array) {
  switch (vtk_type) {
    case VTK_FLOAT:
      return "Float32";
    case VTK_DOUBLE:
      return "Float64";
    case VTK_UNSIGNED_CHAR:
      return "UInt8";
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
      return "Int8";
    case VTK_INT:
      return "Int32";
    case VTK_UNSIGNED_INT:
      return "UInt32";
    case VTK_LONG_LONG:
      return "Int64";
    case VTK_ID_TYPE:
      return sizeof(vtkIdType) == 8 ? "Int64" : "Int32";
    default:
      throw std::invalid_argument(
          fmt::format("describe_arrays: array \"{}\" has VTK type {}, which the summary cannot declare",
                      array, vtk_type));
  }
}

std::vector<VtkArrayDeclaration> declarations(vtkFieldData* data) {
  std::vector<VtkArrayDeclaration> out;
  for (int a = 0; a < data->GetNumberOfArrays(); ++a) {
    vtkAbstractArray* array = data->GetAbstractArray(a);
    const char* name = array->GetName() ? array->GetName() : "";
    out.push_back({name, xml_type(array->GetDataType(), name), array->GetNumberOfComponents()});
  }
  return out;
}

std::string data_section(const char* tag, const std::vector<VtkArrayDeclaration>& arrays,
                         const std::string& vectors) {
  if (arrays.empty()) return "";
  std::string text =
      fmt::format("    <{}{}>\n", tag,
                  vectors.empty() ? "" : fmt::format(" Vectors=\"{}\"", detail::xml_escape(vectors)));
  for (const VtkArrayDeclaration& a : arrays)
    text += fmt::format("      <PDataArray type=\"{}\" Name=\"{}\" NumberOfComponents=\"{}\"/>\n", a.type,
                        detail::xml_escape(a.name), a.components);
  return text + fmt::format("    </{}>\n", tag);
}

std::string header(const char* type) {
  return fmt::format(
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"{}\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
      type);
}

}  // namespace

VtkArrays describe_arrays(vtkDataSet* piece) {
  VtkArrays arrays;
  arrays.point_data = declarations(piece->GetPointData());
  arrays.cell_data = declarations(piece->GetCellData());
  if (vtkDataArray* v = piece->GetPointData()->GetVectors(); v && v->GetName())
    arrays.point_vectors = v->GetName();
  if (vtkDataArray* v = piece->GetCellData()->GetVectors(); v && v->GetName())
    arrays.cell_vectors = v->GetName();
  if (auto* poly = vtkPolyData::SafeDownCast(piece); poly && poly->GetPoints())
    arrays.points_type = xml_type(poly->GetPoints()->GetDataType(), "Points");
  return arrays;
}

void write_pvti(const std::filesystem::path& path, const VtkArrays& arrays,
                const std::array<double, 3>& origin, double h, const std::array<int, 6>& whole_extent,
                const std::vector<std::pair<std::array<int, 6>, std::string>>& pieces) {
  const auto extent = [](const std::array<int, 6>& e) {
    return fmt::format("{} {} {} {} {} {}", e[0], e[1], e[2], e[3], e[4], e[5]);
  };
  // {} prints the shortest text that reads back to the same double.
  std::string text = header("PImageData");
  text += fmt::format(
      "  <PImageData WholeExtent=\"{}\" GhostLevel=\"0\" Origin=\"{} {} {}\" Spacing=\"{} {} {}\" "
      "Direction=\"1 0 0 0 1 0 0 0 1\">\n",
      extent(whole_extent), origin[0], origin[1], origin[2], h, h, h);
  text += data_section("PPointData", arrays.point_data, arrays.point_vectors);
  text += data_section("PCellData", arrays.cell_data, arrays.cell_vectors);
  for (const auto& [piece_extent, source] : pieces)
    text += fmt::format("    <Piece Extent=\"{}\" Source=\"{}\"/>\n", extent(piece_extent),
                        detail::xml_escape(source));
  text += "  </PImageData>\n</VTKFile>\n";
  base::write_text_atomically("write_pvti", path, text);
}

void write_pvtp(const std::filesystem::path& path, const VtkArrays& arrays,
                const std::vector<std::string>& sources) {
  std::string text = header("PPolyData");
  text += "  <PPolyData GhostLevel=\"0\">\n";
  text += data_section("PPointData", arrays.point_data, arrays.point_vectors);
  text += data_section("PCellData", arrays.cell_data, arrays.cell_vectors);
  text += fmt::format(
      "    <PPoints>\n      <PDataArray type=\"{}\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    "
      "</PPoints>\n",
      arrays.points_type);
  for (const std::string& source : sources)
    text += fmt::format("    <Piece Source=\"{}\"/>\n", detail::xml_escape(source));
  text += "  </PPolyData>\n</VTKFile>\n";
  base::write_text_atomically("write_pvtp", path, text);
}

std::string piece_file(const std::string& stem, int index, int rank, const std::string& extension) {
  return fmt::format("{}_{:06d}_{:04d}.{}", stem, index, rank, extension);
}

std::vector<std::string> piece_files(const std::string& stem, int index, int ranks,
                                     const std::string& extension) {
  std::vector<std::string> files;
  for (int r = 0; r < ranks; ++r) files.push_back(piece_file(stem, index, r, extension));
  return files;
}

}  // namespace fw::io
