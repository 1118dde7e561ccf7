#include "io/SkeletonVtk.hpp"

#include "io/VtkXml.hpp"

#include <fmt/format.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

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

// Writes `data` with the shared VTK XML settings (io/VtkXml).
void write_polydata(const char* function, const std::filesystem::path& path, vtkPolyData* data) {
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  write_vtk_xml(function, path, writer);
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
