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

# Include paths. Headers are included as "<folder>/<file>.h" from the source root, but a library
# does not see the whole tree: it gets an include root of its own, build/include/<library>, that
# holds only its own folder (a symbolic link to it), PUBLIC, so it sees another folder only
# through a library it links. A library that links neither slammtt_runtime nor slammtt_msgs
# cannot include runtime/ or a message header: the include does not resolve. Programs and tests
# see the whole tree.
#
# slammtt_include_root(<target> <folder> <PUBLIC|INTERFACE>): <folder> (relative to the source
# root) as <target>'s include root.
function(slammtt_include_root target folder scope)
  set(root ${CMAKE_BINARY_DIR}/include/${target})
  get_filename_component(parent ${root}/${folder} DIRECTORY)
  file(MAKE_DIRECTORY ${parent})
  if(NOT EXISTS ${root}/${folder})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${root}/${folder} SYMBOLIC)
  endif()
  target_include_directories(${target} ${scope} ${root})
endfunction()

# slammtt_library(<name> [PURE] SOURCES ... [PUBLIC_LIBS ...] [PRIVATE_LIBS ...])
# A static library of the current folder (include root: that folder, above). PURE: an algorithm
# library (docs/DEVELOPING.md, "Layers"): configuring fails when it links slammtt_runtime or
# slammtt_msgs, and ctest checks that it cannot include runtime/ or a message header
# (slammtt_purity_tests, tests purity.<name>.*).
function(slammtt_library name)
  cmake_parse_arguments(ARG "PURE" "" "SOURCES;PUBLIC_LIBS;PRIVATE_LIBS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  slammtt_include_root(${name} ${folder} PUBLIC)
  target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_LIBS} PRIVATE ${ARG_PRIVATE_LIBS})
  slammtt_warnings(${name})
  if(ARG_PURE)
    foreach(lib ${ARG_PUBLIC_LIBS} ${ARG_PRIVATE_LIBS})
      if(lib STREQUAL "slammtt_runtime" OR lib STREQUAL "slammtt_msgs")
        message(FATAL_ERROR "${name} is a pure library and links ${lib}")
      endif()
      get_property(impure GLOBAL PROPERTY SLAMMTT_IMPURE_LIBRARIES)
      if(lib IN_LIST impure)
        message(FATAL_ERROR "${name} is a pure library and links ${lib}, which is not")
      endif()
    endforeach()
    set_property(GLOBAL APPEND PROPERTY SLAMMTT_PURE_LIBRARIES ${name})
  else()
    set_property(GLOBAL APPEND PROPERTY SLAMMTT_IMPURE_LIBRARIES ${name})
  endif()
endfunction()

# slammtt_purity_tests(): for every PURE library, two probes (object libraries outside `all`
# that link it and include runtime/config.h or slammtt_msgs/pose_t.hpp) and two tests that build
# them and pass when the compiler cannot find that header. Called once, after every folder.
function(slammtt_purity_tests)
  get_property(pure GLOBAL PROPERTY SLAMMTT_PURE_LIBRARIES)
  foreach(lib ${pure})
    foreach(probe runtime message)
      set(target purity_probe_${lib}_${probe})
      add_library(${target} OBJECT EXCLUDE_FROM_ALL
        ${PROJECT_SOURCE_DIR}/cmake/purity_probe_${probe}.cc)
      target_link_libraries(${target} PRIVATE ${lib})
      add_test(NAME purity.${lib}.cannot_include_${probe}
        COMMAND ${CMAKE_COMMAND} --build ${CMAKE_BINARY_DIR} --target ${target})
      if(probe STREQUAL "runtime")
        set(header "runtime/config.h")
      else()
        set(header "slammtt_msgs/pose_t.hpp")
      endif()
      # Probes build one after the other: two builds of one tree at once would share its files.
      set_tests_properties(purity.${lib}.cannot_include_${probe} PROPERTIES
        PASS_REGULAR_EXPRESSION "${header}: No such file or directory"
        RESOURCE_LOCK slammtt_build_tree
        LABELS unit
        TIMEOUT 300)
    endforeach()
  endforeach()
endfunction()

# slammtt_executable(<name> SOURCES ... [LIBS ...]): a program in build/bin.
function(slammtt_executable name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS})
  slammtt_warnings(${name})
  install(TARGETS ${name} RUNTIME DESTINATION bin)
  set_property(GLOBAL APPEND PROPERTY SLAMMTT_PROGRAMS ${name})
endfunction()

# slammtt_test(<name> SOURCES ... [LIBS ...] [LABELS ...] [NETNS] [ONE_PROCESS] [TIMEOUT s])
# A GoogleTest program; each TEST becomes one ctest test. NETNS runs it in a network namespace
# of its own (tests/support/netns-run), so LCM traffic never leaves it and concurrent tests never
# hear each other. ONE_PROCESS makes the whole program one ctest test instead, for TESTs that
# share expensive runs made once per process (the target tests' replays of 20 seeds).
# Labels: "unit" (default), "integration", "soak", "fuzz", "target", "target_open" (left out
# of the default run), "long" (minutes each; left out of the default run, which runs a short
# version).
function(slammtt_test name)
  if(NOT SLAMMTT_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "NETNS;ONE_PROCESS" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS unit)
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  add_executable(${name} ${ARG_SOURCES})
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
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
  if(ARG_ONE_PROCESS)
    if(ARG_NETNS)
      message(FATAL_ERROR "slammtt_test(${name}): ONE_PROCESS with NETNS is not supported")
    endif()
    add_test(NAME ${name} COMMAND ${name})
    # No SKIP_REGULAR_EXPRESSION here: one skipped TEST would hide the others' failures.
    set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT})
    return()
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
  target_include_directories(${name} PRIVATE ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} benchmark::benchmark)
  slammtt_warnings(${name})
endfunction()
