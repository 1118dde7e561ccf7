#include "viz/FrameFileCheck.hpp"

#include <fmt/format.h>
#include <lz4.h>
#include <zlib.h>

#include <vtkNew.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <array>
#include <cctype>
#include <climits>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/TextNumber.hpp"
#include "viz/VtkErrorCapture.hpp"

namespace fw::viz {

namespace fs = std::filesystem;

namespace {

// The format version VTK 9.1's writers give image and poly data files (io/VtkXml), whose cell arrays store
// one end offset per cell.
constexpr std::string_view kVersion = "1.0";
// LZ4 and zlib expand no block by more than this: a header claiming more describes no file they wrote.
constexpr std::uint64_t kMaxExpansion = 256;
// A header's block size is nominal (VTK's writers use 32 KiB) and may exceed a short array's bytes.
constexpr std::uint64_t kNominalBlockBytes = std::uint64_t(1) << 20;
// Counts past these describe no grid or forest a device holds (2^40 points is 4 TiB of float32 alone); the
// bounds keep every product of count, components and value bytes within 64 bits (2^40 * 2^10 * 8 = 2^53).
constexpr long long kMaxCount = 1LL << 40;
constexpr long long kMaxComponents = 1LL << 10;
// A String array of <FieldData> (a site's CRS as WKT, an inventory's tree ids): each string with its
// terminating NUL, at most this long (a WKT2 of a projected CRS runs to 2-3 kB).
constexpr std::uint64_t kMaxStringBytes = std::uint64_t(1) << 16;
// The four cell arrays of a poly data piece, each with the attribute counting its cells.
constexpr std::array<std::pair<const char*, const char*>, 4> kPolyCells = {{{"Verts", "NumberOfVerts"},
                                                                            {"Lines", "NumberOfLines"},
                                                                            {"Strips", "NumberOfStrips"},
                                                                            {"Polys", "NumberOfPolys"}}};

struct ValueType {
  std::string_view name;
  int bytes;
  bool is_integer;
};
constexpr ValueType kValueTypes[] = {
    {"Int8", 1, true},     {"UInt8", 1, true},    {"Int16", 2, true}, {"UInt16", 2, true},
    {"Int32", 4, true},    {"UInt32", 4, true},   {"Int64", 8, true}, {"UInt64", 8, true},
    {"Float32", 4, false}, {"Float64", 8, false},
};

enum class Compressor { none, lz4, zlib };

[[noreturn]] void refuse(const fs::path& path, const std::string& what) {
  throw FrameReadError(fmt::format("render: {}: {}", path.string(), what));
}

bool is(const char* value, std::string_view expected) {
  return value && expected == value;
}

// The whole numbers of `text`, separated by white space; nullopt when anything else is in it.
std::optional<std::vector<long long>> integers_of(const char* text) {
  if (!text) return std::nullopt;
  std::vector<long long> values;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    const std::optional<long long> value = base::parse_number<long long>(word);
    if (!value) return std::nullopt;
    values.push_back(*value);
  }
  return values;
}

// Points and cells of an image extent [x0 x1 y0 y1 z0 z1], counted as vtkStructuredData does.
struct Extent {
  std::array<long long, 6> bounds{};
  std::uint64_t points() const {
    std::uint64_t n = 1;
    for (int a = 0; a < 3; ++a) n *= std::uint64_t(bounds[2 * a + 1] - bounds[2 * a] + 1);
    return n;
  }
  std::uint64_t cells() const {
    std::uint64_t n = 1;
    for (int a = 0; a < 3; ++a)
      if (bounds[2 * a + 1] > bounds[2 * a]) n *= std::uint64_t(bounds[2 * a + 1] - bounds[2 * a]);
    return n;
  }
  bool within(const Extent& outer) const {
    for (int a = 0; a < 3; ++a)
      if (bounds[2 * a] < outer.bounds[2 * a] || bounds[2 * a + 1] > outer.bounds[2 * a + 1]) return false;
    return true;
  }
  std::string text() const { return fmt::format("{}", fmt::join(bounds, " ")); }
};

// The bytes after <AppendedData encoding="raw">'s '_', where each data array is a UInt64 little-endian
// header and its blocks: with a compressor [blocks, block size, last block size (0: full), each block's
// stored size] then the stored blocks, without one [bytes] then the bytes.
class AppendedBlocks {
 public:
  AppendedBlocks(const fs::path& path, std::uint64_t start, Compressor compressor)
      : path_(path), file_(path, std::ios::binary), start_(start), compressor_(compressor) {
    std::error_code error;
    size_ = fs::file_size(path, error);
    if (error || start_ > size_) refuse(path_, "the appended data begins past the end of the file");
  }

