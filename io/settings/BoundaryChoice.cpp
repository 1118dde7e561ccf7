#include "io/settings/BoundaryChoice.hpp"

namespace fw::io {

std::string to_string(BoundaryChoice choice) {
  switch (choice) {
    case BoundaryChoice::automatic:
      return "auto";
    case BoundaryChoice::inflow:
      return "inflow";
    case BoundaryChoice::outflow:
      return "outflow";
    case BoundaryChoice::slip:
      return "slip";
    case BoundaryChoice::no_slip:
      return "no_slip";
    case BoundaryChoice::periodic:
      return "periodic";
    case BoundaryChoice::rough:
      return "rough";
  }
  return "?";
}

}  // namespace fw::io
