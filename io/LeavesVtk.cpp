#include "io/LeavesVtk.hpp"

#include "io/VtkXml.hpp"

#include <fmt/format.h>

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt32Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkXMLPolyDataWriter.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "trees/LeafState.hpp"

namespace fw::io {

void validate_leaf_frame(const char* function, const LeafFrame& leaves) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(fmt::format("{}: leaves: {}", function, what));
  };
  const std::size_t n = leaves.size_written();
  const auto check_size = [&](const char* name, std::size_t size) {
    if (size != n) fail(fmt::format("{}: expected {} values (one per leaf), got {}", name, n, size));
  };
  check_size("normal", leaves.normal.size());
  check_size("state", leaves.state.size());
  check_size("tree_id", leaves.tree_id.size());
  check_size("size", leaves.side.size());
  const auto finite = [](const std::array<float, 3>& v) {
    return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
  };
  constexpr auto kLastState = std::uint8_t(trees::LeafState::exited);
  for (std::size_t k = 0; k < n; ++k) {
    if (!finite(leaves.position[k])) fail(fmt::format("position of leaf {} is not finite", k));
    if (!finite(leaves.normal[k])) fail(fmt::format("normal of leaf {} is not finite", k));
    if (!std::isfinite(leaves.side[k])) fail(fmt::format("size of leaf {} is not finite", k));
    if (leaves.state[k] > kLastState) {
      fail(fmt::format("state of leaf {}: expected 0 to {}, got {}", k, kLastState, leaves.state[k]));
    }
  }
}

namespace {

// The poly data of `leaves` at `time`, as the header describes it.
vtkSmartPointer<vtkPolyData> leaves_poly_data(double time, const LeafFrame& leaves) {
  const std::size_t n = leaves.size_written();
  // Vertex ids are stored in 32 bits (half the connectivity of 64-bit ids); a frame never comes near 2^31.
  if (n > std::size_t(std::numeric_limits<std::int32_t>::max())) {
    throw std::invalid_argument(
        fmt::format("write_leaves_vtp: leaves: {} leaves, more than a file holds ({})", n,
                    std::numeric_limits<std::int32_t>::max()));
  }
  const auto count = vtkIdType(n);

  // Float32 as the trees' files: positions within a few km keep 0.1 mm, at half the size of float64.
  vtkNew<vtkPoints> points;
  points->SetDataTypeToFloat();
  points->SetNumberOfPoints(count);
  float* xyz = static_cast<vtkFloatArray*>(points->GetData())->GetPointer(0);
  vtkNew<vtkFloatArray> normal;
  normal->SetName("normal");
  normal->SetNumberOfComponents(3);
  normal->SetNumberOfTuples(count);
  vtkNew<vtkUnsignedCharArray> state;
  state->SetName("state");
  state->SetNumberOfTuples(count);
  vtkNew<vtkIntArray> tree_id;
  tree_id->SetName("tree_id");
  tree_id->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> size;
  size->SetName("size");
  size->SetNumberOfTuples(count);
  // One vertex per point: offsets 0, 1, ..., n and connectivity 0, 1, ..., n - 1, built directly rather
  // than cell by cell.
  vtkNew<vtkTypeInt32Array> offsets, connectivity;
  offsets->SetNumberOfTuples(count + 1);
  connectivity->SetNumberOfTuples(count);

  for (std::size_t k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) {
      xyz[3 * k + std::size_t(c)] = leaves.position[k][std::size_t(c)];
      normal->SetTypedComponent(vtkIdType(k), c, leaves.normal[k][std::size_t(c)]);
    }
    state->SetValue(vtkIdType(k), leaves.state[k]);
    tree_id->SetValue(vtkIdType(k), leaves.tree_id[k]);
    size->SetValue(vtkIdType(k), leaves.side[k]);
    offsets->SetValue(vtkIdType(k), std::int32_t(k));
    connectivity->SetValue(vtkIdType(k), std::int32_t(k));
  }
  offsets->SetValue(count, std::int32_t(n));
  vtkNew<vtkCellArray> verts;
  verts->SetData(offsets.Get(), connectivity.Get());

  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetVerts(verts);
  data->GetPointData()->AddArray(normal);
  data->GetPointData()->SetActiveNormals("normal");
  data->GetPointData()->AddArray(state);
  data->GetPointData()->AddArray(tree_id);
  data->GetPointData()->AddArray(size);
  vtkNew<vtkDoubleArray> time_value;
  time_value->SetName("TimeValue");
  time_value->SetNumberOfTuples(1);
  time_value->SetValue(0, time);
  data->GetFieldData()->AddArray(time_value);
  return data;
}

}  // namespace

VtkArrays leaves_vtp_arrays() {
  return describe_arrays(leaves_poly_data(0.0, LeafFrame{}));
}

void write_leaves_vtp(const std::filesystem::path& path, double time, const LeafFrame& leaves) {
  validate_leaf_frame("write_leaves_vtp", leaves);
  vtkSmartPointer<vtkPolyData> data = leaves_poly_data(time, leaves);
  vtkNew<vtkXMLPolyDataWriter> writer;
  writer->SetInputData(data);
  write_vtk_xml("write_leaves_vtp", path, writer);
}

}  // namespace fw::io
