#include "viz/RunFolder.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLImageDataReader.h>
#include <vtkXMLPImageDataReader.h>
#include <vtkXMLPPolyDataReader.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "io/PvdCollection.hpp"
#include "io/YamlDocuments.hpp"

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

// VTK's XML readers report a damaged file through error messages (theirs and their XML parser's), not
// through their return values. While a file is read, this output window collects them instead of printing
// them, so that load() can say which file failed and why, once.
class CapturedOutput : public vtkOutputWindow {
 public:
  static CapturedOutput* New() { return new CapturedOutput; }
  void DisplayText(const char* text) override {
    if (text && errors.empty()) errors = text;
  }
  std::string errors;
};

class ScopedOutputCapture {
 public:
  // VTK logs every error to stderr through vtkLogger as well as to the output window: silence both.
  ScopedOutputCapture()
      : previous_(vtkOutputWindow::GetInstance()), verbosity_(vtkLogger::GetCurrentVerbosityCutoff()) {
    vtkOutputWindow::SetInstance(captured_);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  }
  ~ScopedOutputCapture() {
    vtkLogger::SetStderrVerbosity(verbosity_);
    vtkOutputWindow::SetInstance(previous_);
  }
  const std::string& errors() const { return captured_->errors; }

 private:
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkLogger::Verbosity verbosity_;
  vtkNew<CapturedOutput> captured_;
};

std::string first_line(const std::string& text) {
  std::string line = text.substr(0, text.find('\n'));
  return line.empty() ? "read error" : line;
}

// Whether `element` or one nested in it is a DataArray in VTK's ascii format. forestwind writes appended
// binary (io/VtkXml) and render reads no other: VTK 9.1 reads past an ascii array that holds fewer values
// than its piece has cells or points, a null dereference in vtkXMLDataReader::ReadPieceData seen under ASan
// (tests/fuzz/run_folder_fuzz; docs/fuzzing.md).
bool holds_ascii_array(vtkXMLDataElement* element) {
  if (!element) return false;
  const char* format = element->GetAttribute("format");
  if (format && std::string_view(format) == "ascii") return true;
  for (int n = 0; n < element->GetNumberOfNestedElements(); ++n)
    if (holds_ascii_array(element->GetNestedElement(n))) return true;
  return false;
}

// VTK's appended blocks, raw, little-endian, UInt64 headers (as io/VtkXml writes them): with a compressor a
// header is [blocks, block size, last block size, each block's compressed size], else [bytes]. VTK allocates
// what a header claims before it reads a byte, so a corrupt one asked for terabytes
// (tests/fuzz/run_folder_fuzz). LZ4 and zlib expand no block by more than kMaxExpansion.
constexpr std::uint64_t kMaxExpansion = 256;
// A header's block size is nominal (VTK's writers use 32 KiB) and may exceed a short array's bytes.
constexpr std::uint64_t kNominalBlockBytes = std::uint64_t(1) << 20;

std::optional<std::uint64_t> read_u64(std::ifstream& file, std::uint64_t at) {
  std::uint64_t value = 0;
  file.seekg(std::streamoff(at));
  if (!file.read(reinterpret_cast<char*>(&value), sizeof value)) return std::nullopt;
  return value;
}