  /// What the array at `offset` expands to; refuses a header that does not fit the file.
  std::uint64_t expanded_bytes(std::uint64_t offset) { return header_at(offset).expanded; }

  /// The last value, of `bytes` bytes, of the array at `offset`, decoded (little-endian, unsigned).
  std::uint64_t last_value(std::uint64_t offset, int bytes) {
    const Header header = header_at(offset);
    if (header.expanded < std::uint64_t(bytes)) refuse(path_, "an array's last value is past its bytes");
    std::vector<char> block;
    if (compressor_ == Compressor::none) {
      block = read(header.data_at + header.expanded - std::uint64_t(bytes), std::uint64_t(bytes));
    } else {
      std::uint64_t at = header.data_at;
      for (std::size_t b = 0; b + 1 < header.stored.size(); ++b) at += header.stored[b];
      const std::uint64_t expanded = header.last ? header.last : header.block;
      if (expanded > kMaxExpansion * (header.stored.back() + 1))
        refuse(path_, "an array's last block claims more than compression can give");
      block = expand(read(at, header.stored.back()), expanded);
    }
    if (block.size() < std::size_t(bytes)) refuse(path_, "an array's last block holds part of a value");
    std::uint64_t value = 0;
    for (int k = 0; k < bytes; ++k)
      value |= std::uint64_t(static_cast<unsigned char>(block[block.size() - std::size_t(bytes) + k]))
               << (8 * k);
    return value;
  }

 private:
  struct Header {
    std::uint64_t block = 0, last = 0, expanded = 0, data_at = 0;
    std::vector<std::uint64_t> stored;  // each block's stored size
  };

  std::uint64_t u64_at(std::uint64_t at) {
    const std::vector<char> bytes = read(at, sizeof(std::uint64_t));
    std::uint64_t value = 0;
    for (std::size_t k = 0; k < bytes.size(); ++k)
      value |= std::uint64_t(static_cast<unsigned char>(bytes[k])) << (8 * k);
    return value;
  }

  std::vector<char> read(std::uint64_t at, std::uint64_t count) {
    if (at > size_ || count > size_ - at)
      refuse(path_, "an appended data block reaches past the end of the file");
    std::vector<char> bytes(count);
    file_.clear();
    file_.seekg(std::streamoff(at));
    if (!file_.read(bytes.data(), std::streamsize(count))) refuse(path_, "the appended data cannot be read");
    return bytes;
  }

  std::vector<char> expand(const std::vector<char>& stored, std::uint64_t expected) {
    std::vector<char> out(expected);
    bool whole = false;
    if (compressor_ == Compressor::lz4) {
      if (stored.size() > std::size_t(INT_MAX) || expected > std::uint64_t(INT_MAX))
        refuse(path_, "an LZ4 block larger than LZ4 handles");
      const int made = LZ4_decompress_safe(stored.data(), out.data(), int(stored.size()), int(expected));
      whole = made >= 0 && std::uint64_t(made) == expected;
    } else {
      uLongf made = uLongf(expected);
      whole = uncompress(reinterpret_cast<Bytef*>(out.data()), &made,
                         reinterpret_cast<const Bytef*>(stored.data()), uLong(stored.size())) == Z_OK &&
              made == expected;
    }
    if (!whole) refuse(path_, "a compressed block does not expand to the size its header gives");
    return out;
  }

