#include "host/bench/RanksBench.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "io/JsonWriter.hpp"

namespace fw::bench {
namespace {

constexpr double kMsPerSecond = 1e3;
constexpr double kBytesPerMegabyte = 1e6;
constexpr double kBytesPerKilobyte = 1e3;
constexpr double kBitsPerGigabit = 1e9;
constexpr double kMicrosecondsPerSecond = 1e6;

// The largest of f(rank) over the ranks (0 with none).
template <typename F>
double largest(const std::vector<RankStep>& ranks, F&& f) {
  double most = 0.0;
  for (const RankStep& r : ranks) most = std::max(most, f(r));
  return most;
}

std::string grid_name(const std::array<int, 3>& grid) {
  return fmt::format("{}x{}x{}", grid[0], grid[1], grid[2]);
}

}  // namespace

RankStep rank_step(double ms_per_step, double alone_ms, const host::HaloTraffic& timed, int steps,
                   const fluid::Block& block) {
  RankStep r;
  r.ms = ms_per_step;
  r.alone_ms = alone_ms;
  r.halo_ms = timed.seconds * kMsPerSecond / steps;
  r.halo_copy_ms = timed.copy_seconds * kMsPerSecond / steps;
  r.halo_bytes = double(timed.bytes) / steps;
  r.halo_messages = double(timed.messages) / steps;
  for (int a = 0; a < 2; ++a) r.sides += (block.halo_low[a] > 0 ? 1 : 0) + (block.halo_high[a] > 0 ? 1 : 0);
  return r;
}

std::vector<RankStep> gather_rank_steps(const host::Communicator& world, const RankStep& mine) {
  return host::joined(world.gather(std::vector<RankStep>{mine}));
}

RanksCase gather_case(const host::Communicator& world, const std::array<int, 3>& grid,
                      const fluid::Decomposition& decomposition, const RankRun& mine) {
  RanksCase c;
  c.grid = grid;
  c.decomposition = decomposition.describe();
  c.blocks = decomposition.blocks();
  c.halo = decomposition.halo();
  c.pressure_iterations = mine.pressure_iterations;
  c.ranks = gather_rank_steps(world, rank_step(mine.ms_per_step, mine.alone_ms, mine.halo, mine.steps,
                                               decomposition.block(world.rank())));
  return c;
}

bool alone_run_fits(const host::Communicator& world, const host::DeviceInfo& device, std::size_t bytes) {
  // A machine's ranks share its CPU device (each takes its share of the cores, and all of them the memory);
  // each GPU rank has a device of its own.
  const std::size_t sharing = device.type == "CPU" ? std::size_t(world.node_size()) : 1;
  const bool fits = bytes * sharing <= device.global_memory_bytes;
  return world.min(fits ? 1 : 0) == 1;
}

double RanksCase::ms_per_step() const {
  return largest(ranks, [](const RankStep& r) { return r.ms; });
}

double RanksCase::alone_ms_per_step() const {
  if (ranks.empty()) return 0.0;
  double sum = 0.0;
  for (const RankStep& r : ranks) {
    if (r.alone_ms <= 0.0) return 0.0;
    sum += r.alone_ms;
  }
  return sum / double(ranks.size());
}

double RanksCase::speedup() const {
  const double step = ms_per_step();
  return step > 0.0 ? alone_ms_per_step() / step : 0.0;
}

double RanksCase::efficiency() const {
  return ranks.empty() ? 0.0 : speedup() / double(ranks.size());
}

double RanksCase::halo_bytes() const {
  double sum = 0.0;
  for (const RankStep& r : ranks) sum += r.halo_bytes;
  return sum;
}

double RanksCase::halo_ms_max() const {
  return largest(ranks, [](const RankStep& r) { return r.halo_ms; });
}

MeasuredBlock RanksCase::measured_block() const {
  // Per side: a rank's figures over its sides with a neighbour (a rank without any has none to give).
  const auto per_side = [](double value, const RankStep& r) { return r.sides > 0 ? value / r.sides : 0.0; };
  MeasuredBlock block;
  block.compute_ms = largest(ranks, [](const RankStep& r) { return r.ms - r.halo_ms; });
  block.copy_ms_per_side = largest(ranks, [&](const RankStep& r) { return per_side(r.halo_copy_ms, r); });
  block.bytes_per_side = largest(ranks, [&](const RankStep& r) { return per_side(r.halo_bytes, r); });
  block.messages_per_side = largest(ranks, [&](const RankStep& r) { return per_side(r.halo_messages, r); });
  return block;
}

void print_ranks_bench_table(const RanksBenchResult& r, std::ostream& out) {
  out << fmt::format("forestwind bench {} over {} ranks, a device each (rank 0's: {}): {}; {} timed steps\n",
                     r.bench, r.ranks, r.device, r.workload, r.steps);
  out << fmt::format("not timed over ranks (run it without mpirun for these): {}\n\n", r.skipped);
  out << fmt::format("{:<12} {:<34} {:>4} {:>9} {:>9} {:>8} {:>6} {:>13} {:>11} {:>8}\n", "grid", "blocks",
                     "halo", "ms/step", "alone ms", "speedup", "effic.", "halo MB/step", "halo ms max",
                     "p-iters");
  for (const RanksCase& c : r.cases) {
    const double alone = c.alone_ms_per_step();
    out << fmt::format("{:<12} {:<34} {:>4} {:>9.2f} {:>9} {:>8} {:>6} {:>13.3f} {:>11.2f} {:>8.1f}\n",
                       grid_name(c.grid), c.decomposition, c.halo, c.ms_per_step(),
                       alone > 0.0 ? fmt::format("{:.2f}", alone) : "-",
                       alone > 0.0 ? fmt::format("x{:.2f}", c.speedup()) : "-",
                       alone > 0.0 ? fmt::format("{:.0f}%", 100.0 * c.efficiency()) : "-",
                       c.halo_bytes() / kBytesPerMegabyte, c.halo_ms_max(), c.pressure_iterations);
    out << fmt::format("  {:>4} {:>9} {:>9} {:>9} {:>10} {:>13} {:>10} {:>9}\n", "rank", "ms/step", "compute",
                       "halo ms", "copies ms", "halo KB/step", "msgs/step", "alone ms");
    for (std::size_t k = 0; k < c.ranks.size(); ++k) {
      const RankStep& s = c.ranks[k];
      out << fmt::format("  {:>4} {:>9.2f} {:>9.2f} {:>9.2f} {:>10.2f} {:>13.1f} {:>10.1f} {:>9}\n", k, s.ms,
                         s.ms - s.halo_ms, s.halo_ms, s.halo_copy_ms, s.halo_bytes / kBytesPerKilobyte,
                         s.halo_messages, s.alone_ms > 0.0 ? fmt::format("{:.2f}", s.alone_ms) : "-");
    }
    const WeakScalingEstimate e = estimate_weak_scaling(c.measured_block(), r.interconnect);
    out << fmt::format(
        "  weak scaling to {} ranks (these blocks, 4 neighbours each; {:.0f} Gb/s, {:.1f} us a message): "
        "{:.3f} MB and {:.0f} messages a step; compute {:.2f} + copies {:.2f} + network {:.2f} = {:.2f} "
        "ms/step, efficiency {:.0f}%\n",
        e.ranks, r.interconnect.bits_per_s / kBitsPerGigabit,
        r.interconnect.latency_s * kMicrosecondsPerSecond, e.bytes / kBytesPerMegabyte, e.messages,
        e.compute_ms, e.copy_ms, e.network_ms, e.step_ms, 100.0 * e.efficiency);
  }
  out << "(ms/step: the slowest rank's wall time of a step; alone ms: every rank stepping the whole grid on "
         "its "
         "own device at the same time, the one-rank baseline; speedup = alone / ms/step, effic. = speedup / "
         "ranks; halo: what the exchanges sent, and their time with the device copies and the waits for "
         "neighbours; compute = ms/step - halo ms)\n";
}

std::string ranks_bench_json(const RanksBenchResult& r) {
  io::JsonWriter json;
  json.begin_object();
  json.key("bench").value(r.bench);
  json.key("device").value(r.device);
  json.key("workload").value(r.workload);
  json.key("skipped").value(r.skipped);
  json.key("ranks").value(r.ranks);
  json.key("steps").value(r.steps);
  json.key("interconnect").begin_object();
  json.key("ranks").value(r.interconnect.ranks);
  json.key("bits_per_s").value(r.interconnect.bits_per_s);
  json.key("latency_s").value(r.interconnect.latency_s);
  json.end_object();
  json.key("cases").begin_array();
  for (const RanksCase& c : r.cases) {
    json.begin_object();
    json.key("grid").values(c.grid);
    json.key("blocks").begin_array().value(c.blocks[0]).value(c.blocks[1]).end_array();
    json.key("decomposition").value(c.decomposition);
    json.key("halo_cells").value(c.halo);
    json.key("ms_per_step").value(c.ms_per_step());
    json.key("alone_ms_per_step").value(c.alone_ms_per_step());
    json.key("speedup").value(c.speedup());
    json.key("parallel_efficiency").value(c.efficiency());
    json.key("halo_bytes_per_step").value(c.halo_bytes());
    json.key("halo_ms_per_step_max").value(c.halo_ms_max());
    json.key("pressure_iterations").value(c.pressure_iterations);
    json.key("per_rank").begin_array();
    for (const RankStep& s : c.ranks) {
      json.begin_object();
      json.key("ms_per_step").value(s.ms);
      json.key("halo_ms_per_step").value(s.halo_ms);
      json.key("halo_copy_ms_per_step").value(s.halo_copy_ms);
      json.key("halo_bytes_per_step").value(s.halo_bytes);
      json.key("halo_messages_per_step").value(s.halo_messages);
      json.key("alone_ms_per_step").value(s.alone_ms);
      json.key("neighbour_sides").value(s.sides);
      json.end_object();
    }
    json.end_array();
    const WeakScalingEstimate e = estimate_weak_scaling(c.measured_block(), r.interconnect);
    json.key("weak_scaling").begin_object();
    json.key("ranks").value(e.ranks);
    json.key("halo_bytes_per_step").value(e.bytes);
    json.key("halo_messages_per_step").value(e.messages);
    json.key("compute_ms").value(e.compute_ms);
    json.key("copy_ms").value(e.copy_ms);
    json.key("network_ms").value(e.network_ms);
    json.key("ms_per_step").value(e.step_ms);
    json.key("efficiency").value(e.efficiency);
    json.end_object();
    json.end_object();
  }
  json.end_array();
  json.end_object();
  return json.str();
}

}  // namespace fw::bench
