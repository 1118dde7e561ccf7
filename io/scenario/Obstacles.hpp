// The reader of a scenario's obstacles (Obstacles.cpp), which load_scenario (Load.cpp) calls.
//
//   scenario.obstacles = read_obstacles(loader, *obstacles);
#pragma once

#include <vector>

#include "io/scenario/Reader.hpp"
#include "io/settings/Obstacle.hpp"

namespace fw::io::reader {

std::vector<Obstacle> read_obstacles(const Loader& loader, const Field& field);

}  // namespace fw::io::reader