  Header header_at(std::uint64_t offset) {
    if (offset > size_ - start_) refuse(path_, "a data array's offset is past the end of the file");
    const std::uint64_t at = start_ + offset;
    Header header;
    if (compressor_ == Compressor::none) {
      header.expanded = u64_at(at);
      header.data_at = at + sizeof(std::uint64_t);
      if (header.expanded > size_ - std::min(size_, header.data_at))
        refuse(path_, "a data array's header claims more bytes than the file holds");
      return header;
    }
    const std::uint64_t blocks = u64_at(at);
    header.block = u64_at(at + 8);
    header.last = u64_at(at + 16);
    const std::uint64_t left = size_ - std::min(size_, at + 24);
    if (blocks > left / sizeof(std::uint64_t))
      refuse(path_, "a data array's header lists more blocks than the file holds");
    header.data_at = at + 24 + 8 * blocks;
    std::uint64_t stored = 0;
    for (std::uint64_t b = 0; b < blocks; ++b) {
      header.stored.push_back(u64_at(at + 24 + 8 * b));
      if (header.stored.back() > left) refuse(path_, "a data array's block is larger than the file");
      stored += header.stored.back();
    }
    // VTK computes an array's size as blocks x block size, less what the last block lacks: a header listing
    // no block but a partial last one makes that negative, and VTK then reads a block that is not there.
    if (blocks == 0 ? header.last != 0 : header.block == 0 || header.last > header.block)
      refuse(path_, "a data array's block header is inconsistent");
    header.expanded =
        blocks == 0 ? 0 : (blocks - 1) * header.block + (header.last ? header.last : header.block);
    if (stored > size_ - std::min(size_, header.data_at) || header.expanded > kMaxExpansion * (stored + 1) ||
        header.block > std::max(header.expanded, kNominalBlockBytes))
      refuse(path_, "a data array's block header claims more than the file holds");
    return header;
  }

  fs::path path_;
  std::ifstream file_;
  std::uint64_t start_ = 0, size_ = 0;
  Compressor compressor_;
};

// One frame file: its parsed XML and, once an array asks, its appended blocks.
class FrameFile {
 public:
  explicit FrameFile(const fs::path& path) : path_(path), stream_(path, std::ios::binary) {
    VtkErrorCapture capture;
    parser_->SetStream(&stream_);
    if (!stream_ || !parser_->Parse() || !parser_->GetRootElement())
      refuse(path_, "the file does not read: " + capture.first_error());
  }

  const fs::path& path() const { return path_; }
  vtkXMLDataElement* root() const { return parser_->GetRootElement(); }

  // The one non-negative count in attribute `name` of `element`; `absent` when it has none.
  long long count(vtkXMLDataElement* element, const char* name, std::optional<long long> absent,
                  long long most = kMaxCount) const {
    const char* text = element->GetAttribute(name);
    if (!text && absent) return *absent;
    const auto values = integers_of(text);
    if (!values || values->size() != 1 || values->front() < 0 || values->front() > most)
      refuse(path_, fmt::format("<{} {}>: a whole number from 0 to {} expected, got '{}'", element->GetName(),
                                name, most, text ? text : "(none)"));
    return values->front();
  }

  Extent extent(vtkXMLDataElement* element, const char* name) const {
    const char* text = element->GetAttribute(name);
    const auto values = integers_of(text);
    Extent extent;
    bool ok = values && values->size() == 6;
    for (int k = 0; ok && k < 6; ++k) {
      extent.bounds[std::size_t(k)] = (*values)[std::size_t(k)];
      ok = extent.bounds[std::size_t(k)] >= INT_MIN && extent.bounds[std::size_t(k)] <= INT_MAX;
    }
    for (int a = 0; ok && a < 3; ++a)
      ok = extent.bounds[std::size_t(2 * a + 1)] - extent.bounds[std::size_t(2 * a)] < kMaxCount &&
           extent.bounds[std::size_t(2 * a + 1)] >= extent.bounds[std::size_t(2 * a)];
    // The product in double first: with each side below 2^40, that of integers could overflow.
    double points = 1.0;
    for (int a = 0; ok && a < 3; ++a)
      points *= double(extent.bounds[std::size_t(2 * a + 1)] - extent.bounds[std::size_t(2 * a)] + 1);
    ok = ok && points <= double(kMaxCount);
    if (!ok)
      refuse(
          path_,
          fmt::format("<{} {}>: six whole numbers x0 x1 y0 y1 z0 z1 with each min <= max expected, got '{}'",
                      element->GetName(), name, text ? text : "(none)"));
    return extent;
  }

