#include "viz/RunFolder.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPImageDataReader.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "io/PvdCollection.hpp"
#include "io/SiteVtk.hpp"
#include "io/YamlDocuments.hpp"
#include "viz/FrameFileCheck.hpp"
#include "viz/VtkErrorCapture.hpp"

namespace fw::viz {

namespace fs = std::filesystem;

namespace {

// The units and signs of the wind arrays (io/WindVtk.hpp); a field not listed here is shown without a unit.
struct ArrayMeaning {
  const char* name;
  const char* unit;
  bool is_signed;  // of the array itself (a vector's components are always signed)
};
constexpr ArrayMeaning kArrayMeanings[] = {
    {"velocity", "m/s", false},  {"speed", "m/s", false},          {"pressure", "m^2/s^2", true},
    {"vorticity", "1/s", false}, {"canopy_density", "1/m", false}, {"solid", "", false},
};
constexpr const char* kComponentSuffix[] = {"_x", "_y", "_z"};

const ArrayMeaning* meaning_of(const std::string& name) {
  for (const ArrayMeaning& m : kArrayMeanings)
    if (name == m.name) return &m;
  return nullptr;
}

template <class Reader>
vtkSmartPointer<Reader> read_xml(const fs::path& path) {
  if (!fs::is_regular_file(path))
    throw FrameReadError(fmt::format("render: {}: the file is missing", path.string()));
  VtkErrorCapture capture;
  auto reader = vtkSmartPointer<Reader>::New();
  if (!reader->CanReadFile(path.string().c_str()))
    throw FrameReadError(fmt::format("render: {}: not a VTK XML file of the expected type", path.string()));
  // Before VTK reads a value: its readers trust the sizes a file claims (viz/FrameFileCheck.hpp).
  check_frame_file(path);
  reader->SetFileName(path.string().c_str());
  reader->Update();
  if (!capture.errors().empty() || reader->GetErrorCode() != 0)
    throw FrameReadError(
        fmt::format("render: {}: the file does not read: {}", path.string(), capture.first_error()));
  return reader;
}

// A frame's dataset: its one file, or the .pvti / .pvtp summary of the pieces a run over MPI ranks wrote
// (docs/parallel.md), which the parallel reader joins into one dataset of the whole domain.
template <class Dataset, class Serial, class Parallel>
std::pair<vtkSmartPointer<vtkXMLReader>, Dataset*> read_dataset(const fs::path& path) {
  const std::string extension = path.extension().string();
  vtkSmartPointer<vtkXMLReader> reader;
  if (extension == ".pvti" || extension == ".pvtp")
    reader = read_xml<Parallel>(path);
  else
    reader = read_xml<Serial>(path);
  return {reader, Dataset::SafeDownCast(reader->GetOutputDataObject(0))};
}

std::vector<float> as_floats(vtkDataArray* array) {
  const vtkIdType count = array->GetNumberOfTuples() * array->GetNumberOfComponents();
  std::vector<float> out(static_cast<std::size_t>(count));
  const int components = array->GetNumberOfComponents();
  for (vtkIdType n = 0; n < count; ++n)
    out[std::size_t(n)] = float(array->GetComponent(n / components, int(n % components)));
  return out;
}

WindGrid read_wind(const fs::path& path) {
  const auto [reader, image] =
      read_dataset<vtkImageData, vtkXMLImageDataReader, vtkXMLPImageDataReader>(path);
  int dims[3];
  double origin[3], spacing[3];
  image->GetDimensions(dims);
  image->GetOrigin(origin);
  image->GetSpacing(spacing);
  WindGrid grid;
  grid.file = path;
  for (int a = 0; a < 3; ++a) grid.cells[a] = dims[a] - 1, grid.origin[a] = origin[a];
  grid.cell_size = spacing[0];
  grid.site = io::read_site_field_data(*image->GetFieldData());
  if (grid.cells[0] < 1 || grid.cells[1] < 1 || grid.cells[2] < 1 || !(grid.cell_size > 0.0))
    throw FrameReadError(fmt::format("render: {}: expected a grid of cells, got {} x {} x {} points",
                                     path.string(), dims[0], dims[1], dims[2]));
  const std::size_t cells = std::size_t(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  vtkCellData* data = image->GetCellData();
  for (int n = 0; n < data->GetNumberOfArrays(); ++n) {
    vtkDataArray* array = data->GetArray(n);
    if (!array || !array->GetName() || array->GetNumberOfTuples() != vtkIdType(cells)) continue;
    const std::string name = array->GetName();
    if (name == "solid") {
      grid.solid.resize(cells);
      for (std::size_t c = 0; c < cells; ++c) grid.solid[c] = array->GetComponent(vtkIdType(c), 0) != 0.0;
      continue;
    }
    if (array->GetNumberOfComponents() != 1 && array->GetNumberOfComponents() != 3) continue;
    grid.arrays.push_back({name, array->GetNumberOfComponents(), as_floats(array)});
  }
  // A picture's size follows the grid's: a grid with no array of its cells is not a frame of one.
  if (grid.arrays.empty() && grid.solid.empty())
    throw FrameReadError(fmt::format("render: {}: no cell array of the grid's {} x {} x {} cells",
                                     path.string(), grid.cells[0], grid.cells[1], grid.cells[2]));
  return grid;
}

TreeLines read_trees(const fs::path& path) {
  const auto [reader, poly] = read_dataset<vtkPolyData, vtkXMLPolyDataReader, vtkXMLPPolyDataReader>(path);
  TreeLines trees;
  const vtkIdType points = poly->GetNumberOfPoints();
  vtkDataArray* radius = poly->GetPointData()->GetArray("radius");
  vtkDataArray* displacement = poly->GetPointData()->GetArray("displacement");
  for (vtkIdType n = 0; n < points; ++n) {
    double p[3];
    poly->GetPoint(n, p);
    trees.points.push_back({p[0], p[1], p[2]});
    trees.radius.push_back(radius ? radius->GetComponent(n, 0) : 0.0);
    double d = 0.0;
    if (displacement && displacement->GetNumberOfComponents() == 3)
      for (int c = 0; c < 3; ++c) d += displacement->GetComponent(n, c) * displacement->GetComponent(n, c);
    trees.displacement.push_back(std::sqrt(d));
  }
  // The file's sizes were checked before VTK read it (viz/FrameFileCheck.hpp), its values here: offsets that
  // never decrease and ids of points the piece has, which the picture indexes.
  vtkCellArray* lines = poly->GetLines();
  if (lines && !lines->IsValid())
    throw FrameReadError(
        fmt::format("render: {}: the lines' offsets decrease or overrun their connectivity", path.string()));
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; lines && cell < lines->GetNumberOfCells(); ++cell) {
    lines->GetCellAtId(cell, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= points)
        throw FrameReadError(fmt::format("render: {}: line {} names point {} of {}", path.string(), cell,
                                         ids->GetId(k), points));
    for (vtkIdType k = 0; k + 1 < ids->GetNumberOfIds(); ++k)
      trees.segments.push_back({int(ids->GetId(k)), int(ids->GetId(k + 1))});
  }
  return trees;
}

LeafPoints read_leaves(const fs::path& path) {
  const auto [reader, poly] = read_dataset<vtkPolyData, vtkXMLPolyDataReader, vtkXMLPPolyDataReader>(path);
  LeafPoints leaves;
  vtkDataArray* state = poly->GetPointData()->GetArray("state");
  vtkDataArray* size = poly->GetPointData()->GetArray("size");
  for (vtkIdType n = 0; n < poly->GetNumberOfPoints(); ++n) {
    double p[3];
    poly->GetPoint(n, p);
    leaves.position.push_back({p[0], p[1], p[2]});
    leaves.state.push_back(state ? std::uint8_t(state->GetComponent(n, 0)) : 0);
    leaves.size.push_back(size ? size->GetComponent(n, 0) : 0.0);
  }
  return leaves;
}

std::vector<io::PvdCollection::Entry> entries_of(const fs::path& pvd) {
  return fs::is_regular_file(pvd) ? io::read_pvd(pvd) : std::vector<io::PvdCollection::Entry>{};
}

// The file of `entries` at `time`: equal to the frame time as written (the same double), else empty.
fs::path file_at(const fs::path& folder, const std::vector<io::PvdCollection::Entry>& entries, double time) {
  for (const auto& e : entries)
    if (e.time == time) return folder / e.file;
  return {};
}

// The file of `entries` at `time`, else of the latest entry before it: an output written every N-th frame
// (output.vtk.trees_every, output.leaves.every) holds still between its frames instead of vanishing.
fs::path file_at_or_before(const fs::path& folder, const std::vector<io::PvdCollection::Entry>& entries,
                           double time) {
  const io::PvdCollection::Entry* latest = nullptr;
  for (const auto& e : entries)
    if (e.time <= time && (latest == nullptr || e.time >= latest->time)) latest = &e;
  return latest ? folder / latest->file : fs::path();
}

// The string value of `key` in the JSON text (its first "key": "value" pair, escapes taken as the character
// they escape); empty when there is none. Scanned by hand, not with std::regex, which recurses once a
// character: a long value would overflow the stack (as a long .pvd attribute did, io/PvdCollection.cpp).
std::string json_string_value(std::string_view json, const std::string& key) {
  const std::string quoted = fmt::format("\"{}\"", key);
  const auto skip_space = [&](std::size_t at) {
    while (at < json.size() && std::isspace(static_cast<unsigned char>(json[at]))) ++at;
    return at;
  };
  for (std::size_t at = json.find(quoted); at != std::string_view::npos; at = json.find(quoted, at + 1)) {
    std::size_t n = skip_space(at + quoted.size());
    if (n >= json.size() || json[n] != ':') continue;
    n = skip_space(n + 1);
    if (n >= json.size() || json[n] != '"') continue;
    std::string value;
    for (++n; n < json.size() && json[n] != '"'; ++n) {
      if (json[n] == '\\' && ++n == json.size()) break;
      value += json[n];
    }
    if (n < json.size()) return value;  // closed by its quote
  }
  return {};
}

}  // namespace

std::string scenario_name_of(const fs::path& folder) {
  if (std::ifstream json(folder / "run.json"); json) {
    std::ostringstream text;
    text << json.rdbuf();
    if (std::string name = json_string_value(text.str(), "scenario"); !name.empty()) return name;
  }
  // A run stopped hard writes no run.json; the scenario's copy was written first (io/writers/ManifestWriter).
  for (const auto& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".yaml") continue;
    try {
      std::ifstream file(entry.path(), std::ios::binary);
      std::ostringstream text;
      text << file.rdbuf();
      const YAML::Node root = io::load_yaml(text.str());
      if (root["scenario"] && root["scenario"].IsScalar()) return root["scenario"].as<std::string>();
    } catch (const YAML::Exception&) {
    }
  }
  return fs::absolute(folder).lexically_normal().filename().string();
}

