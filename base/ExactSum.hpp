// An exact sum of floats whose value does not depend on the order of the terms or on how they are split.
//
//   fw::base::ExactSum sum;
//   for (float v : column_sums) sum.add(v);
//   fw::base::ExactSum other = ...;        // another rank's or work-group's terms
//   sum += other;                          // the same as adding its terms one by one
//   double total = sum.value();
//
// Every finite float is an integer m (|m| < 2^24) times 2^(e - 150), e its biased exponent field (1 ..
// 254; subnormals share e = 1). The sum keeps one 64-bit integer a value of e and adds m to it, which is
// exact. So the bins, and value() computed from them alone, are the same for any order of the same terms
// and for any split of them into sums merged with +=. Two runs that add the same cell values, on one rank or
// on many, in rows or in columns, get the same bits: what makes a run's global sums independent of its
// decomposition (docs/parallel.md). MPI merges sums by adding their slots() as 64-bit integers.
//
// Limits: at most kMaxTerms terms in all (a bin then holds < 2^63). NaN, +inf and -inf are counted, and
// value() is NaN after a NaN or after both infinities, else the infinity.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace fw::base {

class ExactSum {
 public:
  /// Bins for the biased exponents 0 .. 254 (bin 0 stays empty: subnormals go to bin 1, their scale).
  static constexpr int kBins = 255;
  /// The counts of NaN, +inf and -inf follow the bins.
  static constexpr int kNanSlot = kBins, kPositiveInfinitySlot = kBins + 1, kNegativeInfinitySlot = kBins + 2;
  static constexpr int kSlots = kBins + 3;
  /// 2^39 terms of |m| < 2^24 stay below 2^63.
  static constexpr std::int64_t kMaxTerms = std::int64_t{1} << 39;

  void add(float value);
  void add(std::span<const float> values) {
    for (float v : values) add(v);
  }
  ExactSum& operator+=(const ExactSum& other);

  /// The sum rounded to double (within one unit in its last place), or the non-finite result.
  double value() const;

  /// The state as 64-bit integers, to be added slot by slot (MPI_SUM on MPI_INT64_T).
  std::array<std::int64_t, kSlots>& slots() { return slots_; }
  const std::array<std::int64_t, kSlots>& slots() const { return slots_; }

 private:
  std::array<std::int64_t, kSlots> slots_{};
};

}  // namespace fw::base