// Whether every appended array's header fits the file: its blocks within the bytes left, and what they expand
// to within what compression can give. Files of another header type, byte order or encoding are left to VTK.
bool appended_headers_fit(const fs::path& path, vtkXMLDataParser* parser) {
  vtkXMLDataElement* root = parser->GetRootElement();
  const char* header = root ? root->GetAttribute("header_type") : nullptr;
  const char* order = root ? root->GetAttribute("byte_order") : nullptr;
  if (!header || std::string_view(header) != "UInt64" || !order || std::string_view(order) != "LittleEndian")
    return true;
  vtkXMLDataElement* appended = root->FindNestedElementWithName("AppendedData");
  const char* encoding = appended ? appended->GetAttribute("encoding") : nullptr;
  if (!encoding || std::string_view(encoding) != "raw") return true;
  const bool compressed = root->GetAttribute("compressor") != nullptr;
  std::error_code error;
  const std::uint64_t size = fs::file_size(path, error),
                      start = std::uint64_t(parser->GetAppendedDataPosition());
  if (error || start > size) return false;
  std::ifstream file(path, std::ios::binary);
  const std::function<bool(vtkXMLDataElement*)> fits = [&](vtkXMLDataElement* element) -> bool {
    const char* format = element->GetAttribute("format");
    const char* offset = element->GetAttribute("offset");
    if (format && std::string_view(format) == "appended" && offset) {
      const std::uint64_t at = start + std::strtoull(offset, nullptr, 10);
      const auto first = read_u64(file, at);
      if (!first) return false;
      const std::uint64_t left = size - std::min(size, at + sizeof(std::uint64_t));
      if (!compressed) return *first <= left;
      const auto block = read_u64(file, at + 8), last = read_u64(file, at + 16);
      if (!block || !last || *first > left / sizeof(std::uint64_t)) return false;
      std::uint64_t stored = 0;
      for (std::uint64_t b = 0; b < *first; ++b) {
        const auto bytes = read_u64(file, at + 24 + 8 * b);
        if (!bytes || *bytes > left) return false;
        stored += *bytes;
      }
      // What the blocks expand to: all full but the last, whose size 0 means full too.
      const std::uint64_t expanded = *first == 0 ? 0 : (*first - 1) * *block + (*last ? *last : *block);
      if (stored > left || expanded > kMaxExpansion * (stored + 1) ||
          *block > std::max(expanded, kNominalBlockBytes) || *last > *block)
        return false;
    }
    for (int n = 0; n < element->GetNumberOfNestedElements(); ++n)
      if (!fits(element->GetNestedElement(n))) return false;
    return true;
  };
  return fits(root);
}

template <class Reader>
vtkSmartPointer<Reader> read_xml(const fs::path& path) {
  if (!fs::is_regular_file(path))
    throw std::runtime_error(fmt::format("render: {}: the file is missing", path.string()));
  ScopedOutputCapture capture;
  auto reader = vtkSmartPointer<Reader>::New();
  if (!reader->CanReadFile(path.string().c_str()))
    throw std::runtime_error(
        fmt::format("render: {}: not a VTK XML file of the expected type", path.string()));
  // The XML is parsed here first, and its arrays checked, because VTK reads some arrays (the field data)
  // while it gathers the file's information, before any array could be checked through the reader.
  vtkNew<vtkXMLDataParser> parser;
  std::ifstream stream(path, std::ios::binary);
  parser->SetStream(&stream);
  if (!parser->Parse() || !parser->GetRootElement())
    throw std::runtime_error(
        fmt::format("render: {}: the file does not read: {}", path.string(), first_line(capture.errors())));
  if (holds_ascii_array(parser->GetRootElement()))
    throw std::runtime_error(fmt::format(
        "render: {}: a data array in ascii format: appended binary expected, as forestwind writes",
        path.string()));
  if (!appended_headers_fit(path, parser))
    throw std::runtime_error(fmt::format(
        "render: {}: an appended data block's header claims more than the file holds", path.string()));
  reader->SetFileName(path.string().c_str());
  reader->Update();
  if (!capture.errors().empty() || reader->GetErrorCode() != 0)
    throw std::runtime_error(
        fmt::format("render: {}: the file does not read: {}", path.string(), first_line(capture.errors())));
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
  if (grid.cells[0] < 1 || grid.cells[1] < 1 || grid.cells[2] < 1 || !(grid.cell_size > 0.0))
    throw std::runtime_error(fmt::format("render: {}: expected a grid of cells, got {} x {} x {} points",
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
  vtkCellArray* lines = poly->GetLines();
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; lines && cell < lines->GetNumberOfCells(); ++cell) {
    lines->GetCellAtId(cell, ids);
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

std::string json_string_value(const std::string& json, const std::string& key) {
  const std::regex pattern("\"" + key + R"re("\s*:\s*"((?:[^"\\]|\\.)*)")re");
  std::smatch match;
  if (!std::regex_search(json, match, pattern)) return {};
  std::string out;
  const std::string raw = match[1].str();
  for (std::size_t n = 0; n < raw.size(); ++n)
    out += (raw[n] == '\\' && n + 1 < raw.size()) ? raw[++n] : raw[n];
  return out;
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
    } catch (const std::runtime_error& e) {
      if (first_error.empty()) first_error = e.what();
    }
  }
  throw std::runtime_error(
      fmt::format("render: {}: no frame up to {} reads: {}", folder_.string(), frame.index, first_error));
}

}  // namespace fw::viz