std::vector<std::string> WindGrid::field_names() const {
  std::vector<std::string> names;
  for (const Array& a : arrays) {
    names.push_back(a.name);
    if (a.components == 3)
      for (const char* suffix : kComponentSuffix) names.push_back(a.name + suffix);
  }
  return names;
}

ScalarField WindGrid::field(const std::string& name) const {
  const std::size_t cells = std::size_t(this->cells[0]) * this->cells[1] * this->cells[2];
  for (const Array& a : arrays) {
    const ArrayMeaning* meaning = meaning_of(a.name);
    ScalarField out{name, meaning ? meaning->unit : "", meaning ? meaning->is_signed : true, {}};
    if (name == a.name) {
      if (a.components == 1) {
        out.values = a.values;
        return out;
      }
      out.values.resize(cells);
      for (std::size_t c = 0; c < cells; ++c) {
        const float* v = &a.values[3 * c];
        out.values[c] = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      }
      out.is_signed = false;
      return out;
    }
    for (int component = 0; a.components == 3 && component < 3; ++component) {
      if (name != a.name + kComponentSuffix[component]) continue;
      out.values.resize(cells);
      for (std::size_t c = 0; c < cells; ++c) out.values[c] = a.values[3 * c + component];
      out.is_signed = true;
      return out;
    }
  }
  throw std::invalid_argument(fmt::format("render: no field '{}' in {}: choose one of {}", name,
                                          file.string(), fmt::join(field_names(), ", ")));
}

