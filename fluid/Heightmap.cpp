#include "fluid/Heightmap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "base/TextNumber.hpp"

namespace fw::fluid {
namespace {

// Caps the allocation a corrupt header could ask for (2^28 doubles = 2 GiB).
constexpr std::int64_t kMaxSamples = std::int64_t(1) << 28;

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

// Tokens go into error messages; a binary file must not fill the terminal with garbage.
std::string printable(std::string_view token) {
  constexpr std::size_t kMax = 32;
  std::string out;
  for (char c : token.substr(0, kMax)) out += std::isprint(static_cast<unsigned char>(c)) ? c : '?';
  if (token.size() > kMax) out += "...";
  return out;
}

struct Token {
  std::string_view text;
  int line = 0;  // 1-based
};

// Whitespace-separated tokens with line numbers. PGM allows '#' comments to the end of the line; the sniff
// of the magic number reads without them.
class Scanner {
 public:
  Scanner(const std::string& path, std::string_view data, bool comments)
      : path_(path), data_(data), comments_(comments) {}

  std::optional<Token> next() {
    skip_space();
    if (pos_ >= data_.size()) return std::nullopt;
    const std::size_t start = pos_;
    while (pos_ < data_.size() && !is_space(data_[pos_]) && !(comments_ && data_[pos_] == '#')) ++pos_;
    last_line_ = line_;
    return Token{data_.substr(start, pos_ - start), line_};
  }

  std::optional<Token> peek() {
    const std::size_t pos = pos_;
    const int line = line_, last_line = last_line_;
    auto token = next();
    pos_ = pos;
    line_ = line;
    last_line_ = last_line;
    return token;
  }

  /// The next token, or an error "LINE: WHAT: expected EXPECTED, got end of file".
  Token require(std::string_view what, std::string_view expected) {
    auto token = next();
    if (!token) fail(last_line_, fmt::format("{}: expected {}, got end of file", what, expected));
    return *token;
  }

  [[noreturn]] void fail(int line, const std::string& message) const {
    throw std::runtime_error(fmt::format("{}:{}: {}", path_, line, message));
  }

  std::size_t pos() const { return pos_; }
  int line() const { return line_; }
  /// Line of the last token returned: where a file that ends too early ran out.
  int last_line() const { return last_line_; }
  std::string_view data() const { return data_; }

