// probes.csv: one row per probe sample (the probes' own interval) with the wind velocity at named points and
// the tip displacement of a few trees.
//
//   fw::io::ProbesCsv probes("out/probes.csv", {"mast", "gap"}, {0, 7});   // writes the header line
//   probes.append(t, {sample_velocity(spec, vel, mast), sample_velocity(spec, vel, gap)},
//                 {{0.12, -0.01, -0.003}, {0.08, 0.02, -0.001}});
//
// Columns: time_s, then <probe>_u,<probe>_v,<probe>_w for each probe (m/s), then
// tree<id>_tip_dx,tree<id>_tip_dy,tree<id>_tip_dz for each tree (m), then, in runs with leaves only,
// leaves_shed,leaves_flying,leaves_landed,leaves_exited (counts over all leaves at the sample's time,
// docs/leaves.md "States and counts"), then, in runs with storm damage only,
// trees_standing,trees_broken,trees_overturned (docs/damage.md). Comma-separated, '\n' line ends, no
// quoting (names with a comma, quote or line break are refused). Numbers: time with 12 significant digits,
// counts as integers, every other value with 9 (enough to read a float32 back exactly); non-finite values
// print as nan / inf.
//
// Writing: every append() leaves a complete file whose last line is a complete row. While the file is
// smaller than `rewrite_limit_bytes` it is rewritten in full through AtomicFile (temporary + rename), so no
// reader ever sees a partial row; past the limit each row is appended with one write of the whole line and a
// flush, which keeps a long run linear in cost - there only a crash in the middle of that one write could
// leave a truncated last line.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "trees/LeafState.hpp"
#include "trees/TreeDamage.hpp"

namespace fw::io {

/// The count columns a probes.csv carries after the probes and tips.
struct CountColumns {
  bool leaves = false;  ///< leaves_shed, leaves_flying, leaves_landed, leaves_exited
  bool damage = false;  ///< trees_standing, trees_broken, trees_overturned
};

class ProbesCsv {
 public:
  static constexpr std::size_t kDefaultRewriteLimit = 256 * 1024;

  /// Writes the header line to `path` (replacing any old file). counts: the count columns to add (without
  /// them the file has none). Throws std::invalid_argument for an empty probe name, a name
  /// with a comma, quote or line break, or duplicate probe names or tree ids; std::runtime_error naming the
  /// path if the folder does not exist or the file cannot be written.
  ProbesCsv(std::filesystem::path path, std::vector<std::string> probe_names, std::vector<int> tree_ids,
            std::size_t rewrite_limit_bytes = kDefaultRewriteLimit, CountColumns counts = {});

  /// A resumed run's file: takes over the probes.csv at `path` written with the same columns, keeping its
  /// header and first `rows` rows (the samples up to the checkpoint) and dropping later ones; appends go on
  /// after them. Without a file there, a new one (as the constructor). Throws std::invalid_argument naming
  /// the path when its header differs from these columns' or it holds fewer rows, and std::runtime_error
  /// when it cannot be read or written.
  static ProbesCsv continued(std::filesystem::path path, std::vector<std::string> probe_names,
                             std::vector<int> tree_ids, std::size_t rows,
                             std::size_t rewrite_limit_bytes = kDefaultRewriteLimit,
                             CountColumns counts = {});

  /// What continued() checks, without writing: throws as it would (nothing when there is no file).
  static void check_continuable(std::filesystem::path path, std::vector<std::string> probe_names,
                                std::vector<int> tree_ids, std::size_t rows, CountColumns counts = {});

  /// Appends one row. probe_velocity: one (u, v, w) per probe, m/s; tip_displacement: one (dx, dy, dz) per
  /// tree, m, both in constructor order. Throws std::invalid_argument for the wrong counts or, in a file
  /// with count columns, for a row without those counts (nothing is written), and std::runtime_error
  /// naming the path on a write failure.
  void append(double time, const std::vector<std::array<float, 3>>& probe_velocity,
              const std::vector<std::array<double, 3>>& tip_displacement);
  /// The same with the leaf counts at `time` (ignored in a file without leaf count columns).
  void append(double time, const std::vector<std::array<float, 3>>& probe_velocity,
              const std::vector<std::array<double, 3>>& tip_displacement,
              const trees::LeafCounts& leaf_counts);
  /// One row per sample, in order, with a single rewrite or append for the whole batch (probes sampled
  /// every step arrive a frame's worth at a time). The same checks as append(), before anything is written.
  struct Row {
    double time = 0.0;
    const std::vector<std::array<float, 3>>* probe_velocity = nullptr;
    const std::vector<std::array<double, 3>>* tip_displacement = nullptr;
    /// Required in a file with leaf count columns, ignored in one without.
    const trees::LeafCounts* leaf_counts = nullptr;
    /// Required in a file with damage count columns, ignored in one without.
    const trees::DamageCounts* damage_counts = nullptr;
  };
  void append_rows(const std::vector<Row>& rows);

  const std::filesystem::path& path() const { return path_; }
  /// The header line, without the line end.
  const std::string& header() const { return header_; }
  /// Rows appended so far.
  std::size_t rows() const { return rows_; }

 private:
  enum class Start { fresh, continued };  // continued: the header is not written
  ProbesCsv(std::filesystem::path path, std::vector<std::string> probe_names, std::vector<int> tree_ids,
            std::size_t rewrite_limit_bytes, CountColumns counts, Start start);
  /// The file's header and first `rows` rows (std::invalid_argument when its header is not this one's or it
  /// holds fewer rows).
  std::string kept_rows(std::size_t rows) const;

  std::filesystem::path path_;
  std::size_t probes_ = 0, trees_ = 0;
  std::size_t rewrite_limit_ = kDefaultRewriteLimit;
  CountColumns counts_;
  std::string header_;
  std::string content_;  // the whole file while it is rewritten; cleared once appending takes over
  bool appending_ = false;
  std::size_t rows_ = 0;
};

}  // namespace fw::io
