# cmake -DFORESTWIND=<path to the forestwind binary> -DWORK=<scratch folder> -P tree_commands.cmake
#
# `forestwind tree generate` and `forestwind tree modes` end to end: files written and read back, JSON keys,
# determinism of the generator, and bad input exiting with code 2 and naming the file and line.
cmake_minimum_required(VERSION 3.25)
if(NOT FORESTWIND OR NOT WORK)
  message(FATAL_ERROR "pass -DFORESTWIND=<binary> -DWORK=<scratch folder>")
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

# run(<expected exit code> <output variable prefix> <arguments>...): runs forestwind, checks the exit code.
function(run expected prefix)
  execute_process(COMMAND "${FORESTWIND}" ${ARGN} RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(REPLACE ";" " " command_line "${ARGN}")
  if(NOT code EQUAL expected)
    message(FATAL_ERROR "forestwind ${command_line} exited with '${code}', expected ${expected}\n"
                        "stdout:\n${out}\nstderr:\n${err}")
  endif()
  set(${prefix}_out "${out}" PARENT_SCOPE)
  set(${prefix}_err "${err}" PARENT_SCOPE)
endfunction()

function(require_contains text needle what)
  string(FIND "${text}" "${needle}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "${what} does not contain '${needle}':\n${text}")
  endif()
endfunction()

# --- generate: deterministic per seed ------------------------------------------------------------------------
run(0 gen tree generate --preset conifer --height 12 --seed 4 -o "${WORK}/a.tree")
run(0 gen tree generate --preset conifer --height 12 --seed 4 -o "${WORK}/b.tree")
run(0 gen tree generate --preset conifer --height 12 --seed 5 -o "${WORK}/c.tree")
file(SHA256 "${WORK}/a.tree" hash_a)
file(SHA256 "${WORK}/b.tree" hash_b)
file(SHA256 "${WORK}/c.tree" hash_c)
if(NOT hash_a STREQUAL hash_b)
  message(FATAL_ERROR "the same seed gave two different .tree files")
endif()
if(hash_a STREQUAL hash_c)
  message(FATAL_ERROR "seeds 4 and 5 gave the same .tree file")
endif()
require_contains("${gen_out}" "conifer tree, seed 5" "tree generate's summary")

# --- modes --json: the keys of docs/design.md -------------------------------------------------------------------
run(0 modes tree modes "${WORK}/a.tree" --modes 6 --json)
string(JSON count LENGTH "${modes_out}" frequencies_hz)
string(JSON nodes GET "${modes_out}" nodes)
string(JSON dofs GET "${modes_out}" dofs)
string(JSON seconds GET "${modes_out}" seconds)
if(NOT count EQUAL 6)
  message(FATAL_ERROR "frequencies_hz has ${count} entries, expected 6:\n${modes_out}")
endif()
math(EXPR expected_dofs "6 * (${nodes} - 1)")
if(NOT dofs EQUAL expected_dofs)
  message(FATAL_ERROR "dofs ${dofs} for ${nodes} nodes, expected ${expected_dofs}")
endif()
# Frequencies ascend and a 12 m conifer sways at a fraction of a hertz to a few hertz.
set(previous 0)
foreach(i RANGE 5)
  string(JSON f GET "${modes_out}" frequencies_hz ${i})
  if(f LESS previous OR f LESS_EQUAL 0.05 OR f GREATER 20)
    message(FATAL_ERROR "frequency ${i} = ${f} Hz is out of order or implausible:\n${modes_out}")
  endif()
  set(previous ${f})
endforeach()
message(STATUS "tree modes --json: ${nodes} nodes, ${dofs} DOFs, ${seconds} s")

# --- modes -o: ParaView files --------------------------------------------------------------------------------
run(0 table tree modes "${WORK}/a.tree" --modes 4 --density 700 -o "${WORK}/modes")
require_contains("${table_out}" "dominant direction" "the mode table")
require_contains("${table_out}" "4 of 4 converged" "the solver status line")
foreach(name skeleton.vtp modes.vtp modes.png)
  if(NOT EXISTS "${WORK}/modes/${name}")
    message(FATAL_ERROR "tree modes -o did not write ${name}")
  endif()
endforeach()
file(READ "${WORK}/modes/modes.vtp" vtp LIMIT 20000)
require_contains("${vtp}" "Name=\"mode_04\"" "modes.vtp")
require_contains("${vtp}" "Name=\"frequencies_hz\"" "modes.vtp")

# --- a TreeQSM cylinder table --------------------------------------------------------------------------------
file(WRITE "${WORK}/qsm.txt"
  "0.10 1.0 0 0 0 0 0 1 0\n"
  "0.08 1.0 0 0 1 0 0 1 1\n"
  "0.05 0.8 0 0 1 0.6 0 0.8 1\n"
  "0.06 1.0 0 0 2 0 0 1 2\n")
run(0 qsm tree modes "${WORK}/qsm.txt" --modes 3 --json)
string(JSON nodes GET "${qsm_out}" nodes)
if(NOT nodes EQUAL 5)
  message(FATAL_ERROR "4 cylinders should give 5 nodes, got ${nodes}")
endif()

# --- bad input: exit code 2, the file and line named, nothing written -------------------------------------------
file(WRITE "${WORK}/bad.tree" "0 -1 0 0 0 0.2\n1 0 0 0 1 0.1\n2 1 0 0 2 -0.05\n")
run(2 bad tree modes "${WORK}/bad.tree" -o "${WORK}/bad_out")
require_contains("${bad_err}" "bad.tree:3: radius:" "the error for a negative radius")
if(EXISTS "${WORK}/bad_out")
  message(FATAL_ERROR "a failed tree modes left the output folder ${WORK}/bad_out behind")
endif()
run(2 missing tree modes "${WORK}/no_such.tree")
require_contains("${missing_err}" "no_such.tree" "the error for a missing file")
run(2 too_many tree modes "${WORK}/qsm.txt" --modes 30)
require_contains("${too_many_err}" "ask for at most 23" "the error for too many modes")
run(2 preset tree generate --preset baobab -o "${WORK}/x.tree")
if(EXISTS "${WORK}/x.tree")
  message(FATAL_ERROR "a bad preset left ${WORK}/x.tree behind")
endif()
file(REMOVE_RECURSE "${WORK}")
