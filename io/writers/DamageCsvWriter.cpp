#include "io/writers/DamageCsvWriter.hpp"

#include <utility>

#include "base/AtomicFile.hpp"

namespace fw::io {

DamageCsvWriter::DamageCsvWriter(std::filesystem::path directory, std::vector<DamageTree> trees)
    : directory_(std::move(directory)), trees_(std::move(trees)) {}

void DamageCsvWriter::begin() {
  write_records(std::vector<trees::TreeDamageRecord>(trees_.size()));
}

void DamageCsvWriter::write(const OutputFrame& frame) {
  if (!frame.damage.empty()) write_records(frame.damage);
}

void DamageCsvWriter::finish(const RunOutcome& outcome) {
  if (!outcome.damage.empty()) write_records(outcome.damage);
}

void DamageCsvWriter::write_records(const std::vector<trees::TreeDamageRecord>& records) const {
  base::write_text_atomically("DamageCsvWriter", directory_ / "damage.csv", damage_csv(trees_, records));
}

}  // namespace fw::io
