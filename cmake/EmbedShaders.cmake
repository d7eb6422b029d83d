# Compiles GLSL compute shaders to SPIR-V at build time and embeds the words in the library, so a
# program that links vksplat needs no shader files beside it. Each shader, in the folder of the
# module that records it (shaders/<module>/<name>.comp), becomes a typed kernel: the generated
# header shaders/<module>/<name>.kernel.hpp (cmake/EmbedKernel.cmake says what it declares).
set(VKSPLAT_EMBED_KERNEL_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/EmbedKernel.cmake)

function(vksplat_embed_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES;INCLUDE_DIRS" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  file(MAKE_DIRECTORY ${out_dir}/shaders)
  string(REPLACE ";" "|" include_dirs "${ARG_INCLUDE_DIRS}")
  set(headers)
  foreach(src ${ARG_SOURCES})
    get_filename_component(name ${src} NAME_WE)
    get_filename_component(module ${src} DIRECTORY)
    if(NOT module)
      message(FATAL_ERROR "${src}: a shader belongs in the folder of the module that records it (shaders/README.md)")
    endif()
    file(MAKE_DIRECTORY ${out_dir}/shaders/${module})
    set(spirv ${out_dir}/shaders/${module}/${name}.spv.h)
    set(kernel ${out_dir}/shaders/${module}/${name}.kernel.hpp)
    add_custom_command(
      OUTPUT ${spirv} ${kernel}
      COMMAND ${CMAKE_COMMAND} -DGLSLANG=${GLSLANG_VALIDATOR} -DSOURCE=${CMAKE_CURRENT_SOURCE_DIR}/${src}
              -DNAME=${name} -DMODULE=${module} -DINCLUDE_DIRS=${include_dirs} -DSPIRV=${spirv} -DKERNEL=${kernel}
              -P ${VKSPLAT_EMBED_KERNEL_SCRIPT}
      DEPENDS ${src} ${VKSPLAT_EMBED_KERNEL_SCRIPT}
      DEPFILE ${spirv}.d
      COMMENT "Compiling kernel ${src}"
      VERBATIM)
    list(APPEND headers ${kernel})
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_spirv)
  # Kernel headers include their layout headers as "shaders/<module>/<name>.h", from the project root.
  target_include_directories(${target} INTERFACE ${out_dir} ${PROJECT_SOURCE_DIR})
endfunction()
