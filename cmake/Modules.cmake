# One static library per module folder (src/<module>/ -> vksplat_<module>), linking only the
# modules it uses, so that the build checks the layering of ../shared/DESIGN.md:
# - a module compiles with its own private headers ("<module>/<name>.hpp") and no other module's:
#   each private folder is reached through a folder of its own holding one link to it, so an
#   include of another module's internals does not find the file. Where a module needs another's
#   internals (the gpu plumbing for the modules that record passes, render's frame for train's
#   backward pass), the owner offers them as vksplat_<module>_internal and the user links that by name;
# - a module's tests link the module and what they use, not the whole library, so a call into a
#   module that is not linked fails to link.
# libvksplat.a, what applications link (vksplat::vksplat, pkg-config), holds every module's objects.

add_library(vksplat_headers INTERFACE)
# vksplat/version.hpp is generated from the project's version, beside the written headers.
configure_file(${PROJECT_SOURCE_DIR}/cmake/version.hpp.in ${PROJECT_BINARY_DIR}/generated_include/vksplat/version.hpp)
target_include_directories(vksplat_headers INTERFACE $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                                     $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated_include>)
target_link_libraries(vksplat_headers INTERFACE glm::glm Vulkan::Headers)
target_compile_features(vksplat_headers INTERFACE cxx_std_20)

# The warnings every module and its tests compile with. Not -Wmissing-field-initializers: Vulkan's
# idiom `VkFooInfo info{VK_STRUCTURE_TYPE_FOO_INFO}` value-initialises the other members to zero
# on purpose, and GCC 12 warns about that and about designated initialisers (`{.ratio = 0.5}`)
# alike: about 300 such warnings in a clean build hid the few that meant something.
set(VKSPLAT_WARNINGS -Wall -Wextra -Wpedantic -Wno-missing-field-initializers)

# The folder through which `module`'s private headers are included, and nothing else.
function(vksplat_private_include_dir module out)
  set(dir ${PROJECT_BINARY_DIR}/private_include/${module})
  if(NOT EXISTS ${dir}/${module})
    file(MAKE_DIRECTORY ${dir})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/src/${module} ${dir}/${module} SYMBOLIC)
  endif()
  set(${out} ${dir} PARENT_SCOPE)
endfunction()

# Private headers only (src/stats/): an INTERFACE target that modules link by name.
function(vksplat_header_module name)
  vksplat_private_include_dir(${name} dir)
  add_library(vksplat_${name} INTERFACE)
  target_include_directories(vksplat_${name} INTERFACE ${dir})
endfunction()

# vksplat_module(<name> [INTERNAL] [TARGET <target>] [LINKS <target>...] [PRIVATE_LINKS <target>...]
#                [SOURCES <file>...])
#   Every .cpp of src/<name>/ (and SOURCES) in vksplat_<name> (or TARGET); LINKS are the modules its
#   public headers expose or its code calls, PRIVATE_LINKS what only its .cpp files use. INTERNAL
#   also makes <target>_internal: its private headers, for the modules that link it by name.
function(vksplat_module name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "INTERNAL" "TARGET" "LINKS;PRIVATE_LINKS;SOURCES")
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/${name}/*.cpp)
  set(target vksplat_${name})
  if(arg_TARGET)
    set(target ${arg_TARGET})
  endif()
  add_library(${target} STATIC ${sources} ${arg_SOURCES})
  vksplat_private_include_dir(${name} dir)
  target_include_directories(${target} PRIVATE ${dir} ${VOLK_INCLUDE_DIR})
  target_link_libraries(${target} PUBLIC vksplat_headers ${arg_LINKS} PRIVATE ${arg_PRIVATE_LINKS})
  target_compile_options(${target} PRIVATE ${VKSPLAT_WARNINGS})
  # volk supplies the entry points inside the library; applications keep their own prototypes.
  target_compile_definitions(${target} PRIVATE VK_NO_PROTOTYPES)
  vksplat_private_volk(${target} ${VOLK_INCLUDE_DIR}/volk.h)
  if(arg_INTERNAL)
    add_library(${target}_internal INTERFACE)
    target_include_directories(${target}_internal INTERFACE ${dir})
    target_link_libraries(${target}_internal INTERFACE ${target})
  endif()
  set_property(GLOBAL APPEND PROPERTY VKSPLAT_MODULES ${target})  # libvksplat.a holds them all
endfunction()
