// damage.csv (io/DamageCsv.hpp): what the storm did to every tree, rewritten whole and atomically at every
// frame and at the end of the run (docs/damage.md, "Outputs").
//
//   fw::io::DamageCsvWriter damage("out/windthrow", trees);   // trees: io::DamageTree, whole-forest order
#pragma once

#include <filesystem>
#include <vector>

#include "io/DamageCsv.hpp"
#include "io/writers/FrameWriter.hpp"

namespace fw::io {

class DamageCsvWriter : public FrameWriter {
 public:
  DamageCsvWriter(std::filesystem::path directory, std::vector<DamageTree> trees);

  std::string name() const override { return "damage.csv"; }
  FrameNeeds needs() const override { return {.damage = true}; }
  /// Writes every tree standing, so that the folder has the file from the start.
  void begin() override;
  /// A resumed run's file is the checkpoint's records, written at its first frame: nothing to take over.
  void resume(const OutputResume& /*resume*/) override {}
  void write(const OutputFrame& frame) override;
  /// The records at the end (RunOutcome::damage), when the run could gather them.
  void finish(const RunOutcome& outcome) override;

 private:
  void write_records(const std::vector<trees::TreeDamageRecord>& records) const;

  std::filesystem::path directory_;
  std::vector<DamageTree> trees_;
};

}  // namespace fw::io