RunFolder::RunFolder(fs::path folder) : folder_(std::move(folder)) {
  if (!fs::is_directory(folder_))
    throw std::invalid_argument(fmt::format("render: {}: expected a run's output folder", folder_.string()));
  const auto wind = entries_of(folder_ / "wind.pvd");
  const auto trees = entries_of(folder_ / "trees.pvd");
  const auto leaves = entries_of(folder_ / "leaves.pvd");
  const auto& leading = wind.empty() ? trees : wind;
  if (leading.empty())
    throw std::invalid_argument(
        fmt::format("render: {}: no frames: expected wind.pvd or trees.pvd listing at least one frame",
                    folder_.string()));
  for (const auto& entry : leading) {
    Frame frame;
    frame.index = int(frames_.size());
    frame.time = entry.time;
    frame.wind = file_at(folder_, wind, entry.time);
    frame.trees = file_at_or_before(folder_, trees, entry.time);
    frame.leaves = file_at_or_before(folder_, leaves, entry.time);
    frames_.push_back(frame);
  }
  scenario_name_ = scenario_name_of(folder_);
}

std::string describe_frames(const std::vector<RunFolder::Frame>& frames) {
  if (frames.empty()) return "no frames";
  return fmt::format("frames 0..{} (t = {:g} .. {:g} s)", frames.size() - 1, frames.front().time,
                     frames.back().time);
}

