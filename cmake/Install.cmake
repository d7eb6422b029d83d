# `cmake --install` puts the headers, libvksplat.a (shaders are embedded in it), the CLI, a CMake
# package (find_package(vksplat) -> vksplat::vksplat) and a pkg-config file (vksplat.pc) under the
# prefix. tests/install/install_test.sh builds examples/find_package against an installed copy.
include(CMakePackageConfigHelpers)

set(VKSPLAT_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/vksplat)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/vksplat TYPE INCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/generated_include/vksplat/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vksplat)
install(TARGETS vksplat EXPORT vksplatTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
if(TARGET vksplat_cli)
  install(TARGETS vksplat_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
install(EXPORT vksplatTargets NAMESPACE vksplat:: DESTINATION ${VKSPLAT_CMAKE_DIR})

# The OpenCV modules the library links (opencv_core -> core, ...), for find_dependency.
string(REPLACE "opencv_" "" VKSPLAT_OPENCV_COMPONENTS "${OpenCV_LIBS}")
string(REPLACE ";" " " VKSPLAT_OPENCV_COMPONENTS "${VKSPLAT_OPENCV_COMPONENTS}")
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vksplatConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/vksplatConfig.cmake INSTALL_DESTINATION ${VKSPLAT_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vksplatConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vksplatConfig.cmake ${PROJECT_BINARY_DIR}/vksplatConfigVersion.cmake
        DESTINATION ${VKSPLAT_CMAKE_DIR})

configure_file(${PROJECT_SOURCE_DIR}/cmake/vksplat.pc.in ${PROJECT_BINARY_DIR}/vksplat.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/vksplat.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