  /// Checks the header of the serial file (encoding, version) and returns its dataset element.
  vtkXMLDataElement* serial_dataset(std::string_view type) {
    vtkXMLDataElement* root = this->root();
    if (!is(root->GetName(), "VTKFile") || !is(root->GetAttribute("type"), type))
      refuse(path_, fmt::format("a VTKFile of type {} expected", type));
    if (!is(root->GetAttribute("version"), kVersion) ||
        !is(root->GetAttribute("byte_order"), "LittleEndian") ||
        !is(root->GetAttribute("header_type"), "UInt64"))
      refuse(path_,
             fmt::format("VTK XML version {}, LittleEndian, header_type UInt64 expected, as forestwind "
                         "writes",
                         kVersion));
    const char* compressor = root->GetAttribute("compressor");
    if (!compressor)
      compressor_ = Compressor::none;
    else if (is(compressor, "vtkLZ4DataCompressor"))
      compressor_ = Compressor::lz4;
    else if (is(compressor, "vtkZLibDataCompressor"))
      compressor_ = Compressor::zlib;
    else
      refuse(path_, fmt::format("compressor {}: vtkLZ4DataCompressor, vtkZLibDataCompressor or none expected",
                                compressor));
    vtkXMLDataElement* dataset = nullptr;
    for (int n = 0; n < root->GetNumberOfNestedElements(); ++n) {
      vtkXMLDataElement* element = root->GetNestedElement(n);
      if (is(element->GetName(), type) && !dataset)
        dataset = element;
      else if (!is(element->GetName(), "AppendedData"))
        refuse(path_, fmt::format("<{}> in <VTKFile>: one <{}> and <AppendedData> expected",
                                  element->GetName(), type));
    }
    if (!dataset) refuse(path_, fmt::format("no <{}> element", type));
    return dataset;
  }

  /// Checks one data array, whose size must be `tuples` tuples; returns its element.
  void check_array(vtkXMLDataElement* array, std::uint64_t tuples, bool single_integer = false) {
    const char* name = array->GetAttribute("Name");
    const std::string label = fmt::format("data array '{}'", name ? name : "(unnamed)");
    if (!is(array->GetName(), "DataArray"))
      refuse(path_, fmt::format("<{}>: only <DataArray> elements expected there", array->GetName()));
    if (!name || !*name) refuse(path_, "a data array without a Name");
    if (!is(array->GetAttribute("format"), "appended"))
      refuse(path_,
             fmt::format("{}: format appended expected (raw binary, as forestwind writes), got {}", label,
                         array->GetAttribute("format") ? array->GetAttribute("format") : "none"));
    const ValueType* type = value_type(array->GetAttribute("type"));
    if (!type)
      refuse(path_, fmt::format("{}: a numeric type (Int8 .. UInt64, Float32, Float64) expected", label));
    const long long components = count(array, "NumberOfComponents", 1, kMaxComponents);
    if (components < 1 || (single_integer && (components != 1 || !type->is_integer)))
      refuse(path_, fmt::format("{}: {} expected", label,
                                single_integer ? "one integer component" : "at least one component"));
    const std::uint64_t expected = tuples * std::uint64_t(components) * std::uint64_t(type->bytes);
    const std::uint64_t holds =
        blocks().expanded_bytes(std::uint64_t(count(array, "offset", std::nullopt, LLONG_MAX)));
    if (holds != expected)
      refuse(path_,
             fmt::format("{}: its block holds {} bytes, its piece's counts give {} ({} tuples of {} x {})",
                         label, holds, expected, tuples, components, type->name));
  }

  /// Checks every array nested in `group` (<PointData>, <CellData>, <Points>) against `tuples` tuples.
  void check_arrays(vtkXMLDataElement* group, std::uint64_t tuples) {
    for (int n = 0; group && n < group->GetNumberOfNestedElements(); ++n)
      check_array(group->GetNestedElement(n), tuples);
    check_names_unique(group);
  }

  /// Checks the arrays of <FieldData>, each of the tuples it declares; a String array's block holds one to
  /// kMaxStringBytes bytes a string.
  void check_field_data(vtkXMLDataElement* field) {
    for (int n = 0; n < field->GetNumberOfNestedElements(); ++n) {
      vtkXMLDataElement* array = field->GetNestedElement(n);
      const auto tuples = std::uint64_t(count(array, "NumberOfTuples", std::nullopt));
      if (is(array->GetAttribute("type"), "String"))
        check_string_array(array, tuples);
      else
        check_array(array, tuples);
    }
    check_names_unique(field);
  }

