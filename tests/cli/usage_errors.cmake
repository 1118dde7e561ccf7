# cmake -DFORESTWIND=<path to the forestwind binary> -P usage_errors.cmake
#
# Bad usage exits with code 2 (docs/design.md "Command line") and says what was wrong. None of these cases
# needs an OpenCL device: the arguments are rejected before one is chosen.
if(NOT FORESTWIND)
  message(FATAL_ERROR "pass -DFORESTWIND=<path to the forestwind binary>")
endif()

# expect_usage_error(<what stderr must contain, or ""> <arguments>...)
function(expect_usage_error needle)
  execute_process(
    COMMAND "${FORESTWIND}" ${ARGN}
    RESULT_VARIABLE code
    OUTPUT_VARIABLE out
    ERROR_VARIABLE err)
  string(REPLACE ";" " " command_line "${ARGN}")
  if(NOT code EQUAL 2)
    message(FATAL_ERROR "forestwind ${command_line} exited with '${code}', expected 2\n"
                        "stdout:\n${out}\nstderr:\n${err}")
  endif()
  if(needle)
    string(FIND "${err}" "${needle}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "stderr of forestwind ${command_line} does not name '${needle}':\n${err}")
    endif()
  endif()
  message(STATUS "forestwind ${command_line}: exit code 2")
endfunction()

expect_usage_error("--grid" bench wind --grid 0x4x4)
expect_usage_error("--grid" bench wind --grid 4x4)
expect_usage_error("" nosuchcommand)
expect_usage_error("" bench nosuchbench)
expect_usage_error("" bench wind --steps 0)

# render --field damage draws the folder's damage.csv (docs/pictures.md): a folder without one is refused
# before any frame is read, and nothing is written.
set(no_damage "${CMAKE_CURRENT_BINARY_DIR}/test-work/usage_errors/no_damage")
file(REMOVE_RECURSE "${no_damage}")
file(MAKE_DIRECTORY "${no_damage}")
expect_usage_error("render: --field damage: ${no_damage} has no damage.csv (run with forest.damage.enabled)"
                   render "${no_damage}" --field damage -o "${no_damage}/damage.png")
if(EXISTS "${no_damage}/damage.png")
  message(FATAL_ERROR "render --field damage without damage.csv wrote a picture")
endif()
file(REMOVE_RECURSE "${no_damage}")
