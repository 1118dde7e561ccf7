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
