#include "io/WindVtk.hpp"

#include "io/AtomicFile.hpp"
#include "io/PvdCollection.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vtkCallbackCommand.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLImageDataWriter.h>
#include <vtkXMLWriter.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace fw::io {
namespace {

// Keeps VTK's error text (instead of printing it on stderr) so that it can go into the exception.
void keep_error_text(vtkObject* /*caller*/, unsigned long /*event*/, void* client, void* call) {
  auto* text = static_cast<std::string*>(client);
  std::string message = call ? static_cast<const char*>(call) : "unknown VTK error";
  // VTK 9.1: "ERROR: In FILE, line N\nCLASS (ADDRESS): message\n\n". Only the message is useful to a user.
  if (message.rfind("ERROR: In ", 0) == 0) {
    if (const auto newline = message.find('\n'); newline != std::string::npos) message.erase(0, newline + 1);
  }
  if (const auto colon = message.find("): "); colon != std::string::npos && colon < message.find('\n')) {
    message.erase(0, colon + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (!text->empty()) *text += "; ";
  *text += message;
}

// vtkErrorCode::GetStringFromErrorCode is in VTK::CommonMisc (not linked); the enum itself is header-only.
std::string error_code_text(unsigned long code) {
  if (code == vtkErrorCode::CannotOpenFileError) return "cannot open the file";
  if (code == vtkErrorCode::OutOfDiskSpaceError) return "out of disk space";
  if (code == vtkErrorCode::NoFileNameError) return "no file name";
  if (code > 0 && code < vtkErrorCode::FirstVTKErrorCode) return std::strerror(int(code));
  return fmt::format("VTK error code {}", code);
}

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

namespace detail {

void write_vtk_xml(const char* function, const std::filesystem::path& path, vtkXMLWriter* writer) {
  require_output_folder(function, path);
  AtomicFile file(path);
  const std::string temporary = file.temporary_path().string();
  writer->SetFileName(temporary.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw bytes after <AppendedData>, not base64
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();  // frames over 4 GiB uncompressed stay readable

  std::string messages;
  vtkNew<vtkCallbackCommand> on_error;
  on_error->SetCallback(keep_error_text);
  on_error->SetClientData(&messages);
  writer->AddObserver(vtkCommand::ErrorEvent, on_error);
  // The executive repeats a failure with a dump of the pipeline request: keep it off stderr, and use its
  // first line only when nothing better was said.
  std::string pipeline_messages;
  vtkNew<vtkCallbackCommand> on_pipeline_error;
  on_pipeline_error->SetCallback(keep_error_text);
  on_pipeline_error->SetClientData(&pipeline_messages);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, on_pipeline_error);

  const int written = writer->Write();
  const unsigned long code = writer->GetErrorCode();
  writer->RemoveObservers(vtkCommand::ErrorEvent);
  writer->GetExecutive()->RemoveObservers(vtkCommand::ErrorEvent);
  if (written == 0 || code != vtkErrorCode::NoError || !messages.empty()) {
    std::string reason = messages;
    if (reason.empty() && code != vtkErrorCode::NoError) reason = error_code_text(code);
    if (reason.empty()) reason = pipeline_messages.substr(0, pipeline_messages.find('\n'));
    if (reason.empty()) reason = "the VTK writer failed";
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), reason));
  }
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), error.what()));
  }
}

}  // namespace detail

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
  detail::write_vtk_xml("write_wind_vti", path, writer);
}

}  // namespace fw::io
