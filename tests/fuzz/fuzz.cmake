# The fuzz targets of tests/fuzz (docs/fuzzing.md), one per reader of user files.
#
# Every build compiles each target a second time with tests/fuzz/replay_main.cpp, a plain main that feeds
# it every file of its seed corpus and of its regressions (every input that once crashed or hung it); CTest
# runs that replay, so no clang is needed to keep old crashes fixed. With -DFORESTWIND_FUZZ=ON and clang
# (`make fuzz`, `make sanitize`), each target is also linked against libFuzzer as fuzz_<name>.

# name: the target's source tests/fuzz/<name>.cpp and its folders corpus/<name>, regressions/<name>;
# reader: what the CTest test names; libraries: what it links.
function(forestwind_fuzz_target name reader)
  set(libraries ${ARGN})
  set(source ${CMAKE_SOURCE_DIR}/tests/fuzz/${name}.cpp)
  add_executable(${name}_replay ${source} tests/fuzz/replay_main.cpp)
  target_link_libraries(${name}_replay PRIVATE forestwind_fuzz_support ${libraries})
  add_test(NAME "fuzz: every input that once crashed the ${reader} and every seed is refused cleanly or read"
           COMMAND ${name}_replay ${CMAKE_SOURCE_DIR}/tests/fuzz/corpus/${name}
                   ${CMAKE_SOURCE_DIR}/tests/fuzz/regressions/${name})
  if(FORESTWIND_FUZZ)
    add_executable(fuzz_${name} ${source})
    target_link_libraries(fuzz_${name} PRIVATE forestwind_fuzz_support ${libraries})
    target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
    add_dependencies(fuzz fuzz_${name})
  endif()
endfunction()

add_library(forestwind_fuzz_support STATIC tests/fuzz/FuzzSupport.cpp)
target_include_directories(forestwind_fuzz_support PUBLIC ${CMAKE_SOURCE_DIR})
target_link_libraries(forestwind_fuzz_support PUBLIC forestwind_base)
# The scenario target copies the example terrain next to its scenario, so that seeds naming it read.
target_compile_definitions(forestwind_fuzz_support PUBLIC FORESTWIND_SOURCE_DIR="${CMAKE_SOURCE_DIR}")

if(FORESTWIND_FUZZ)
  add_custom_target(fuzz)
  # The species whose cache entry seeds the basis cache target, written by the code itself.
  add_executable(basis_cache_seed tests/fuzz/basis_cache_seed.cpp)
  target_link_libraries(basis_cache_seed PRIVATE forestwind_fuzz_support forestwind_trees)
  add_dependencies(fuzz basis_cache_seed)
endif()

forestwind_fuzz_target(scenario_fuzz "scenario loader and planner" forestwind_app)
forestwind_fuzz_target(expression_fuzz "expression parser" forestwind_io)
forestwind_fuzz_target(tree_file_fuzz ".tree reader" forestwind_trees)
forestwind_fuzz_target(qsm_fuzz "TreeQSM reader" forestwind_trees)
forestwind_fuzz_target(heightmap_fuzz "heightmap reader" forestwind_fluid)
forestwind_fuzz_target(basis_cache_fuzz "basis cache reader" forestwind_trees)
forestwind_fuzz_target(run_folder_fuzz "run folder reader" forestwind_viz)
forestwind_fuzz_target(probe_table_fuzz "probes.csv reader" forestwind_viz)
forestwind_fuzz_target(damage_table_fuzz "damage.csv reader" forestwind_viz)
forestwind_fuzz_target(tree_inventory_fuzz "tree inventory reader" forestwind_io)
