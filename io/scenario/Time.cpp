// time: the run's span and time step.
#include "io/scenario/Time.hpp"
#include "base/TextNumber.hpp"

namespace fw::io::reader {

void read_time(const Loader& loader, const Field& field, TimeSettings& time) {
  const Section<schema::kTimeKeys, "time"> map(loader, field);
  time.end = loader.number(map.require<"end">());
  if (const auto dt = map.get<"dt">()) {
    const Key& key = key_of(*dt);
    if (!(dt->node.IsScalar() && dt->node.Scalar() == key.word)) {  // the word: auto
      const std::optional<double> step =
          dt->node.IsScalar() ? base::parse_finite(dt->node.Scalar()) : std::nullopt;
      if (!step || !(*step > 0.0)) loader.expected(*dt);
      time.dt = *step;
    }
  }
  if (const auto cfl = map.get<"cfl">()) time.cfl = loader.number(*cfl);
  if (const auto spin_up = map.get<"spin_up">()) time.spin_up = loader.number(*spin_up);
}

}  // namespace fw::io::reader
