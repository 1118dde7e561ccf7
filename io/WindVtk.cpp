#include "io/WindVtk.hpp"

#include "io/VtkXml.hpp"

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
                    const std::vector<std::string>& fields) {
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
  auto wanted = [&](const std::string& name) {
    return std::find(fields.begin(), fields.end(), name) != fields.end();
  };

  vtkNew<vtkImageData> image;
  image->SetOrigin(frame.origin[0], frame.origin[1], frame.origin[2]);
  image->SetSpacing(frame.h, frame.h, frame.h);
  image->SetExtent(0, frame.dims[0], 0, frame.dims[1], 0, frame.dims[2]);
  vtkCellData* cells = image->GetCellData();

  // Derived fields live here until the writer is done with them (the arrays point into them).
  std::vector<float> speed, vorticity;
  if (wanted("velocity")) {
    cells->AddArray(float_array("velocity", frame.velocity, 3));
    cells->SetActiveVectors("velocity");
  }
  if (wanted("pressure") && !frame.pressure.empty())
    cells->AddArray(float_array("pressure", frame.pressure, 1));
  if (wanted("speed")) {
    speed = wind_speed(frame);
    cells->AddArray(float_array("speed", speed, 1));
  }
  if (wanted("vorticity")) {
    vorticity = wind_vorticity(frame);
    cells->AddArray(float_array("vorticity", vorticity, 3));
  }
  if (wanted("solid") && !frame.solid.empty()) {
    vtkNew<vtkUnsignedCharArray> solid;
    solid->SetName("solid");
    solid->SetNumberOfTuples(vtkIdType(frame.solid.size()));
    // 0/1 rather than the raw bytes, so that a threshold at 0.5 selects solid cells.
    for (std::size_t c = 0; c < frame.solid.size(); ++c)
      solid->SetValue(vtkIdType(c), frame.solid[c] ? 1 : 0);
    cells->AddArray(solid);
  }
  if (wanted("canopy_density") && !frame.canopy_density.empty()) {
    cells->AddArray(float_array("canopy_density", frame.canopy_density, 1));
  }

  vtkNew<vtkDoubleArray> time;
  time->SetName("TimeValue");
  time->SetNumberOfTuples(1);
  time->SetValue(0, frame.time);
  image->GetFieldData()->AddArray(time);

  vtkNew<vtkXMLImageDataWriter> writer;
  writer->SetInputData(image);
  write_vtk_xml("write_wind_vti", path, writer);
}

}  // namespace fw::io
