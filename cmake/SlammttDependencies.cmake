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

# Java (optional): the message types' jar and slammtt-lcm-spy (docs/tools.md, "Java"). The C++
# build needs none of it. javac and jar come from a JDK (default-jdk-headless); lcm.jar from
# liblcm-java, whose pkg-config file names it; jchart2d.jar (libjchart2d-java) draws lcm-spy's
# charts. SLAMMTT_JAVA is ON when all of them are there.
find_package(Java 1.8 COMPONENTS Runtime Development QUIET)
pkg_check_modules(LCM_JAVA QUIET lcm-java)
if(LCM_JAVA_FOUND)
  pkg_get_variable(lcm_java_classpath lcm-java classpath)
  get_filename_component(lcm_java_dir "${lcm_java_classpath}" DIRECTORY)
endif()
find_file(LCM_JAR NAMES lcm.jar HINTS ${lcm_java_dir} PATHS /usr/share/java)
find_file(JCHART2D_JAR NAMES jchart2d.jar PATHS /usr/share/java)
set(SLAMMTT_JAVA OFF)
set(SLAMMTT_JAVA_MISSING "")
if(NOT Java_JAVA_EXECUTABLE OR NOT Java_JAVAC_EXECUTABLE OR NOT Java_JAR_EXECUTABLE)
  string(APPEND SLAMMTT_JAVA_MISSING " a JDK (java, javac, jar: default-jdk-headless)")
endif()
if(NOT LCM_JAR)
  string(APPEND SLAMMTT_JAVA_MISSING " lcm.jar (liblcm-java)")
endif()
if(NOT JCHART2D_JAR)
  string(APPEND SLAMMTT_JAVA_MISSING " jchart2d.jar (libjchart2d-java)")
endif()
if(SLAMMTT_JAVA_MISSING STREQUAL "")
  set(SLAMMTT_JAVA ON)
  message(STATUS "Java types and slammtt-lcm-spy: ${Java_JAVAC_EXECUTABLE}, ${LCM_JAR}")
else()
  message(STATUS "Java types and slammtt-lcm-spy: not built, missing:${SLAMMTT_JAVA_MISSING}"
                 " (scripts/install-deps.sh installs them; the Java tests are skipped)")
endif()
