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
