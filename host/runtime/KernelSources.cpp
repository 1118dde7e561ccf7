#include "host/runtime/KernelSources.hpp"

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fw::host {
namespace embedded {
extern const std::pair<std::string_view, std::string_view> kKernelFiles[];
extern const int kKernelFileCount;
}  // namespace embedded

namespace {

std::string raw_file(const std::string& name) {
  if (const char* dir = std::getenv("FORESTWIND_KERNEL_DIR"); dir && *dir) {
    const std::string path = std::string(dir) + "/" + name;
    std::ifstream in(path);
    if (!in)
      throw std::runtime_error(fmt::format("kernel file {} not found (FORESTWIND_KERNEL_DIR={})", path, dir));
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }
  for (int i = 0; i < embedded::kKernelFileCount; ++i)
    if (embedded::kKernelFiles[i].first == name) return std::string(embedded::kKernelFiles[i].second);
  throw std::runtime_error(fmt::format("kernel file {} is not embedded in this build", name));
}

// Expands `#include "x"` lines so that a program is one self-contained string (no -I path needed, which
// matters for an installed binary). Each file is included at most once.
void expand(const std::string& name, std::set<std::string>& done, std::string& out) {
  if (!done.insert(name).second) return;
  out += fmt::format("#line 1 \"{}\"\n", name);
  std::istringstream in(raw_file(name));
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const auto start = line.find_first_not_of(" \t");
    if (start != std::string::npos && line.compare(start, 8, "#include") == 0) {
      const auto open = line.find('"', start);
      const auto close = open == std::string::npos ? open : line.find('"', open + 1);
      if (close != std::string::npos) {
        expand(line.substr(open + 1, close - open - 1), done, out);
        out += fmt::format("#line {} \"{}\"\n", line_number + 1,
                           name);  // keeps compiler messages pointing at the right file
        continue;
      }
    }
    out += line;
    out += '\n';
  }
}

}  // namespace

std::string kernel_source(const std::string& file_name) {
  std::set<std::string> done;
  std::string out;
  expand(file_name, done, out);
  return out;
}

std::vector<std::string> embedded_kernel_files() {
  std::vector<std::string> names;
  for (int i = 0; i < embedded::kKernelFileCount; ++i) names.emplace_back(embedded::kKernelFiles[i].first);
  return names;
}

}  // namespace fw::host
