# slammtt_lcm_types(<target> <lcm files...>)
# Runs `lcm-gen --cpp` at build time (not configure time, so a changed type never leaves a stale
# header) into the build tree, and exposes the generated headers through an INTERFACE target.
function(slammtt_lcm_types target)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(headers "")
  foreach(lcm_file ${ARGN})
    get_filename_component(abs ${lcm_file} ABSOLUTE)
    # (the ';' ending the line would split a CMake list: match the name only)
    file(STRINGS ${abs} package_line REGEX "^package[ \t]+[A-Za-z0-9_]+")
    string(REGEX MATCH "[A-Za-z0-9_]+$" package "${package_line}")
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
