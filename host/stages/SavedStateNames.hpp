// The names under which the stages save what they carry from step to step (StageState), and the stages'
// own names in a checkpoint: one list for the stages that save, restore and take their share of it over
// other ranks (WindGrid::share_of, ForestStages::share_of, LeafStages::share_of).
//
//   state.save(cc, fw::host::saved::kModalState, state_);      // ForestStages::save_state
#pragma once

namespace fw::host::saved {

// The stages, as CoupledStep::save_state names them.
inline constexpr const char* kWindStage = "wind";
inline constexpr const char* kTreesStage = "trees";
inline constexpr const char* kLeavesStage = "leaves";

// WindGrid: the velocity's face arrays, one a component; its parts' cell arrays (WindPart::saved_arrays).
inline constexpr const char* kVelocity[] = {"u", "v", "w"};
inline constexpr const char* kPressureSolution = "phi";
inline constexpr const char* kEddyViscosity = "eddy_viscosity";
inline constexpr const char* kSubgridEnergy = "subgrid_energy";

// ForestStages: 2 floats (q, qdot) an instance-mode; ForestStages::kTravelFloats an instance.
inline constexpr const char* kModalState = "modal_state";
inline constexpr const char* kTravelled = "travelled";
// BranchStages (the element tree models): FW_JOINT_FLOATS an entry of an element tree; the springs' clock.
inline constexpr const char* kJointState = "joints";
inline constexpr const char* kBranchClock = "branch_clock";
// DamageStages (storm damage): an FwTreeDamage record a tree.
inline constexpr const char* kDamage = "damage";

// LeafStages: per slot a state byte, four float4 and the flight drag; per own leaf the flutter angle and
// rate; the counters.
inline constexpr const char* kLeafState = "state";
inline constexpr const char* kLeafVectors[] = {"position", "velocity", "normal", "flight"};
inline constexpr const char* kFlightDrag = "flight_drag";
inline constexpr const char* kFlutterAngle = "theta";
inline constexpr const char* kFlutterRate = "theta_rate";
inline constexpr const char* kLeafCounters = "counters";

}  // namespace fw::host::saved
