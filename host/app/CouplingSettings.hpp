// How the trees and the wind exchange momentum, as the planner resolves it (host/app/plan/CouplingPlan.cpp)
// and CoupledStep applies it: the canopy drag fed back into the wind, the modal integrator, the strong-wind
// correction of output frames, Stam's unresolved forcing and every species' leaves.
#pragma once

#include <vector>

#include "fluid/DragLaw.hpp"

#include "trees/ModalIntegrator.hpp"
#include "trees/SpeciesLeaves.hpp"
#include "trees/TreeDamage.hpp"
#include "trees/TreeDynamics.hpp"
#include "trees/UnresolvedTurbulence.hpp"

namespace fw::host {

struct CouplingSettings {
  trees::ModalIntegrator integrator = trees::ModalIntegrator::exact;
  /// Per cell, the drag density k (1/m, fluid/CanopyField); empty = one-way coupling (the air feels no tree).
  std::vector<float> drag_density;
  /// Diener's strong-wind correction of the deformation on output frames (trees/StrongWindCorrection).
  bool strong_wind_correction = true;
  /// How the drag coefficients vary with the wind (fluid/DragLaw.hpp), on the air and the trees alike.
  fluid::DragLaw drag_law;
  /// Stam's forcing of every tree by the turbulence the grid cannot resolve (trees/UnresolvedTurbulence);
  /// off unless `enabled`. Its intensity follows the run (TimeInputs::unresolved_intensity).
  trees::UnresolvedTurbulenceSettings unresolved;
  /// The leaves of each species (docs/leaves.md), one per forest species, in the skeleton frame of its
  /// basis; empty, or none with leaves: no leaf stage.
  std::vector<trees::SpeciesLeaves> leaves;
  /// The model that moves each species' trees (trees/TreeDynamics.hpp), one per forest species; empty: every
  /// species modal.
  std::vector<trees::SpeciesDynamics> dynamics;
  /// Storm damage (forest.damage, docs/damage.md): every tree's loads against its species' strength, one
  /// per forest species when enabled.
  trees::DamageSettings damage;
};

}  // namespace fw::host
