#include "io/SkeletonVtk.hpp"

#include "io/AtomicFile.hpp"

#include <fmt/format.h>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>

namespace fw::io {
namespace {

// The skeleton's points, line cells and the node/element arrays shared by both files.
void fill_skeleton(vtkPolyData* data, const trees::Skeleton& skeleton) {
  const int n = skeleton.size();

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  radius->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> node_id;
  node_id->SetName("node_id");
  node_id->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> parent;
  parent->SetName("parent");
  parent->SetNumberOfTuples(n);
  for (int i = 0; i < n; ++i) {
    const trees::SkeletonNode& node = skeleton.node(i);
    points->SetPoint(i, node.position.x(), node.position.y(), node.position.z());
    radius->SetValue(i, node.radius);
    node_id->SetValue(i, i);
    parent->SetValue(i, node.parent);
  }

  const auto& elements = skeleton.elements();
  const vtkIdType element_count = vtkIdType(elements.size());
  vtkNew<vtkCellArray> lines;
  lines->AllocateExact(element_count, 2 * element_count);
  vtkNew<vtkIntArray> element;
  element->SetName("element");
  element->SetNumberOfTuples(element_count);
  for (vtkIdType k = 0; k < element_count; ++k) {
    const auto [from, to] = elements[std::size_t(k)];
    lines->InsertNextCell({vtkIdType(from), vtkIdType(to)});
    element->SetValue(k, int(k));
  }

  data->SetPoints(points);
  data->SetLines(lines);
  data->GetPointData()->AddArray(radius);
  data->GetPointData()->AddArray(node_id);
  data->GetPointData()->AddArray(parent);
  data->GetCellData()->AddArray(element);
}

// Collects the error messages a VTK object reports, instead of letting them go to the output window (stderr).
void collect_error(vtkObject* /*caller*/, unsigned long /*event*/, void* client, void* call) {
  auto* messages = static_cast<std::string*>(client);
  if (!messages->empty()) *messages += "; ";
  std::string text = call ? static_cast<const char*>(call) : "unknown VTK error";
  // VTK 9.1 formats "ERROR: In FILE, line N\nCLASS (ADDRESS): message\n\n"; keep the message only.
  if (text.rfind("ERROR: In ", 0) == 0 && text.find('\n') != std::string::npos)
    text.erase(0, text.find('\n') + 1);
  if (const auto colon = text.find("): "); colon != std::string::npos && colon < text.find('\n')) {
    text.erase(0, colon + 3);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  *messages += text;
}

// vtkErrorCode::GetStringFromErrorCode lives in VTK::CommonMisc, which forestwind_io does not link; the codes
// themselves are a header-only enum (below FirstVTKErrorCode they are errno values).
std::string describe_error_code(unsigned long code) {
  switch (code) {
    case vtkErrorCode::FileNotFoundError:
      return "file not found";
    case vtkErrorCode::CannotOpenFileError:
      return "cannot open the file";
    case vtkErrorCode::NoFileNameError:
      return "no file name";
    case vtkErrorCode::OutOfDiskSpaceError:
      return "out of disk space";
    default:
      break;
  }
  if (code > 0 && code < vtkErrorCode::FirstVTKErrorCode) return std::strerror(int(code));
  return fmt::format("VTK error code {}", code);
}

// Writes `data` to `path` as binary appended, zlib-compressed XML PolyData through an AtomicFile.
void write_polydata(const char* function, const std::filesystem::path& path, vtkPolyData* data) {
  std::filesystem::path folder = path.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (!std::filesystem::is_directory(folder, error)) {
    const bool exists = std::filesystem::exists(folder, error);
    throw std::runtime_error(exists ? fmt::format("{}: cannot write {}: {} is not a folder", function,
                                                  path.string(), folder.string())
                                    : fmt::format("{}: cannot write {}: the folder {} does not exist",
                                                  function, path.string(), folder.string()));
  }

  AtomicFile file(path);
  const std::string temporary = file.temporary_path().string();

  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  writer->SetFileName(temporary.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw bytes after <AppendedData>, not base64
  writer->SetCompressorTypeToZLib();
  writer->SetHeaderTypeToUInt64();

  std::string messages;
  vtkNew<vtkCallbackCommand> on_error;
  on_error->SetCallback(collect_error);
  on_error->SetClientData(&messages);
  writer->AddObserver(vtkCommand::ErrorEvent, on_error);
  // The pipeline repeats a failure with a dump of the request; keep it off stderr and use it only as a
  // fallback reason.
  std::string pipeline_messages;
  vtkNew<vtkCallbackCommand> on_pipeline_error;
  on_pipeline_error->SetCallback(collect_error);
  on_pipeline_error->SetClientData(&pipeline_messages);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, on_pipeline_error);

  const int written = writer->Write();
  const unsigned long code = writer->GetErrorCode();
  if (written == 0 || code != vtkErrorCode::NoError || !messages.empty()) {
    std::string reason = messages;
    if (reason.empty() && code != vtkErrorCode::NoError) reason = describe_error_code(code);
    if (reason.empty() && !pipeline_messages.empty()) {
      reason = pipeline_messages.substr(0, pipeline_messages.find('\n'));
    }
    if (reason.empty()) reason = "vtkXMLPolyDataWriter::Write() failed";
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), reason));
  }
  file.commit();  // throws std::runtime_error naming the path; the temporary is removed either way
}