const RunFolder::Frame& RunFolder::select(std::optional<int> index, std::optional<double> time) const {
  if (index) {
    if (*index < 0 || *index >= int(frames_.size()))
      throw std::invalid_argument(
          fmt::format("render: --frame {}: {} holds {}", *index, folder_.string(), describe_frames(frames_)));
    return frames_[std::size_t(*index)];
  }
  if (time) {
    // Nearest frame, but not a time outside the run by more than half a frame interval.
    const double half_interval =
        frames_.size() > 1 ? 0.5 * (frames_.back().time - frames_.front().time) / (frames_.size() - 1) : 0.0;
    if (!std::isfinite(*time) || *time < frames_.front().time - half_interval ||
        *time > frames_.back().time + half_interval)
      throw std::invalid_argument(
          fmt::format("render: --time {}: {} holds {}", *time, folder_.string(), describe_frames(frames_)));
    return *std::min_element(frames_.begin(), frames_.end(), [&](const Frame& a, const Frame& b) {
      return std::abs(a.time - *time) < std::abs(b.time - *time);
    });
  }
  return frames_.back();
}

FrameData RunFolder::load(const Frame& frame) const {
  FrameData data;
  data.index = frame.index;
  data.time = frame.time;
  if (!frame.wind.empty()) data.wind = read_wind(frame.wind);
  if (!frame.trees.empty()) data.trees = read_trees(frame.trees);
  if (!frame.leaves.empty()) data.leaves = read_leaves(frame.leaves);
  return data;
}

FrameData RunFolder::load_last_complete(const Frame& frame, std::string* note) const {
  std::string first_error;
  for (int n = frame.index; n >= 0; --n) {
    try {
      FrameData data = load(frames_[std::size_t(n)]);
      if (note && n != frame.index)
        *note =
            fmt::format("frame {} does not read ({}); rendering frame {} (t = {:g} s), the last complete one",
                        frame.index, first_error, n, frames_[std::size_t(n)].time);
      return data;
    } catch (const FrameReadError& e) {
      if (first_error.empty()) first_error = e.what();
    }
  }
  throw FrameReadError(
      fmt::format("render: {}: no frame up to {} reads: {}", folder_.string(), frame.index, first_error));
}

}  // namespace fw::viz
