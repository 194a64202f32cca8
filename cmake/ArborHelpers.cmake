# One-line helpers so that every library, test and benchmark target is declared the same way.
include_guard(GLOBAL)

# arbor_glob(VAR dir...): the .cc files under the given directories (recursive). New files are picked up at
# the next build (CONFIGURE_DEPENDS), so adding a variant never means editing a CMakeLists.txt.
function(arbor_glob out)
  set(files)
  foreach(dir IN LISTS ARGN)
    file(GLOB_RECURSE found CONFIGURE_DEPENDS ${dir}/*.cc)
    list(APPEND files ${found})
  endforeach()
  list(SORT files)
  set(${out} ${files} PARENT_SCOPE)
endfunction()

# arbor_precompile_headers(target): precompiles the standard, Eigen, fmt and GoogleTest headers for a test
# binary, under clang only, where it saves up to 4 s of each sanitized test file (models_test 29.7 s to 25.4 s,
# factors_test 20.3 s to 16.3 s on the 2-core VM), about a tenth of CI's sanitizer build. Not for the
# libraries: there it saved nothing or cost time (fastslam_run.cc 22.5 s to 27.8 s). Not for gcc 12, which
# spends longer building the header (11 s) than the files gain; gcc builds, the Release one included, parse
# as before and keep checking that every file includes what it uses. Only third-party and standard headers
# go in, so a change to Arbor's own headers rebuilds what includes them and no more.
function(arbor_precompile_headers target)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT ARBOR_PRECOMPILE_HEADERS)
    return()
  endif()
  target_precompile_headers(${target} PRIVATE
    <algorithm> <array> <cmath> <cstdint> <filesystem> <fstream> <map> <memory> <optional> <random> <sstream>
    <string> <string_view> <unordered_map> <utility> <vector>
    <Eigen/Cholesky> <Eigen/Core> <Eigen/Eigenvalues> <Eigen/LU> <fmt/core.h> <fmt/format.h> <gtest/gtest.h>)
endfunction()

# arbor_add_test(name DIRS dir... DEPS target...): one GoogleTest binary from every .cc in DIRS.
function(arbor_add_test name)
  cmake_parse_arguments(ARG "" "" "DIRS;DEPS" ${ARGN})
  arbor_glob(srcs ${ARG_DIRS})
  if(NOT srcs)
    return()
  endif()
  add_executable(${name} ${srcs})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main arbor_options)
  target_compile_definitions(${name} PRIVATE ARBOR_TEST_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(CMAKE_CXX_COMPILER_ID STREQUAL "Clang" AND ARBOR_PRECOMPILE_HEADERS)
    arbor_precompile_headers(${name})
  else()
    # gcc: four test files per compiler run, so GoogleTest, Eigen and the engine's headers are parsed once
    # for them (Release test objects 534 s -> 464 s of CPU on the 2-core VM). Under clang the precompiled
    # header does that job, and batching on top of it cost time (399 s -> 460 s). Names at namespace scope
    # must be unique within a test binary, anonymous namespaces included; -DARBOR_UNITY_TESTS=OFF compiles
    # the files one by one.
    set_target_properties(${name} PROPERTIES UNITY_BUILD ${ARBOR_UNITY_TESTS} UNITY_BUILD_BATCH_SIZE 4)
  endif()
  gtest_discover_tests(${name} WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "ARBOR_BINARY_DIR=${PROJECT_BINARY_DIR}")
endfunction()

# arbor_add_benchmark(name SOURCE file DEPS target...): a Google Benchmark program, built by the 'bench' target.
function(arbor_add_benchmark name)
  cmake_parse_arguments(ARG "" "SOURCE" "DEPS" ${ARGN})
  add_executable(${name} EXCLUDE_FROM_ALL ${ARG_SOURCE})
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} benchmark::benchmark arbor_options)
  add_dependencies(bench ${name})
endfunction()