void require_nodes(const char* function, const trees::Skeleton& skeleton) {
  if (skeleton.size() == 0) {
    throw std::invalid_argument(
        fmt::format("{}: the skeleton is empty (expected at least one node)", function));
  }
}

}  // namespace

std::string mode_array_name(int index, int count) {
  int digits = 1;
  for (int rest = count; rest >= 10; rest /= 10) ++digits;
  return fmt::format("mode_{:0{}}", index + 1, std::max(2, digits));
}

void write_skeleton_vtp(const std::filesystem::path& path, const trees::Skeleton& skeleton) {
  require_nodes("write_skeleton_vtp", skeleton);
  vtkNew<vtkPolyData> data;
  fill_skeleton(data, skeleton);
  write_polydata("write_skeleton_vtp", path, data);
}

void write_modes_vtp(const std::filesystem::path& path, const trees::Skeleton& skeleton,
                     const std::vector<ModeShape>& modes, double display_amplitude) {
  require_nodes("write_modes_vtp", skeleton);
  const int n = skeleton.size();
  const int m = int(modes.size());
  if (!std::isfinite(display_amplitude) || display_amplitude < 0.0) {
    throw std::invalid_argument(fmt::format(
        "write_modes_vtp: display_amplitude: expected a finite value >= 0 (0 = 10% of the height), got {}",
        display_amplitude));
  }
  for (int j = 0; j < m; ++j) {
    const Eigen::MatrixX3d& u = modes[std::size_t(j)].displacement;
    if (u.rows() != n) {
      throw std::invalid_argument(fmt::format(
          "write_modes_vtp: mode {} ({}): expected a displacement with {} rows (one per node), got {}", j + 1,
          mode_array_name(j, m), n, u.rows()));
    }
    if (!u.allFinite()) {
      throw std::invalid_argument(fmt::format("write_modes_vtp: mode {} ({}): the displacement is not finite",
                                              j + 1, mode_array_name(j, m)));
    }
  }

  double amplitude = display_amplitude;
  if (amplitude == 0.0) {
    const double height = skeleton.height();
    amplitude = height > 0.0 ? 0.1 * height : 0.1 * skeleton.bounding_box().diagonal().norm();
  }

  vtkNew<vtkPolyData> data;
  fill_skeleton(data, skeleton);

  vtkNew<vtkDoubleArray> frequencies;
  frequencies->SetName("frequencies_hz");
  frequencies->SetNumberOfTuples(m);
  vtkNew<vtkDoubleArray> damping;
  damping->SetName("damping_ratios");
  damping->SetNumberOfTuples(m);
  vtkNew<vtkDoubleArray> scales;
  scales->SetName("modal_scale");
  scales->SetNumberOfTuples(m);

  for (int j = 0; j < m; ++j) {
    const ModeShape& mode = modes[std::size_t(j)];
    const double largest = mode.displacement.rowwise().norm().maxCoeff();
    // A zero mode keeps scale 0 (and an all-zero array) rather than dividing by zero.
    const double scale = largest > 0.0 ? amplitude / largest : 0.0;

    vtkNew<vtkDoubleArray> shape;
    const std::string name = mode_array_name(j, m);
    shape->SetName(name.c_str());
    shape->SetNumberOfComponents(3);
    shape->SetNumberOfTuples(n);
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) shape->SetTypedComponent(i, c, scale * mode.displacement(i, c));
    }
    data->GetPointData()->AddArray(shape);
    if (j == 0) data->GetPointData()->SetActiveVectors(name.c_str());

    frequencies->SetValue(j, mode.frequency_hz);
    damping->SetValue(j, mode.damping_ratio);
    scales->SetValue(j, scale);
  }

  data->GetFieldData()->AddArray(frequencies);
  data->GetFieldData()->AddArray(damping);
  data->GetFieldData()->AddArray(scales);
  write_polydata("write_modes_vtp", path, data);
}

}  // namespace fw::io
