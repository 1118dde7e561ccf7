#include "io/ScenarioError.hpp"

#include <fmt/format.h>

#include <utility>

namespace fw::io {

ScenarioError::ScenarioError(std::string file, int line, std::string key, const std::string& message)
    : std::invalid_argument(fmt::format("{}:{}: {}: {}", file, line, key, message)),
      file_(std::move(file)),
      line_(line),
      key_(std::move(key)) {}

}  // namespace fw::io
