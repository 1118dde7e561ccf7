// A run's output folder read back for pictures: which frames it holds and, for one frame, the wind grid's
// cell arrays, the deformed trees and the leaves (the files of io/writers, through VTK's XML readers).
//
//   fw::viz::RunFolder run("out/storm");
//   const fw::viz::RunFolder::Frame& frame = run.select(std::nullopt, std::nullopt);   // the last one
//   fw::viz::FrameData data = run.load(frame);
//   const fw::viz::ScalarField speed = data.wind->field("speed");
//
// Frames are the entries of wind.pvd (or of trees.pvd in a run without wind output), each matched with the
// trees and leaves entries of the same time, or, for outputs written every N-th frame, of the latest time
// before it (the trees hold still between their frames rather than vanish). A .pvd lists a frame only once
// its file is complete (io/writers/FrameWriter.hpp), but a folder copied mid-run or damaged may still hold a
// listed file that does not read: load_last_complete() then falls back to the frame before it and says which
// one it used.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/settings/SiteSettings.hpp"
#include "viz/FrameFileCheck.hpp"

namespace fw::viz {

/// One scalar per cell of the wind grid, x fastest (VTK's order): a cell array or one derived from a vector
/// array (its magnitude or one component).
struct ScalarField {
  std::string name;           ///< e.g. "speed", "velocity_z", "vorticity"
  std::string unit;           ///< e.g. "m/s"; empty for a pure number
  bool is_signed = false;     ///< can be negative: drawn with the diverging map about 0
  std::vector<float> values;  ///< nx * ny * nz
};

/// The wind grid of one frame: its geometry and every cell array of its .vti.
struct WindGrid {
  std::array<int, 3> cells{0, 0, 0};            ///< nx, ny, nz
  std::array<double, 3> origin{0.0, 0.0, 0.0};  ///< the domain's minimum corner, m
  double cell_size = 0.0;                       ///< h, m
  struct Array {
    std::string name;
    int components = 1;
    std::vector<float> values;  ///< components per cell, interleaved
  };
  std::vector<Array> arrays;
  std::vector<std::uint8_t> solid;  ///< 1 per solid cell; empty when the file holds no "solid" array
  /// The run's site, from the frame's field data (io/SiteVtk.hpp); none for a run without one.
  std::optional<io::SiteSettings> site;

  /// The field names field() accepts: every scalar array, and for a vector array NAME its magnitude NAME
  /// and its components NAME_x, NAME_y, NAME_z.
  std::vector<std::string> field_names() const;
  /// Throws std::invalid_argument("render: no field 'X' in FILE: choose one of ...") for another name.
  ScalarField field(const std::string& name) const;
  std::size_t index(int i, int j, int k) const { return (std::size_t(k) * cells[1] + j) * cells[0] + i; }
  std::filesystem::path file;  ///< where it was read from, for messages
};

/// The deformed forest of one frame: one segment per element, at the deformed positions.
struct TreeLines {
  std::vector<std::array<double, 3>> points;  ///< m, world frame
  std::vector<double> radius;                 ///< per point, m
  std::vector<double> displacement;           ///< per point, |displacement|, m
  std::vector<std::array<int, 2>> segments;   ///< point indices (parent, child)
};

/// The written leaves of one frame.
struct LeafPoints {
  std::vector<std::array<double, 3>> position;  ///< blade centres, m
  std::vector<std::uint8_t> state;              ///< trees::LeafState: 0 attached, 1 flying, 2 landed
  std::vector<double> size;                     ///< blade side, m
};

struct FrameData {
  int index = 0;
  double time = 0.0;  ///< s
  std::optional<WindGrid> wind;
  std::optional<TreeLines> trees;
  std::optional<LeafPoints> leaves;
};

class RunFolder {
 public:
  struct Frame {
    int index = 0;                              ///< position in the list, 0 = the first frame
    double time = 0.0;                          ///< s
    std::filesystem::path wind, trees, leaves;  ///< empty where that output has no entry at (trees, leaves:
                                                ///< or before) this time
  };

  /// Reads the folder's .pvd files and the scenario's name. Throws std::invalid_argument("render: ...") when
  /// `folder` is not a folder or holds neither wind.pvd nor trees.pvd, or when neither lists a frame.
  explicit RunFolder(std::filesystem::path folder);

  const std::filesystem::path& folder() const { return folder_; }
  /// The scenario's name: run.json's "scenario", else the scenario copy's "scenario" key, else the folder's
  /// name.
  const std::string& scenario_name() const { return scenario_name_; }
  const std::vector<Frame>& frames() const { return frames_; }

  /// The frame numbered `index`, or the one nearest `time` (s), or the last one when both are empty.
  /// Throws std::invalid_argument("render: ...") naming the frames there are (0..N-1, their times) for a
  /// number outside them or a time outside the run by more than half a frame interval.
  const Frame& select(std::optional<int> index, std::optional<double> time) const;

  /// Reads a frame's files. Throws FrameReadError("render: FILE: ...") when one is missing or does not read
  /// (viz/FrameFileCheck.hpp).
  FrameData load(const Frame& frame) const;
  /// load(), going back from `frame` to the latest frame whose files all read; when that is not `frame`,
  /// `note` (if given) gets a sentence saying which frame failed and which was used. Throws
  /// FrameReadError when none reads.
  FrameData load_last_complete(const Frame& frame, std::string* note = nullptr) const;

 private:
  std::filesystem::path folder_;
  std::string scenario_name_;
  std::vector<Frame> frames_;
};

/// A run folder's scenario name: run.json's "scenario", else the scenario copy's "scenario" key, else the
/// folder's name (a folder without frames too).
std::string scenario_name_of(const std::filesystem::path& folder);

/// "frames 0..N-1 (t = A .. B s)": what a folder offers, for messages.
std::string describe_frames(const std::vector<RunFolder::Frame>& frames);

}  // namespace fw::viz
