// time: the run's span and time step.
#include "io/scenario/Time.hpp"

namespace fw::io::reader {

void read_time(const Loader& loader, const Field& field, TimeSettings& time) {
  const Section<schema::kTimeKeys, "time"> map(loader, field);
  const Field end = map.require<"end">();
  time.end = loader.number(end);
  time.end_line = end.line;
  time.dt_line = time.spin_up_line = field.line;
  if (const auto dt = map.get<"dt">()) {
    time.dt = loader.number_or_word(*dt);
    time.dt_line = dt->line;
  }
  if (const auto cfl = map.get<"cfl">()) time.cfl = loader.number(*cfl);
  if (const auto spin_up = map.get<"spin_up">()) {
    time.spin_up = loader.number(*spin_up);
    time.spin_up_line = spin_up->line;
  }
}

}  // namespace fw::io::reader