 private:
  void skip_space() {
    while (pos_ < data_.size()) {
      const char c = data_[pos_];
      if (c == '\n') {
        ++line_;
        ++pos_;
      } else if (is_space(c)) {
        ++pos_;
      } else if (comments_ && c == '#') {
        while (pos_ < data_.size() && data_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  const std::string& path_;
  std::string_view data_;
  bool comments_;
  std::size_t pos_ = 0;
  int line_ = 1;
  int last_line_ = 1;
};

std::int64_t parse_integer(Scanner& scan, const Token& token, std::string_view what, std::int64_t min,
                           std::int64_t max, std::string_view expected) {
  const auto value = base::parse_number<std::int64_t>(token.text);
  if (!value || *value < min || *value > max)
    scan.fail(token.line, fmt::format("{}: expected {}, got '{}'", what, expected, printable(token.text)));
  return *value;
}

void check_sample_count(Scanner& scan, int line, std::int64_t columns, std::int64_t rows) {
  if (columns * rows > kMaxSamples)
    scan.fail(line, fmt::format("expected at most {} samples, got {} x {}", kMaxSamples, columns, rows));
}

// The samples in storage order (row 0 = south) from the file's order (north row first).
std::vector<double> south_rows_first(const std::vector<double>& file_order, std::int64_t columns) {
  std::vector<double> heights(file_order.size());
  const std::int64_t rows = std::int64_t(file_order.size()) / columns;
  for (std::int64_t row = 0; row < rows; ++row)
    std::copy_n(file_order.begin() + row * columns, columns, heights.begin() + (rows - 1 - row) * columns);
  return heights;
}

// Room for the samples a text file's header promises, but no more than its remaining bytes can hold (one
// digit and one separator each): a header's size is not believed before the data is there.
std::size_t text_samples_room(const Scanner& scan, std::int64_t count) {
  constexpr std::size_t kBytesPerValue = 2;
  return std::min(std::size_t(count), (scan.data().size() - scan.pos()) / kBytesPerValue + 1);
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error(fmt::format("{}: read error", path));
  return data;
}

Heightmap read_pgm(const std::string& path, Scanner& scan, const Token& magic, double cell_size_m,
                   double max_height_m) {
  if (!(cell_size_m > 0.0) || !std::isfinite(cell_size_m))
    throw std::runtime_error(
        fmt::format("{}: cell_size: expected a positive number of metres, got {}", path, cell_size_m));
  if (!(max_height_m >= 0.0) || !std::isfinite(max_height_m))
    throw std::runtime_error(
        fmt::format("{}: max_height: expected a non-negative number of metres, got {}", path, max_height_m));

  constexpr std::string_view kPositive = "a positive integer";
  const Token width_token = scan.require("width", kPositive);
  const std::int64_t width = parse_integer(scan, width_token, "width", 1, 1 << 24, kPositive);
  const Token height_token = scan.require("height", kPositive);
  const std::int64_t height = parse_integer(scan, height_token, "height", 1, 1 << 24, kPositive);
  check_sample_count(scan, height_token.line, width, height);
  constexpr std::string_view kMaxval = "an integer in 1..65535";
  const Token maxval_token = scan.require("maxval", kMaxval);
  const std::int64_t maxval = parse_integer(scan, maxval_token, "maxval", 1, 65535, kMaxval);

  const std::int64_t count = width * height;
  // Image rows run north to south, as read here; storage rows run south to north (south_rows_first).
  std::vector<double> image;
  const double scale = max_height_m / double(maxval);
  auto store = [&](std::int64_t value) { image.push_back(double(value) * scale); };

  if (magic.text == "P2") {
    image.reserve(text_samples_room(scan, count));
    const std::string expected = fmt::format("an integer in 0..{}", maxval);
    for (std::int64_t i = 0; i < count; ++i) {
      const auto token = scan.next();
      if (!token)
        scan.fail(scan.last_line(), fmt::format("truncated data: expected {} pixel values ({} x {}), got {}",
                                                count, width, height, i));
      store(parse_integer(scan, *token, "pixel value", 0, maxval, expected));
    }
    if (const auto extra = scan.next())
      scan.fail(extra->line,
                fmt::format("wrong number of values: expected {} pixel values ({} x {}), got more: '{}'",
                            count, width, height, printable(extra->text)));
  } else {
    // P5: exactly one whitespace byte separates maxval from the pixel bytes.
    const std::string_view data = scan.data();
    std::size_t start = scan.pos();
    if (start < data.size() && !is_space(data[start]))
      scan.fail(scan.line(), "maxval: expected one whitespace character before the binary data");
    start = std::min(start + 1, data.size());
    const std::int64_t bytes_per_pixel = maxval > 255 ? 2 : 1;
    const std::int64_t need = count * bytes_per_pixel;
    const std::int64_t have = std::int64_t(data.size() - start);
    if (have < need)
      throw std::runtime_error(fmt::format(
          "{}: binary data: truncated data: expected {} bytes ({} x {} pixels of {} byte(s)), got {}", path,
          need, width, height, bytes_per_pixel, have));
    if (have > need)
      throw std::runtime_error(fmt::format(
          "{}: binary data: wrong number of values: expected {} bytes ({} x {} pixels of {} byte(s)), "
          "got {} more",
          path, need, width, height, bytes_per_pixel, have - need));
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data() + start);
    image.reserve(std::size_t(count));  // the bytes are there: checked above
    for (std::int64_t i = 0; i < count; ++i) {
      const std::int64_t value = bytes_per_pixel == 2 ? (std::int64_t(bytes[2 * i]) << 8) | bytes[2 * i + 1]
                                                      : std::int64_t(bytes[i]);
      if (value > maxval)
        throw std::runtime_error(
            fmt::format("{}: binary data: pixel (row {}, column {}): expected a value in 0..{}, got {}", path,
                        i / width + 1, i % width + 1, maxval, value));
      store(value);
    }
  }
  return Heightmap(int(width), int(height), cell_size_m, {0.5 * cell_size_m, 0.5 * cell_size_m},
                   south_rows_first(image, width));
}

}  // namespace

Heightmap Heightmap::read(const std::string& path, double cell_size_m, double max_height_m) {
  const std::string data = read_file(path);
  // Georeferenced rasters (ESRI ASCII grids, GeoTIFFs) are GDAL's to read (io/gis/GeoRaster.hpp).
  constexpr std::string_view kExpected =
      "expected a PGM image (P2/P5; an ESRI grid or a GeoTIFF is read as terrain.raster)";
  // Sniff the first token without comment handling: the format decides whether '#' means anything.
  Scanner sniff(path, data, false);
  const auto first = sniff.next();
  if (!first) sniff.fail(sniff.line(), fmt::format("{}, got an empty file", kExpected));
  if (first->text == "P2" || first->text == "P5") {
    Scanner scan(path, data, true);
    const Token magic = *scan.next();
    return read_pgm(path, scan, magic, cell_size_m, max_height_m);
  }
  sniff.fail(first->line, fmt::format("{}, got '{}'", kExpected, printable(first->text)));
}

Heightmap::Heightmap(int columns, int rows, double cell_size_m, std::array<double, 2> sw_centre_m,
                     std::vector<double> heights_m)
    : columns_(columns),
      rows_(rows),
      cell_size_(cell_size_m),
      sw_centre_(sw_centre_m),
      heights_(std::move(heights_m)) {
  if (columns <= 0 || rows <= 0)
    throw std::invalid_argument(
        fmt::format("Heightmap: dimensions must be positive, got {} x {} samples", columns, rows));
  if (!(cell_size_m > 0.0) || !std::isfinite(cell_size_m))
    throw std::invalid_argument(fmt::format("Heightmap: cell size must be > 0 m, got {}", cell_size_m));
  if (!std::isfinite(sw_centre_m[0]) || !std::isfinite(sw_centre_m[1]))
    throw std::invalid_argument("Heightmap: the south-west sample's position must be finite");
  if (heights_.size() != std::size_t(columns) * std::size_t(rows))
    throw std::invalid_argument(fmt::format("Heightmap: expected {} x {} = {} heights, got {}", columns, rows,
                                            std::size_t(columns) * std::size_t(rows), heights_.size()));
  max_height_ = -std::numeric_limits<double>::infinity();
  for (double height : heights_) {
    if (!std::isfinite(height)) throw std::invalid_argument("Heightmap: heights must be finite");
    max_height_ = std::max(max_height_, height);
  }
}

double Heightmap::height_at(double x_m, double y_m) const {
  if (std::isnan(x_m) || std::isnan(y_m)) return std::numeric_limits<double>::quiet_NaN();
  // Position in sample units, clamped to the lattice of centres (edge values continue outwards).
  const double fx = std::clamp((x_m - sw_centre_[0]) / cell_size_, 0.0, double(columns_ - 1));
  const double fy = std::clamp((y_m - sw_centre_[1]) / cell_size_, 0.0, double(rows_ - 1));
  const int i0 = std::min(int(fx), std::max(columns_ - 2, 0));
  const int j0 = std::min(int(fy), std::max(rows_ - 2, 0));
  const int i1 = std::min(i0 + 1, columns_ - 1);
  const int j1 = std::min(j0 + 1, rows_ - 1);
  const double tx = fx - i0, ty = fy - j0;
  const double south = (1.0 - tx) * sample(i0, j0) + tx * sample(i1, j0);
  const double north = (1.0 - tx) * sample(i0, j1) + tx * sample(i1, j1);
  return (1.0 - ty) * south + ty * north;
}

}  // namespace fw::fluid
