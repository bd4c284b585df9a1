# Helpers that give every target of the project the same warnings and layout.

# slammtt_warnings(<target>): the project's warning set, errors with SLAMMTT_WERROR.
function(slammtt_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
    -Wnon-virtual-dtor -Wcast-align -Wunused -Woverloaded-virtual -Wnull-dereference
    -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
  if(SLAMMTT_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# slammtt_library(<name> SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# A static library whose headers are included as "<folder>/<file>.h" from the source root.
function(slammtt_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  slammtt_warnings(${name})
endfunction()

# slammtt_executable(<name> SOURCES ... [LIBS ...]): a program in build/bin.
function(slammtt_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  slammtt_warnings(${name})
  install(TARGETS ${name} RUNTIME DESTINATION bin)
endfunction()

# slammtt_test(<name> SOURCES ... [LIBS ...] [LABELS ...] [NETNS] [TIMEOUT s])
# A GoogleTest program; each TEST becomes one ctest test. NETNS runs it in a network namespace
# of its own (tests/support/netns-run), so LCM traffic never leaves it and concurrent tests never
# hear each other. Labels: "unit" (default), "integration", "soak", "fuzz", "target".
function(slammtt_test name)
  if(NOT SLAMMTT_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "NETNS" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    SLAMMTT_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SLAMMTT_BIN_DIR="${CMAKE_BINARY_DIR}/bin")
  slammtt_warnings(${name})
  if(ARG_NETNS)
    # gtest_discover_tests (CMake 3.25) has no launcher option; it honours the target's
    # CROSSCOMPILING_EMULATOR, read when it is called, for listing and for running the tests.
    set_property(TARGET ${name} PROPERTY CROSSCOMPILING_EMULATOR
      ${PROJECT_SOURCE_DIR}/tests/support/netns-run)
  endif()
  gtest_discover_tests(${name}
    DISCOVERY_MODE PRE_TEST
    TEST_PREFIX "${name}."
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
endfunction()

# slammtt_benchmark(<name> SOURCES ... [LIBS ...]): a Google Benchmark program in build/bin.
function(slammtt_benchmark name)
  if(NOT SLAMMTT_BUILD_BENCHMARKS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} benchmark::benchmark)
  slammtt_warnings(${name})
endfunction()
