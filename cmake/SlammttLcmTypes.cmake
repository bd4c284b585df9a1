# slammtt_lcm_package(<lcm file> <variable>): the package the file declares (lcm-gen writes its
# outputs into a folder of that name), an error when there is none.
function(slammtt_lcm_package lcm_file variable)
  file(STRINGS ${lcm_file} package_line REGEX "^package[ \t]+[A-Za-z0-9_]+")
  # The ';' ending the line splits it into a CMake list: the name is matched inside, not at its
  # end.
  if(NOT package_line MATCHES "^package[ \t]+([A-Za-z0-9_]+)")
    message(FATAL_ERROR "${lcm_file}: no 'package NAME;' line")
  endif()
  set(${variable} ${CMAKE_MATCH_1} PARENT_SCOPE)
endfunction()

# slammtt_lcm_types(<target> <lcm files...>)
# Runs `lcm-gen --cpp` at build time (not configure time, so a changed type never leaves a stale
# header) into the build tree, and exposes the generated headers through an INTERFACE target.
function(slammtt_lcm_types target)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(headers "")
  foreach(lcm_file ${ARGN})
    get_filename_component(abs ${lcm_file} ABSOLUTE)
    slammtt_lcm_package(${abs} package)
    get_filename_component(type_name ${lcm_file} NAME_WE)
    set(header ${out_dir}/${package}/${type_name}.hpp)
    add_custom_command(OUTPUT ${header}
      COMMAND ${LCM_GEN_EXECUTABLE} --cpp --cpp-hpath ${out_dir} ${abs}
      DEPENDS ${abs}
      COMMENT "lcm-gen --cpp ${type_name}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${target}_gen DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_gen)
  # SYSTEM: generated code is not ours to warn about.
  target_include_directories(${target} SYSTEM INTERFACE ${out_dir})
  target_link_libraries(${target} INTERFACE PkgConfig::LCM)
endfunction()

# slammtt_lcm_java_types(<target> <jar> <lcm files...>)
# Runs `lcm-gen --java` at build time into the build tree and compiles the classes with javac
# against lcm.jar into <jar> (a target of ALL, its JAR_FILE property names the jar). Needs
# SLAMMTT_JAVA (cmake/SlammttDependencies.cmake). The classes are compiled afresh each time any
# type changes, so a removed type never stays in the jar.
function(slammtt_lcm_java_types target jar)
  set(source_dir ${CMAKE_CURRENT_BINARY_DIR}/java)
  set(classes_dir ${CMAKE_CURRENT_BINARY_DIR}/java-classes)
  set(sources "")
  foreach(lcm_file ${ARGN})
    get_filename_component(abs ${lcm_file} ABSOLUTE)
    slammtt_lcm_package(${abs} package)
    get_filename_component(type_name ${lcm_file} NAME_WE)
    set(source ${source_dir}/${package}/${type_name}.java)
    add_custom_command(OUTPUT ${source}
      COMMAND ${LCM_GEN_EXECUTABLE} --java --jpath ${source_dir} ${abs}
      DEPENDS ${abs}
      COMMENT "lcm-gen --java ${type_name}"
      VERBATIM)
    list(APPEND sources ${source})
  endforeach()
  get_filename_component(jar_dir ${jar} DIRECTORY)
  add_custom_command(OUTPUT ${jar}
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${classes_dir}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${classes_dir} ${jar_dir}
    # -nowarn: generated code is not ours to warn about.
    COMMAND ${Java_JAVAC_EXECUTABLE} -nowarn -encoding UTF-8 -cp ${LCM_JAR} -d ${classes_dir}
            ${sources}
    COMMAND ${Java_JAR_EXECUTABLE} cf ${jar} -C ${classes_dir} .
    DEPENDS ${sources} ${LCM_JAR}
    COMMENT "javac: ${jar}"
    VERBATIM)
  add_custom_target(${target} ALL DEPENDS ${jar})
  set_target_properties(${target} PROPERTIES JAR_FILE ${jar})
endfunction()
