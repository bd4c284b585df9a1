# Every dependency is a Debian package (scripts/install-deps.sh installs them).
find_package(PkgConfig REQUIRED)
find_package(Threads REQUIRED)

# LCM 1.3.1 ships no CMake package: pkg-config finds it (it links glib).
pkg_check_modules(LCM REQUIRED IMPORTED_TARGET lcm>=1.3.1)
find_program(LCM_GEN_EXECUTABLE lcm-gen REQUIRED)

find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(yaml-cpp REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
pkg_check_modules(SERIALPORT REQUIRED IMPORTED_TARGET libserialport)

# CHOLMOD (SuiteSparse) for the smoother. SuiteSparse 7 ships a CMake package with the target
# SuiteSparse::CHOLMOD; SuiteSparse 5 (Debian 12's libsuitesparse-dev) ships neither a CMake
# package nor a pkg-config file for it: the header and the library are found by name (the shared
# library brings its own AMD, COLAMD, METIS, BLAS and LAPACK dependencies).
find_package(CHOLMOD CONFIG QUIET)
if(NOT TARGET SuiteSparse::CHOLMOD)
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
  find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
  add_library(SuiteSparse::CHOLMOD UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::CHOLMOD PROPERTIES
    IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}")
endif()

if(SLAMMTT_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
if(SLAMMTT_BUILD_BENCHMARKS)
  find_package(benchmark REQUIRED)
endif()

# yaml-cpp 0.7 on Debian exports the target "yaml-cpp" without a namespace.
if(TARGET yaml-cpp AND NOT TARGET yaml-cpp::yaml-cpp)
  add_library(yaml-cpp::yaml-cpp ALIAS yaml-cpp)
endif()