  void check_string_array(vtkXMLDataElement* array, std::uint64_t tuples) {
    const char* name = array->GetAttribute("Name");
    if (!name || !*name) refuse(path_, "a data array without a Name");
    const std::string label = fmt::format("string array '{}'", name);
    if (!is(array->GetAttribute("format"), "appended"))
      refuse(path_, fmt::format("{}: format appended expected (raw binary, as forestwind writes)", label));
    if (count(array, "NumberOfComponents", 1, 1) != 1)
      refuse(path_, fmt::format("{}: one component expected", label));
    const std::uint64_t holds =
        blocks().expanded_bytes(std::uint64_t(count(array, "offset", std::nullopt, LLONG_MAX)));
    if (holds < tuples || holds > tuples * kMaxStringBytes)
      refuse(path_, fmt::format("{}: its block holds {} bytes, for {} strings of 1 to {} bytes", label, holds,
                                tuples, kMaxStringBytes));
  }

  /// Refuses two arrays of one name in `group`: VTK's dataset keeps one array a name, while its reader
  /// counts the file's, and reads the second into an array that is not there (a null dereference in
  /// vtkXMLStructuredDataReader::ReadSubExtent; tests/fuzz/run_folder_fuzz).
  void check_names_unique(vtkXMLDataElement* group) const {
    std::set<std::string_view> names;
    for (int n = 0; group && n < group->GetNumberOfNestedElements(); ++n) {
      const char* name = group->GetNestedElement(n)->GetAttribute("Name");
      if (name && !names.insert(name).second)
        refuse(path_, fmt::format("<{}>: two data arrays named '{}'", group->GetName(), name));
    }
  }

  /// Checks a cell array's offsets (one end offset per cell) and connectivity (as many ids as the last one).
  void check_cells(vtkXMLDataElement* group, std::uint64_t cells) {
    vtkXMLDataElement* offsets = nullptr;
    vtkXMLDataElement* connectivity = nullptr;
    for (int n = 0; group && n < group->GetNumberOfNestedElements(); ++n) {
      vtkXMLDataElement* array = group->GetNestedElement(n);
      if (is(array->GetAttribute("Name"), "offsets") && !offsets)
        offsets = array;
      else if (is(array->GetAttribute("Name"), "connectivity") && !connectivity)
        connectivity = array;
      else
        refuse(path_, fmt::format("<{}>: one offsets and one connectivity array expected", group->GetName()));
    }
    if (cells == 0 && !offsets && !connectivity) return;
    if (!offsets || !connectivity)
      refuse(path_, fmt::format("<{}>: its cells need an offsets and a connectivity array",
                                group ? group->GetName() : "cells"));
    check_array(offsets, cells, true);
    std::uint64_t ids = 0;
    if (cells > 0) {
      const ValueType* type = value_type(offsets->GetAttribute("type"));
      const std::uint64_t last =
          blocks().last_value(std::uint64_t(count(offsets, "offset", std::nullopt, LLONG_MAX)), type->bytes);
      const bool negative = type->name.front() == 'I' && (last >> (8 * type->bytes - 1)) != 0;
      if (negative || last > std::uint64_t(kMaxCount))
        refuse(path_, fmt::format("<{}>: the last offset is not a count of point ids", group->GetName()));
      ids = last;
    }
    check_array(connectivity, ids, true);
  }

 private:
  static const ValueType* value_type(const char* name) {
    for (const ValueType& type : kValueTypes)
      if (is(name, type.name)) return &type;
    return nullptr;
  }

  AppendedBlocks& blocks() {
    if (!blocks_) {
      vtkXMLDataElement* appended = root()->FindNestedElementWithName("AppendedData");
      if (!appended || !is(appended->GetAttribute("encoding"), "raw"))
        refuse(path_, "appended arrays need <AppendedData encoding=\"raw\">, as forestwind writes");
      blocks_.emplace(path_, std::uint64_t(parser_->GetAppendedDataPosition()), compressor_);
    }
    return *blocks_;
  }

