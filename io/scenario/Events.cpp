// events: gusts.
#include "io/scenario/Events.hpp"

#include "io/schema/EventKeys.hpp"

namespace fw::io::reader {

std::vector<GustEvent> read_events(const Loader& loader, const Field& field, const WindSource& wind) {
  std::vector<GustEvent> events;
  for (const Field& item : loader.items(field)) {
    const Section<schema::kEventKeys, "events[]"> kind(loader, item);  // gust is required
    const Section<schema::kEventKeys, "events[].gust"> map(loader, kind.require<"gust">());
    GustEvent gust;
    gust.start = loader.number(map.require<"start">());
    gust.duration = loader.number(map.require<"duration">());
    gust.peak_speed = loader.number(map.require<"peak_speed">());
    gust.center = loader.vector<3>(map.require<"center">());
    gust.radius = loader.number(map.require<"radius">());
    gust.travel_with_wind = true;
    if (const auto travel = map.get<"travel">()) {
      const Key& key = key_of(*travel);
      if (travel->node.IsSequence() && travel->node.size() == 3) {
        gust.travel_with_wind = false;
        for (std::size_t i = 0; i < 3; ++i) gust.travel[i] = loader.component(*travel, i, key);
      } else if (!(travel->node.IsScalar() && travel->node.Scalar() == key.word)) {  // the word: with_wind
        loader.expected(*travel);
      }
    }
    if (gust.travel_with_wind) gust.travel = wind_vector(wind, gust.start);
    events.push_back(gust);
  }
  return events;
}

}  // namespace fw::io::reader
