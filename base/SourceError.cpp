#include "base/SourceError.hpp"

#include <fmt/format.h>

#include <utility>

namespace fw::base {

namespace {

std::string located(std::string_view file, int line) {
  return line > 0 ? fmt::format("{}:{}", file, line) : std::string(file);
}

}  // namespace

SourceError::SourceError(std::string message, std::string_view file, int line)
    : std::invalid_argument(std::move(message)), file_(file), line_(line) {}

SourceError::SourceError(std::string_view file, int line, std::string_view key, std::string_view expected,
                         std::string_view got)
    : SourceError(got.empty() ? fmt::format("{}: {}: {}", located(file, line), key, expected)
                              : fmt::format("{}: {}: {}, got {}", located(file, line), key, expected, got),
                  file, line) {}

SourceError SourceError::unreadable(std::string_view file, std::string_view what) {
  return SourceError(fmt::format("{}: {}", file, what), file, 0);
}

}  // namespace fw::base