  fs::path path_;
  std::ifstream stream_;
  vtkNew<vtkXMLDataParser> parser_;
  Compressor compressor_ = Compressor::none;
  std::optional<AppendedBlocks> blocks_;
};

// Checks that the only elements nested in `element` are of the given names.
void check_children(const FrameFile& file, vtkXMLDataElement* element,
                    std::initializer_list<std::string_view> allowed) {
  for (int n = 0; n < element->GetNumberOfNestedElements(); ++n) {
    const char* name = element->GetNestedElement(n)->GetName();
    bool known = false;
    for (std::string_view a : allowed) known = known || is(name, a);
    if (!known)
      refuse(file.path(), fmt::format("<{}> in <{}>: only {} expected there", name, element->GetName(),
                                      fmt::join(allowed, ", ")));
  }
}

// The one piece of a serial file, its field data checked. forestwind writes one piece a file (a rank's block
// in a file of its own); VTK sizes the arrays of a file of several by the first piece's, over all of them.
vtkXMLDataElement* single_piece(FrameFile& file, vtkXMLDataElement* dataset) {
  check_children(file, dataset, {"FieldData", "Piece"});
  vtkXMLDataElement* piece = nullptr;
  for (int n = 0; n < dataset->GetNumberOfNestedElements(); ++n) {
    vtkXMLDataElement* element = dataset->GetNestedElement(n);
    if (is(element->GetName(), "FieldData")) {
      file.check_field_data(element);
    } else if (piece) {
      refuse(file.path(), "more than one <Piece>: one expected, as forestwind writes");
    } else {
      piece = element;
    }
  }
  if (!piece) refuse(file.path(), "no <Piece>");
  return piece;
}

// An array a parallel summary declares (<PDataArray>), which VTK allocates over the whole dataset with the
// summary's type and components: each piece must hold it so.
struct DeclaredArray {
  std::string group;  // PointData, CellData or Points
  std::string name, type;
  long long components = 1;
};

std::vector<DeclaredArray> declared_arrays(const FrameFile& file, vtkXMLDataElement* summary) {
  std::vector<DeclaredArray> arrays;
  for (int n = 0; n < summary->GetNumberOfNestedElements(); ++n) {
    vtkXMLDataElement* group = summary->GetNestedElement(n);
    const std::string_view name = group->GetName();
    if (name != "PPointData" && name != "PCellData" && name != "PPoints") continue;
    for (int k = 0; k < group->GetNumberOfNestedElements(); ++k) {
      vtkXMLDataElement* array = group->GetNestedElement(k);
      const char* array_name = array->GetAttribute("Name");
      const char* type = array->GetAttribute("type");
      arrays.push_back({std::string(name.substr(1)), array_name ? array_name : "", type ? type : "",
                        file.count(array, "NumberOfComponents", 1, kMaxComponents)});
    }
  }
  return arrays;
}

void check_holds_declared(const FrameFile& file, vtkXMLDataElement* piece,
                          const std::vector<DeclaredArray>& declared) {
  for (const DeclaredArray& d : declared) {
    vtkXMLDataElement* group = piece->FindNestedElementWithName(d.group.c_str());
    bool held = false;
    for (int n = 0; group && n < group->GetNumberOfNestedElements() && !held; ++n) {
      vtkXMLDataElement* array = group->GetNestedElement(n);
      held = (d.group == "Points" || is(array->GetAttribute("Name"), d.name)) &&
             is(array->GetAttribute("type"), d.type) &&
             file.count(array, "NumberOfComponents", 1, kMaxComponents) == d.components;
    }
    if (!held)
      refuse(file.path(),
             fmt::format("its summary declares {} array '{}' ({} x {}), which it does not hold so", d.group,
                         d.name, d.components, d.type));
  }
}

// A serial .vti. As a piece of a .pvti: `extent` is what the summary gives it, and `declared` its arrays.
void check_image(const fs::path& path, const std::optional<Extent>& extent,
                 const std::vector<DeclaredArray>& declared) {
  FrameFile file(path);
  vtkXMLDataElement* image = file.serial_dataset("ImageData");
  const Extent whole = file.extent(image, "WholeExtent");
  if (extent && whole.bounds != extent->bounds)
    refuse(path, fmt::format("its whole extent {} is not the extent {} its summary gives it", whole.text(),
                             extent->text()));
  vtkXMLDataElement* piece = single_piece(file, image);
  // VTK allocates the whole extent's arrays: the piece must hold all of it.
  if (file.extent(piece, "Extent").bounds != whole.bounds)
    refuse(path, fmt::format("its piece's extent is not its whole extent {}", whole.text()));
  check_children(file, piece, {"PointData", "CellData"});
  file.check_arrays(piece->FindNestedElementWithName("PointData"), whole.points());
  file.check_arrays(piece->FindNestedElementWithName("CellData"), whole.cells());
  check_holds_declared(file, piece, declared);
}

// A serial .vtp. As a piece of a .pvtp: `declared` is its summary's arrays.
void check_poly(const fs::path& path, const std::vector<DeclaredArray>& declared) {
  FrameFile file(path);
  vtkXMLDataElement* piece = single_piece(file, file.serial_dataset("PolyData"));
  check_children(file, piece, {"PointData", "CellData", "Points", "Verts", "Lines", "Strips", "Polys"});
  const auto points = std::uint64_t(file.count(piece, "NumberOfPoints", 0));
  std::uint64_t cells = 0;
  for (const auto& [group, attribute] : kPolyCells) {
    const auto count = std::uint64_t(file.count(piece, attribute, 0));
    file.check_cells(piece->FindNestedElementWithName(group), count);
    cells += count;
  }
  vtkXMLDataElement* coordinates = piece->FindNestedElementWithName("Points");
  if (points > 0 && (!coordinates || coordinates->GetNumberOfNestedElements() != 1))
    refuse(path, "a piece with points needs <Points> with one data array");
  if (coordinates && coordinates->GetNumberOfNestedElements() > 0 &&
      file.count(coordinates->GetNestedElement(0), "NumberOfComponents", 1) != 3)
    refuse(path, "<Points>: three components expected");
  file.check_arrays(coordinates, points);
  file.check_arrays(piece->FindNestedElementWithName("PointData"), points);
  file.check_arrays(piece->FindNestedElementWithName("CellData"), cells);
  check_holds_declared(file, piece, declared);
}

// A .pvti or .pvtp summary and each piece it names.
void check_summary(const fs::path& path, std::string_view type) {
  FrameFile file(path);
  const std::string parallel = fmt::format("P{}", type);
  vtkXMLDataElement* root = file.root();
  if (!is(root->GetName(), "VTKFile") || !is(root->GetAttribute("type"), parallel))
    refuse(path, fmt::format("a VTKFile of type {} expected", parallel));
  vtkXMLDataElement* summary = root->FindNestedElementWithName(parallel.c_str());
  if (!summary) refuse(path, fmt::format("no <{}> element", parallel));
  const std::vector<DeclaredArray> declared = declared_arrays(file, summary);
  for (std::size_t a = 0; a < declared.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (declared[a].group == declared[b].group && declared[a].name == declared[b].name)
        refuse(path,
               fmt::format("it declares two {} arrays named '{}'", declared[a].group, declared[a].name));
  const bool image = type == "ImageData";
  std::optional<Extent> whole;
  if (image) whole = file.extent(summary, "WholeExtent");
  std::uint64_t covered = 0;
  int pieces = 0;
  for (int n = 0; n < summary->GetNumberOfNestedElements(); ++n) {
    vtkXMLDataElement* piece = summary->GetNestedElement(n);
    if (!is(piece->GetName(), "Piece")) continue;
    const char* source = piece->GetAttribute("Source");
    if (!source || !*source) refuse(path, "a <Piece> without its Source file");
    const fs::path piece_path = path.parent_path() / source;
    if (!fs::is_regular_file(piece_path))
      refuse(path, fmt::format("piece {} is missing", piece_path.string()));
    ++pieces;
    if (!image) {
      check_poly(piece_path, declared);
      continue;
    }
    const Extent extent = file.extent(piece, "Extent");
    if (!extent.within(*whole))
      refuse(path, fmt::format("piece {}'s extent {} is outside the whole extent {}", source, extent.text(),
                               whole->text()));
    check_image(piece_path, extent, declared);
    covered += extent.points();
  }
  if (pieces == 0) refuse(path, "a summary that names no piece");
  // VTK allocates the declared arrays over the whole extent: the pieces must hold at least as many points.
  if (image && covered < whole->points())
    refuse(path, fmt::format("its pieces do not cover its whole extent {}", whole->text()));
}

}  // namespace

void check_frame_file(const fs::path& path) {
  const std::string extension = path.extension().string();
  if (extension == ".vti")
    check_image(path, std::nullopt, {});
  else if (extension == ".vtp")
    check_poly(path, {});
  else if (extension == ".pvti")
    check_summary(path, "ImageData");
  else if (extension == ".pvtp")
    check_summary(path, "PolyData");
  else
    refuse(path, "a .vti, .vtp, .pvti or .pvtp file expected");
}

}  // namespace fw::viz
