// Fuzz target: a run folder read back for `forestwind render` (viz/RunFolder: the .pvd lists through
// io::read_pvd, run.json's scenario name, the frames' .vti/.vtp through VTK's XML readers).
// Feeds: the bytes cut at each line "=====" into, in this order, wind.pvd, trees.pvd, leaves.pvd, run.json,
// wind/0.vti, trees/0.vtp, leaves/0.vtp and scenario.yaml (the scenario's copy, whose name
// render reads when run.json gives none) of a fresh folder (a part left out is a file left out); then the
// folder is opened, its last and first frames selected, and the last frame that reads is loaded, as render
// does.
// Clean refusals: std::invalid_argument or std::runtime_error whose message names the folder or a file in
// it (render exits 2 or 1 with it). Bugs: anything else: a crash, a sanitizer report, another exception, an
// unnamed file, a hang, a huge allocation.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "tests/fuzz/FuzzSupport.hpp"
#include "viz/RunFolder.hpp"

namespace {

constexpr const char* kParts[] = {"wind.pvd",   "trees.pvd",   "leaves.pvd",   "run.json",
                                  "wind/0.vti", "trees/0.vtp", "leaves/0.vtp", "scenario.yaml"};
constexpr std::string_view kCut = "\n=====\n";

void expect_names_folder(const std::exception& e, const std::filesystem::path& folder) {
  if (std::string_view(e.what()).find(folder.string()) == std::string_view::npos)
    fw::fuzz::fail("a refusal that does not name the run folder: " + std::string(e.what()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto folder = fw::fuzz::scratch_folder() / "run";
  std::filesystem::remove_all(folder);  // nothing of the last input may stay
  std::filesystem::create_directories(folder);
  std::string_view rest(reinterpret_cast<const char*>(data), size);
  for (const char* part : kParts) {
    const std::size_t cut = rest.find(kCut);
    const std::string_view text = rest.substr(0, cut);
    if (!text.empty())
      fw::fuzz::write_input(std::string("run/") + part, reinterpret_cast<const std::uint8_t*>(text.data()),
                            text.size());
    if (cut == std::string_view::npos) break;
    rest.remove_prefix(cut + kCut.size());
  }
  try {
    const fw::viz::RunFolder run(folder);
    const auto& last = run.select(std::nullopt, std::nullopt);
    run.select(0, std::nullopt);
    run.select(std::nullopt, last.time);
    std::string note;
    run.load_last_complete(last, &note);
  } catch (const std::invalid_argument& e) {
    expect_names_folder(e, folder);
  } catch (const std::runtime_error& e) {
    expect_names_folder(e, folder);
  }
  return 0;
}
