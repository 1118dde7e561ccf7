#include "io/WindVtk.hpp"

#include "io/SiteVtk.hpp"

#include "io/VtkXml.hpp"

#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fw::io {
namespace {

// A float array over `values`, zero-copy: the writer only reads it and it does not outlive the call.
vtkSmartPointer<vtkFloatArray> float_array(const char* name, const std::vector<float>& values,
                                           int components) {
  auto array = vtkSmartPointer<vtkFloatArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetArray(const_cast<float*>(values.data()), vtkIdType(values.size()), /*save=*/1);
  return array;
}

}  // namespace

const std::vector<std::string>& wind_field_names() {
  static const std::vector<std::string> names = {"velocity",  "pressure", "speed",
                                                 "vorticity", "solid",    "canopy_density"};
  return names;
}

void write_wind_vti(const std::filesystem::path& path, const WindFrame& frame,
                    const std::vector<std::string>& fields, const WindPiece* piece, VtkArrays* declared) {
  const auto& known = wind_field_names();
  for (const std::string& field : fields) {
    if (std::find(known.begin(), known.end(), field) == known.end()) {
      throw std::invalid_argument(fmt::format("write_wind_vti: unknown field \"{}\" (expected one of {})",
                                              field, fmt::join(known, ", ")));
    }
  }
  try {
    frame.validate();
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("write_wind_vti: ") + error.what());
  }
  if (piece != nullptr)
    for (int a = 0; a < 2; ++a)
      if (piece->first[a] < 0 || piece->count[a] < 1 || piece->first[a] + piece->count[a] > frame.dims[a])
        throw std::invalid_argument(
            fmt::format("write_wind_vti: the piece's cells {}..{} along {} lie outside the frame's {}",
                        piece->first[a], piece->first[a] + piece->count[a] - 1, "xy"[a], frame.dims[a]));
  auto wanted = [&](const std::string& name) {
    return std::find(fields.begin(), fields.end(), name) != fields.end();
  };
  // A piece's cells of an array over the frame's (x fastest, `components` values a cell), kept in `store`;
  // for a whole frame the array itself, uncopied.
  const auto piece_of = [&](const auto& values, int components,
                            std::decay_t<decltype(values)>& store) -> const std::decay_t<decltype(values)>& {
    if (piece == nullptr) return values;
    store.clear();
    for (int k = 0; k < frame.dims[2]; ++k)
      for (int j = piece->first[1]; j < piece->first[1] + piece->count[1]; ++j) {
        const auto row =
            values.begin() + std::ptrdiff_t(components * frame.cell_index(piece->first[0], j, k));
        store.insert(store.end(), row, row + std::ptrdiff_t(components) * piece->count[0]);
      }
    return store;
  };

  vtkNew<vtkImageData> image;
  image->SetOrigin(frame.origin[0], frame.origin[1], frame.origin[2]);
  image->SetSpacing(frame.h, frame.h, frame.h);
  if (piece == nullptr) {
    image->SetExtent(0, frame.dims[0], 0, frame.dims[1], 0, frame.dims[2]);
  } else {
    const auto& d = piece->domain_first;
    image->SetExtent(d[0], d[0] + piece->count[0], d[1], d[1] + piece->count[1], 0, frame.dims[2]);
  }
  vtkCellData* cells = image->GetCellData();
  // The arrays live here until the writer is done with them (the VTK arrays point into them); derived ones
  // are computed over the whole frame before a piece is cut from them.
  std::vector<float> velocity, pressure, speed, speed_cells, vorticity, vorticity_cells, canopy;
  std::vector<std::uint8_t> solid_piece;
  if (wanted("velocity")) {
    cells->AddArray(float_array("velocity", piece_of(frame.velocity, 3, velocity), 3));
    cells->SetActiveVectors("velocity");
  }
  if (wanted("pressure") && !frame.pressure.empty())
    cells->AddArray(float_array("pressure", piece_of(frame.pressure, 1, pressure), 1));
  if (wanted("speed")) {
    speed = wind_speed(frame);
    cells->AddArray(float_array("speed", piece_of(speed, 1, speed_cells), 1));
  }
  if (wanted("vorticity")) {
    vorticity = wind_vorticity(frame);
    cells->AddArray(float_array("vorticity", piece_of(vorticity, 3, vorticity_cells), 3));
  }
  if (wanted("solid") && !frame.solid.empty()) {
    const std::vector<std::uint8_t>& solid_cells = piece_of(frame.solid, 1, solid_piece);
    vtkNew<vtkUnsignedCharArray> solid;
    solid->SetName("solid");
    solid->SetNumberOfTuples(vtkIdType(solid_cells.size()));
    // 0/1 rather than the raw bytes, so that a threshold at 0.5 selects solid cells.
    for (std::size_t c = 0; c < solid_cells.size(); ++c)
      solid->SetValue(vtkIdType(c), solid_cells[c] ? 1 : 0);
    cells->AddArray(solid);
  }
  if (wanted("canopy_density") && !frame.canopy_density.empty())
    cells->AddArray(float_array("canopy_density", piece_of(frame.canopy_density, 1, canopy), 1));
  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->SetNumberOfTuples(1);
  time->SetValue(0, frame.time);
  image->GetFieldData()->AddArray(time);
  if (frame.site) add_site_field_data(*image->GetFieldData(), *frame.site);
  if (declared != nullptr) *declared = describe_arrays(image);

  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  write_vtk_xml("write_wind_vti", path, writer);
}

}  // namespace fw::io
