// stats.nc for a run (output.statistics; docs/statistics.md): the wind's profiles against height, averaged
// over each horizontal plane's fluid cells (host/stages/PlaneStatistics) and over time, for the whole domain
// and for each region, and the time series of the run's state.
//
//   fw::host::StatisticsRecorder statistics(cc, plan, coupled, world, folder / "stats.nc");
//   statistics.after_step(report);          // each step: samples what is due, writes a finished record
//   statistics.write();                     // everything so far (rank 0), before a checkpoint and at the end
//
// A record at each multiple t_n of `interval` is the mean of the samples taken in (t_n - averaging, t_n]:
// every `sample_every`-th step in the window and the step that reaches t_n (its time is that step's). Each
// sample's moments are about its own plane mean. The time series take a row every `series_every`-th step.
// Every value is the same on every rank; rank 0 writes. The file is rewritten whole, under a temporary
// name, at each record, each checkpoint and the end, so that a killed run keeps every record written
// before. A checkpoint keeps the window's sums (saved()); a resumed run reads the file back, drops what
// lies past the checkpoint and goes on (resume()), so that its file is the uninterrupted run's.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fluid/PlaneProfiles.hpp"
#include "host/app/CoupledStep.hpp"
#include "host/app/Schedule.hpp"
#include "host/app/SimulationPlan.hpp"
#include "host/runtime/Communicator.hpp"
#include "host/stages/PlaneStatistics.hpp"
#include "io/StatsNetcdf.hpp"

namespace fw::host {

/// The file's name in the output folder.
inline constexpr const char* kStatisticsFile = "stats.nc";

/// The time series' variables (stats.nc's group timeseries), in their order.
std::vector<io::StatsVariable> series_columns();

/// A region of the statistics: its group name (empty for the whole domain), its cells and its box, m.
struct StatisticsArea {
  std::string name;
  PlaneRegion cells;
  std::array<double, 2> min{}, max{};
};

/// The areas `plan` averages over: the whole domain first, then output.statistics.regions, then a stand_N
/// for each stand when output.statistics.stands is set.
std::vector<StatisticsArea> statistics_areas(const SimulationPlan& plan);

class StatisticsRecorder {
 public:
  /// Off (nothing sampled, nothing written) without plan.output.statistics.
  StatisticsRecorder(ComputeContext& cc, const SimulationPlan& plan, CoupledStep& coupled,
                     const Communicator& world, std::filesystem::path file);

  bool on() const { return statistics_.has_value(); }
  /// After each step of the run (collective): the samples and the time-series row due at it, and a record
  /// when the step reaches one's time (written at once).
  void after_step(const CoupledStepReport& report);
  /// Writes stats.nc with every record and row so far (rank 0; the others wait for nothing).
  void write();
  /// The averaging window so far and each area's scales, as a checkpoint keeps them (numbers the same on
  /// every rank).
  std::vector<double> saved() const;
  /// Goes on from a checkpoint at `time` (s) that saved `saved`: reads stats.nc back and keeps its records
  /// and rows up to `time`. Empty `saved` (a checkpoint of a run without statistics) starts afresh.
  void resume(double time, const std::vector<double>& saved);
  /// Wall time spent sampling and writing, ms.
  double ms() const { return ms_; }

 private:
  /// Adds a sample of every area to the window; the domain's sample is returned for the time series.
  fluid::PlaneProfiles sample_window(double speed_bound);
  /// The time series' row from the domain's sample `domain` and the step's report (collective).
  std::vector<double> series_row(const fluid::PlaneProfiles& domain, const CoupledStepReport& report);
  /// u* at the ground from the domain's profiles at its lowest fluid height k: over a rough ground the log
  /// law of the wall stage, kappa / ln(z_1 / z0) times the plane's mean horizontal wind; else the fourth root
  /// of the squared total momentum fluxes there.
  double ground_friction_velocity(const fluid::PlaneProfiles& p, int k) const;
  /// The window's mean as the next record.
  void close_record(double time);

  const SimulationPlan& plan_;
  CoupledStep& coupled_;
  const Communicator& world_;
  std::filesystem::path file_;
  std::optional<PlaneStatistics> statistics_;
  std::vector<StatisticsArea> areas_;
  std::vector<PlaneScales> scales_;  // per area, its last sample's (PlaneStatistics::sample)
  Schedule records_{0.0};
  // The window: per area, per profile, per height, the sum of its samples' values.
  std::vector<double> window_;
  long samples_ = 0;
  io::StatsFile out_;
  double ms_ = 0.0;
};

}  // namespace fw::host
