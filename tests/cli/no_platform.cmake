# cmake -DFORESTWIND=<path to the forestwind binary> -P no_platform.cmake
#
# Runs `forestwind devices` with an ICD loader that finds no OpenCL platform and checks that the binary
# exits with code 3 and tells the user which Debian package provides one. Debian's ocl-icd loader reads
# the vendor .icd files from the folder in OCL_ICD_VENDORS (instead of /etc/OpenCL/vendors) and adds the
# libraries listed in OCL_ICD_FILENAMES, so an empty folder and an empty list leave it with no platform.
if(NOT FORESTWIND)
  message(FATAL_ERROR "pass -DFORESTWIND=<path to the forestwind binary>")
endif()

string(RANDOM LENGTH 12 tag)
set(empty_dir "${CMAKE_CURRENT_BINARY_DIR}/fw_no_icd_vendors_${tag}")
file(REMOVE_RECURSE "${empty_dir}")
file(MAKE_DIRECTORY "${empty_dir}")

execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "OCL_ICD_VENDORS=${empty_dir}" "OCL_ICD_FILENAMES=" "${FORESTWIND}" devices
  RESULT_VARIABLE code
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
file(REMOVE_RECURSE "${empty_dir}")

if(NOT code EQUAL 3)
  message(FATAL_ERROR "forestwind devices without an OpenCL platform exited with '${code}', expected 3\n"
                      "stdout:\n${out}\nstderr:\n${err}")
endif()
if(NOT err MATCHES "pocl-opencl-icd")
  message(FATAL_ERROR "stderr of forestwind devices does not name pocl-opencl-icd:\n${err}")
endif()
message(STATUS "exit code 3, stderr: ${err}")
