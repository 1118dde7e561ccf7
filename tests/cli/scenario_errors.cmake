# cmake -DFORESTWIND=<binary> -DWORK=<scratch folder> -DSCENARIOS=<repo>/scenarios -P scenario_errors.cmake
#
# Every bad scenario makes `forestwind run` and `forestwind check` exit with code 2, print FILE:LINE: KEY,
# and leave no output folder behind. The example scenarios pass `forestwind check`.
cmake_minimum_required(VERSION 3.25)
if(NOT FORESTWIND OR NOT WORK OR NOT SCENARIOS)
  message(FATAL_ERROR "pass -DFORESTWIND=<binary> -DWORK=<scratch folder> -DSCENARIOS=<scenarios folder>")
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
file(WRITE "${WORK}/tree.tree" "0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 2 0.05\n")
file(WRITE "${WORK}/broken.tree" "0 -1 0 0 0 0.1\n1 0 0 0 1 0.08\n2 1 0 0 two 0.05\n")

# A valid scenario; each case below replaces one line of it.
set(base
"scenario: bad_case
time: {end: 2.0, dt: auto}
domain: {origin: [0, 0, 0], size: [32, 16, 16], cell_size: 2.0}
wind: {speed: 5.0, direction: 270.0}
forest:
  species:
    - name: shrub
      skeleton: {file: tree.tree}
      modes: {count: 4}
  trees:
    - {species: shrub, position: [16, 8]}
output: {directory: OUTDIR, interval: 1.0}
")

# expect_bad(<case name> <line> <key> <line to replace> <replacement>)
function(expect_bad name line key old new)
  string(REPLACE "${old}" "${new}" text "${base}")
  string(REPLACE "OUTDIR" "${WORK}/out_${name}" text "${text}")
  if(text STREQUAL base)
    message(FATAL_ERROR "case ${name}: '${old}' is not in the base scenario")
  endif()
  file(WRITE "${WORK}/${name}.yaml" "${text}")
  foreach(command run check)
    execute_process(COMMAND "${FORESTWIND}" ${command} "${WORK}/${name}.yaml"
                    RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(NOT code EQUAL 2)
      message(FATAL_ERROR "${command} ${name}: exit code '${code}', expected 2\nstdout:\n${out}\nstderr:\n${err}")
    endif()
    string(FIND "${err}" "${line}: ${key}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${command} ${name}: stderr does not name '${line}: ${key}':\n${err}")
    endif()
    if(EXISTS "${WORK}/out_${name}")
      message(FATAL_ERROR "${command} ${name}: left the output folder ${WORK}/out_${name} behind")
    endif()
  endforeach()
  message(STATUS "${name}: exit code 2, ${err}")
endfunction()

expect_bad(unknown_key "${WORK}/unknown_key.yaml:4" "wind.gustiness"
           "wind: {speed: 5.0, direction: 270.0}" "wind: {speed: 5.0, direction: 270.0, gustiness: 3}")
expect_bad(wrong_type "${WORK}/wrong_type.yaml:9" "forest.species[0].modes.count"
           "modes: {count: 4}" "modes: {count: many}")
expect_bad(negative_size "${WORK}/negative_size.yaml:3" "domain.size"
           "size: [32, 16, 16]" "size: [32, -16, 16]")
expect_bad(negative_spin_up "${WORK}/negative_spin_up.yaml:2" "time.spin_up: a number >= 0 and <= 1e9 (s) expected, got '-3'"
           "time: {end: 2.0, dt: auto}" "time: {end: 2.0, dt: auto, spin_up: -3}")
expect_bad(word_spin_up "${WORK}/word_spin_up.yaml:2" "time.spin_up: a number >= 0 and <= 1e9 (s) expected, got 'long'"
           "time: {end: 2.0, dt: auto}" "time: {end: 2.0, dt: auto, spin_up: long}")
expect_bad(tree_outside "${WORK}/tree_outside.yaml:11" "forest.trees[0].position"
           "position: [16, 8]" "position: [16, 80]")
expect_bad(expression "${WORK}/expression.yaml:4" "wind.speed"
           "speed: 5.0" "speed: \"5 + (t\"")
expect_bad(missing_skeleton "${WORK}/missing_skeleton.yaml:8" "forest.species[0].skeleton.file"
           "{file: tree.tree}" "{file: no_such.tree}")
# A skeleton file that exists but does not parse: the error names the .tree file's line and column.
expect_bad(unreadable_skeleton "${WORK}/broken.tree:3" "z" "{file: tree.tree}" "{file: broken.tree}")
# The 3-node skeleton has 12 DOFs: 12 modes are one too many, found once the skeleton is read.
expect_bad(too_many_modes "${WORK}/too_many_modes.yaml:9" "forest.species[0].modes.count"
           "modes: {count: 4}" "modes: {count: 12}")
# A log profile whose reference height (10 m, the default) lies below d + z0.
expect_bad(log_profile "${WORK}/log_profile.yaml:4" "wind.profile.displacement_height"
           "wind: {speed: 5.0, direction: 270.0}"
           "wind: {speed: 5.0, direction: 270.0, profile: {type: log, roughness_length: 0.5, displacement_height: 12}}")

# Turbulence needs its integral length scale; the map's line is blamed for the missing key.
expect_bad(turbulence_length "${WORK}/turbulence_length.yaml:4" "wind.turbulence.length_scale"
           "wind: {speed: 5.0, direction: 270.0}"
           "wind: {speed: 5.0, direction: 270.0, turbulence: {intensity: 0.1}}")
# The mean forcing drives a domain without inflow only: here the four sides are auto.
expect_bad(forcing_open "${WORK}/forcing_open.yaml:4" "wind.forcing"
           "wind: {speed: 5.0, direction: 270.0}"
           "wind: {speed: 5.0, direction: 270.0, forcing: {relaxation_time: 5}}")
# rough is a ground condition.
expect_bad(rough_side "${WORK}/rough_side.yaml:4" "boundaries.west"
           "domain: {origin: [0, 0, 0], size: [32, 16, 16], cell_size: 2.0}"
           "domain: {origin: [0, 0, 0], size: [32, 16, 16], cell_size: 2.0}\nboundaries: {west: rough}")
# Leaves: a bad model word; leaves without foliage (no leaf area index, blamed at the species entry); a stride
# of attached leaves below 1.
expect_bad(leaves_model "${WORK}/leaves_model.yaml:10" "forest.species[0].leaves.model"
           "modes: {count: 4}" "modes: {count: 4}\n      leaves: {model: flutter}")
expect_bad(leaves_without_foliage "${WORK}/leaves_without_foliage.yaml:7"
           "forest.species[0].canopy.leaf_area_index"
           "modes: {count: 4}" "modes: {count: 4}\n      leaves: {}")
expect_bad(leaves_attached "${WORK}/leaves_attached.yaml:12" "output.leaves.attached"
           "interval: 1.0}" "interval: 1.0, leaves: {attached: 0}}")

# A leaf area index whose leaves overflow what one tree may carry (the leaf stage's 32-bit count): refused by
# the plan at the key, not a crash of the leaf count (it was "forestwind: vector::reserve", exit 1). A small
# generated broadleaf: the shrub above is a stick, whose crown has no area to carry leaves. The index is the
# largest a scenario takes (18), the leaves a square micrometre each.
expect_bad(leaf_count_overflow "${WORK}/leaf_count_overflow.yaml:10" "forest.species[0].canopy.leaf_area_index"
           "{file: tree.tree}\n      modes: {count: 4}"
           "{generate: {preset: broadleaf, height: 3.0, seed: 3}}\n      modes: {count: 4}\n      canopy: {leaf_area_index: 18}\n      leaves: {area: 1e-12}")

# A ',' that begins a YAML document outside any [ ] or { }: yaml-cpp 0.7 never finishes parsing it and filled
# the memory (found by tests/fuzz/scenario_fuzz); io/YamlDocuments stops it at the comma's line.
expect_bad(comma_document "${WORK}/comma_document.yaml:13" "(yaml): valid YAML expected"
           "interval: 1.0}" "interval: 1.0}\n,")

# Tree models: an unknown dynamics word; the modal model's `modes` on a springs species; the springs model's
# keys on a modal one (the default).
expect_bad(dynamics_word "${WORK}/dynamics_word.yaml:10" "forest.species[0].dynamics"
           "modes: {count: 4}" "modes: {count: 4}\n      dynamics: pendulum")
expect_bad(modes_on_springs "${WORK}/modes_on_springs.yaml:9" "forest.species[0].modes"
           "modes: {count: 4}" "modes: {count: 4}\n      dynamics: springs")
expect_bad(springs_on_modal "${WORK}/springs_on_modal.yaml:10" "forest.species[0].springs"
           "modes: {count: 4}" "modes: {count: 4}\n      springs: {max_angle_deg: 10}")

# A stand's own leaf area index: past the forests' largest (the loader), and on the shrub, a stick whose crown
# has no horizontal extent to carry leaves (the plan, once the skeleton is read).
expect_bad(stand_lai_above "${WORK}/stand_lai_above.yaml:11" "forest.stands[0].leaf_area_index" "  trees:"
           "  stands:\n    - {species: shrub, region: {min: [4, 4], max: [12, 12]}, spacing: 4, leaf_area_index: 20}\n  trees:")
expect_bad(stand_lai_no_crown "${WORK}/stand_lai_no_crown.yaml:11" "forest.stands[0].leaf_area_index" "  trees:"
           "  stands:\n    - {species: shrub, region: {min: [4, 4], max: [12, 12]}, spacing: 4, leaf_area_index: 2}\n  trees:")

# Storm damage's keys: an unknown strength preset; a knot factor past clear wood's 1; deep rooting, which the
# table gives on soil A only, on soil C; a strength without a preset that lacks one of its four numbers; a
# modulus of rupture past any wood's; damage enabled with a species without strength (its entry's line).
expect_bad(strength_preset "${WORK}/strength_preset.yaml:10"
           "forest.species[0].strength.preset: one of sitka_spruce | norway_spruce | scots_pine | birch expected, got 'oak'"
           "modes: {count: 4}" "modes: {count: 4}\n      strength: {preset: oak}")
expect_bad(strength_knot_factor "${WORK}/strength_knot_factor.yaml:10"
           "forest.species[0].strength.knot_factor: a number > 0 and <= 1 expected, got '1.5'"
           "modes: {count: 4}" "modes: {count: 4}\n      strength: {preset: norway_spruce, knot_factor: 1.5}")
expect_bad(strength_deep_on_c "${WORK}/strength_deep_on_c.yaml:10"
           "forest.species[0].strength.rooting: one of mean (the table has no anchorage for deep rooting on soil C, line 10) expected, got 'deep'"
           "modes: {count: 4}" "modes: {count: 4}\n      strength: {preset: sitka_spruce, soil: C, rooting: deep}")
expect_bad(strength_no_anchorage "${WORK}/strength_no_anchorage.yaml:10"
           "forest.species[0].strength.anchorage: a number >= 10 and <= 1000 (N m/kg), needed without a preset expected (required), got nothing"
           "modes: {count: 4}"
           "modes: {count: 4}\n      strength: {modulus_of_rupture: 4.0e7, knot_factor: 0.9, green_density: 850}")
expect_bad(strength_mor_bound "${WORK}/strength_mor_bound.yaml:10"
           "forest.species[0].strength.modulus_of_rupture: a number >= 1e6 and <= 3e8 (Pa) expected, got '1e30'"
           "modes: {count: 4}" "modes: {count: 4}\n      strength: {preset: scots_pine, modulus_of_rupture: 1e30}")
expect_bad(damage_without_strength "${WORK}/damage_without_strength.yaml:8"
           "forest.species[0].strength: a map {preset, soil, rooting, modulus_of_rupture, knot_factor, green_density, anchorage} expected (required: forest.damage.enabled is true on line 6), got nothing"
           "  species:" "  damage: {enabled: true}\n  species:")

# The example scenarios are valid.
file(GLOB examples "${SCENARIOS}/*.yaml")
foreach(example ${examples})
  execute_process(COMMAND "${FORESTWIND}" check "${example}" RESULT_VARIABLE code OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "check ${example}: exit code ${code}\n${out}\n${err}")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK}")
