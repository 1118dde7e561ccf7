#include "io/AtomicFile.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <stdexcept>
#include <system_error>
#include <utility>

namespace fw::io {

AtomicFile::AtomicFile(std::filesystem::path target) : target_(std::move(target)) {
  temporary_ = target_;
  temporary_ += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temporary_, ignored);
  }
}

void AtomicFile::commit() {
  std::error_code error;
  if (!std::filesystem::is_regular_file(temporary_, error)) {
    throw std::runtime_error(fmt::format("AtomicFile: {} was not written (expected the temporary {})",
                                         target_.string(), temporary_.string()));
  }
  std::filesystem::rename(temporary_, target_, error);
  if (error) {
    throw std::runtime_error(fmt::format("AtomicFile: cannot rename {} to {}: {}", temporary_.string(),
                                         target_.string(), error.message()));
  }
  committed_ = true;
}

}  // namespace fw::io
