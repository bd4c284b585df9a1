# Tests that open pseudo-terminals through libserialport. Include this file from a test
# folder's CMakeLists.txt (any order, any number of times):
#
#   include(${PROJECT_SOURCE_DIR}/tests/support/pty/SlammttPtyTest.cmake)
#   slammtt_pty_test(p3dx_pty_test SOURCES ... LIBS ... LABELS integration [NETNS])
#
# slammtt_pty_test() takes the arguments of slammtt_test() and runs every test of the program
# under tests/support/pty/pty-run with the modem-line shim (and under netns-run first with
# NETNS), so the program and every process it starts can open /dev/pts/N with libserialport.
# Inside, SLAMMTT_IN_PTY_NS=1 and SLAMMTT_PTY_STATE_DIR are set (see pty-run). The shim's
# target, slammtt_pty_shim, is defined in tests/support/CMakeLists.txt.

function(slammtt_pty_test name)
  cmake_parse_arguments(ARG "NETNS" "" "" ${ARGN})
  set(shim ${CMAKE_BINARY_DIR}/lib/libslammtt_pty_shim.so)
  set(launcher ${PROJECT_SOURCE_DIR}/tests/support/pty/pty-run --shim ${shim} --)
  if(ARG_NETNS)
    set(launcher ${PROJECT_SOURCE_DIR}/tests/support/netns-run ${launcher})
  endif()
  # slammtt_test() reads the target's emulator when it registers the tests; the variable
  # initialises that property on the target it creates.
  set(CMAKE_CROSSCOMPILING_EMULATOR ${launcher})
  slammtt_test(${name} ${ARG_UNPARSED_ARGUMENTS})
  if(TARGET ${name})
    add_dependencies(${name} slammtt_pty_shim)
  endif()
endfunction()
