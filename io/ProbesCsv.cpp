#include "io/ProbesCsv.hpp"

#include "base/AtomicFile.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace fw::io {

ProbesCsv::ProbesCsv(std::filesystem::path path, std::vector<std::string> probe_names,
                     std::vector<int> tree_ids, std::size_t rewrite_limit_bytes, CountColumns counts)
    : ProbesCsv(std::move(path), std::move(probe_names), std::move(tree_ids), rewrite_limit_bytes, counts,
                Start::fresh) {}

ProbesCsv ProbesCsv::continued(std::filesystem::path path, std::vector<std::string> probe_names,
                               std::vector<int> tree_ids, std::size_t rows, std::size_t rewrite_limit_bytes,
                               CountColumns counts) {
  if (!std::filesystem::exists(path))
    return ProbesCsv(std::move(path), std::move(probe_names), std::move(tree_ids), rewrite_limit_bytes,
                     counts);
  ProbesCsv csv(std::move(path), std::move(probe_names), std::move(tree_ids), rewrite_limit_bytes, counts,
                Start::continued);
  csv.content_ = csv.kept_rows(rows);
  base::write_text_atomically("ProbesCsv", csv.path_, csv.content_);
  csv.rows_ = rows;
  if (csv.content_.size() > csv.rewrite_limit_) {
    csv.appending_ = true;
    csv.content_.clear();
  }
  return csv;
}

void ProbesCsv::check_continuable(std::filesystem::path path, std::vector<std::string> probe_names,
                                  std::vector<int> tree_ids, std::size_t rows, CountColumns counts) {
  if (!std::filesystem::exists(path)) return;
  ProbesCsv(std::move(path), std::move(probe_names), std::move(tree_ids), kDefaultRewriteLimit, counts,
            Start::continued)
      .kept_rows(rows);
}

std::string ProbesCsv::kept_rows(std::size_t rows) const {
  std::ifstream in(path_, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw std::runtime_error(fmt::format("ProbesCsv: cannot read {}", path_.string()));
  const std::string content = text.str();
  // The header line and `rows` whole lines after it; anything later is dropped.
  std::size_t end = content.find('\n');
  if (end == std::string::npos || content.compare(0, end, header_) != 0)
    throw std::invalid_argument(fmt::format(
        "{}: the columns differ from this run's (output.probes or the tracked trees changed): resume into "
        "another folder (-o), or keep the probes as they were",
        path_.string()));
  for (std::size_t row = 0; row < rows; ++row) {
    const std::size_t next = content.find('\n', end + 1);
    if (next == std::string::npos)
      throw std::invalid_argument(fmt::format(
          "{}: holds {} rows, and the checkpoint was written after {}: it is not the checkpoint's run's file",
          path_.string(), row, rows));
    end = next;
  }
  return content.substr(0, end + 1);
}

ProbesCsv::ProbesCsv(std::filesystem::path path, std::vector<std::string> probe_names,
                     std::vector<int> tree_ids, std::size_t rewrite_limit_bytes, CountColumns counts,
                     Start start)
    : path_(std::move(path)),
      probes_(probe_names.size()),
      trees_(tree_ids.size()),
      rewrite_limit_(rewrite_limit_bytes),
      counts_(counts) {
  std::set<std::string> seen_names;
  for (const std::string& name : probe_names) {
    if (name.empty()) throw std::invalid_argument("ProbesCsv: expected a probe name, got an empty one");
    if (name.find_first_of(",\"\r\n") != std::string::npos) {
      throw std::invalid_argument(fmt::format(
          "ProbesCsv: probe \"{}\": a name may not contain a comma, a quote or a line break", name));
    }
    if (!seen_names.insert(name).second) {
      throw std::invalid_argument(fmt::format("ProbesCsv: probe \"{}\" is listed twice", name));
    }
  }
  std::set<int> seen_ids;
  for (int id : tree_ids) {
    if (!seen_ids.insert(id).second) {
      throw std::invalid_argument(fmt::format("ProbesCsv: tree {} is listed twice", id));
    }
  }

  header_ = "time_s";
  for (const std::string& name : probe_names) header_ += fmt::format(",{0}_u,{0}_v,{0}_w", name);
  for (int id : tree_ids) header_ += fmt::format(",tree{0}_tip_dx,tree{0}_tip_dy,tree{0}_tip_dz", id);
  if (counts_.leaves) header_ += ",leaves_shed,leaves_flying,leaves_landed,leaves_exited";
  if (counts_.damage) header_ += ",trees_standing,trees_broken,trees_overturned";
  if (start == Start::continued) return;
  content_ = header_ + "\n";
  base::write_text_atomically("ProbesCsv", path_, content_);
}

void ProbesCsv::append(double time, const std::vector<std::array<float, 3>>& probe_velocity,
                       const std::vector<std::array<double, 3>>& tip_displacement) {
  append_rows({Row{time, &probe_velocity, &tip_displacement}});
}

void ProbesCsv::append(double time, const std::vector<std::array<float, 3>>& probe_velocity,
                       const std::vector<std::array<double, 3>>& tip_displacement,
                       const trees::LeafCounts& leaf_counts) {
  append_rows({Row{time, &probe_velocity, &tip_displacement, &leaf_counts}});
}

void ProbesCsv::append_rows(const std::vector<Row>& rows) {
  std::string lines;
  for (const Row& row : rows) {
    const auto& probe_velocity = *row.probe_velocity;
    const auto& tip_displacement = *row.tip_displacement;
    if (probe_velocity.size() != probes_ || tip_displacement.size() != trees_) {
      throw std::invalid_argument(
          fmt::format("ProbesCsv: {}: expected {} probe velocities and {} tip displacements, got {} and {}",
                      path_.string(), probes_, trees_, probe_velocity.size(), tip_displacement.size()));
    }
    if ((counts_.leaves && !row.leaf_counts) || (counts_.damage && !row.damage_counts)) {
      throw std::invalid_argument(fmt::format(
          "ProbesCsv: {}: the file has {} count columns: expected those counts with every row, at time {}",
          path_.string(), counts_.leaves && !row.leaf_counts ? "leaf" : "damage", row.time));
    }
    lines += fmt::format("{:.12g}", row.time);
    for (const auto& v : probe_velocity) lines += fmt::format(",{:.9g},{:.9g},{:.9g}", v[0], v[1], v[2]);
    for (const auto& d : tip_displacement) lines += fmt::format(",{:.9g},{:.9g},{:.9g}", d[0], d[1], d[2]);
    if (counts_.leaves) {
      const trees::LeafCounts& n = *row.leaf_counts;
      lines += fmt::format(",{},{},{},{}", n.shed, n.flying, n.landed, n.exited);
    }
    if (counts_.damage) {
      const trees::DamageCounts& n = *row.damage_counts;
      lines += fmt::format(",{},{},{}", n.standing, n.broken, n.overturned);
    }
    lines += '\n';
  }
  if (rows.empty()) return;

  if (!appending_ && content_.size() + lines.size() <= rewrite_limit_) {
    content_ += lines;
    try {
      base::write_text_atomically("ProbesCsv", path_, content_);
    } catch (...) {
      content_.resize(content_.size() - lines.size());  // the file still holds the previous rows
      throw;
    }
    rows_ += rows.size();
    return;
  }

  // Past the limit: the whole batch appended at once (cut back on failure: no partial row is left).
  base::append_text("ProbesCsv", path_, lines);
  appending_ = true;
  content_.clear();
  content_.shrink_to_fit();
  rows_ += rows.size();
}

}  // namespace fw::io
