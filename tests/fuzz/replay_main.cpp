// The main that replays a fuzz target without libFuzzer (tests/fuzz/fuzz.cmake): every file of the folders
// given is fed once to LLVMFuzzerTestOneInput, in name order. A crash, a sanitizer report or an escaping
// exception ends the process; otherwise it prints how many inputs it fed and exits 0. An empty or missing
// folder list is an error, so that a test cannot pass by feeding nothing.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> inputs;
  for (int k = 1; k < argc; ++k) {
    if (!std::filesystem::is_directory(argv[k])) continue;  // a target may have no regressions yet
    for (const auto& entry : std::filesystem::directory_iterator(argv[k]))
      if (entry.is_regular_file()) inputs.push_back(entry.path());
  }
  std::sort(inputs.begin(), inputs.end());
  if (inputs.empty()) {
    std::cerr << "replay: no input in the folders given\n";
    return 1;
  }
  for (const auto& path : inputs) {
    std::cout << "replay: " << path.string() << std::endl;  // flushed: a crash names its input
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  }
  std::cout << "replay: " << inputs.size() << " inputs, each read or refused cleanly\n";
  return 0;
}
