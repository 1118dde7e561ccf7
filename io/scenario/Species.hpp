// The reader of an item of a scenario's forest.species (Species.cpp), which read_forest (Forest.cpp) calls.
//
//   forest.species.push_back(read_species(loader, item, forest.species, seed));
#pragma once

#include <cstdint>
#include <vector>

#include "io/scenario/Reader.hpp"
#include "io/settings/Species.hpp"

namespace fw::io::reader {

/// One item of forest.species, after the species `earlier`.
Species read_species(const Loader& loader, const Field& item, const std::vector<Species>& earlier,
                     std::uint64_t global_seed);

}  // namespace fw::io::reader
