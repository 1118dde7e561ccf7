// Fuzz target: damage.csv read back for `forestwind render --field damage` and `plot` (viz/DamageTable).
// Feeds: the bytes as scratch/damage.csv. Checks: every tree read keeps the reading rules (a standing tree
// without failure values, a failed one with a time, a break height within its height and a utilisation of at
// least 1, each id once), and the counts at any time and over a span add up to the trees.
// Clean refusals: base::SourceError naming the file ("FILE:LINE: COLUMN: ..."). Bugs: anything else: a
// crash, a sanitizer report, another exception, a hang, a huge allocation.
#include <algorithm>
#include <cstdint>
#include <set>

#include "base/SourceError.hpp"
#include "tests/fuzz/FuzzSupport.hpp"
#include "viz/DamageTable.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using fw::trees::TreeState;
  const auto path = fw::fuzz::write_input("damage.csv", data, size);
  try {
    const fw::viz::DamageTable table = fw::viz::read_damage_table(path);
    std::set<int> ids;
    double last_failure = 0.0;
    for (const fw::viz::DamagedTree& t : table.trees) {
      if (!ids.insert(t.id).second) fw::fuzz::fail("a tree id read twice");
      const bool standing = t.state == TreeState::standing;
      if (standing != !t.time || standing != !t.break_height || standing != !t.top_wind)
        fw::fuzz::fail("failure values that do not match the state");
      if (!standing && (*t.break_height < 0.0 || *t.break_height > t.height || t.max_utilisation < 1.0))
        fw::fuzz::fail("a failed tree outside the rules");
      if (t.time) last_failure = std::max(last_failure, *t.time);
    }
    const auto total = [&](int standing, int broken, int overturned) {
      return std::size_t(standing) + std::size_t(broken) + std::size_t(overturned);
    };
    for (const double time : {0.0, 0.5 * last_failure, last_failure}) {
      const auto counts = table.counts_at(time);
      if (total(counts[0], counts[1], counts[2]) != table.trees.size())
        fw::fuzz::fail("counts that miss trees");
    }
    const fw::viz::DamageCounts series = table.counts_over(0.0, last_failure);
    for (std::size_t n = 0; n < series.time.size(); ++n)
      if (total(series.standing[n], series.broken[n], series.overturned[n]) != table.trees.size() ||
          (n > 0 && !(series.time[n] > series.time[n - 1])))
        fw::fuzz::fail("a count series that misses trees or does not move forward in time");
  } catch (const fw::base::SourceError& e) {
    fw::fuzz::expect_names_file(e, path);
  }
  return 0;
}
