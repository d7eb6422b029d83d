# Compiles GLSL compute shaders to SPIR-V at build time and embeds the words in C headers
# (`<name>.spv.h` defining `const uint32_t <name>_spv[]`), so a program that links vksplat
# needs no shader files beside it.
function(vksplat_embed_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES;INCLUDE_DIRS" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  file(MAKE_DIRECTORY ${out_dir}/shaders)
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I${dir})
  endforeach()
  set(headers)
  foreach(src ${ARG_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    set(header ${out_dir}/shaders/${name}.spv.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.2 ${include_flags}
              --depfile ${header}.d --vn ${name}_spv -o ${header} ${CMAKE_CURRENT_SOURCE_DIR}/${src}
      DEPENDS ${src}
      DEPFILE ${header}.d
      COMMENT "Compiling shader ${src}"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_spirv)
  target_include_directories(${target} INTERFACE ${out_dir})
endfunction()
