# install() rules for hofem's core and its CMake package, included at the end of
# core/CMakeLists.txt (after every layer exists). `cmake --install build --prefix P`
# then lets another project write
#   find_package(hofem REQUIRED)   # CMAKE_PREFIX_PATH=P
#   target_link_libraries(app PRIVATE hofem::core)   # or one layer: hofem::mesh
# Installed layout:
#   lib/libhofem_<layer>.a                 one static library per layer
#   include/hofem/<layer>/*.hpp            included as "layer/file.hpp"
#   lib/cmake/hofem/hofemConfig.cmake      + Version, Targets, and the dependency
#                                          finder shared with the project
# The build keeps its per-layer include directories (layer enforcement); an
# installed consumer sees include/hofem, all layers, as a user of the whole core.
if(HOFEM_SANITIZE OR HOFEM_FUZZ)
  return()  # instrumented builds are for testing, not for installing
endif()
include(CMakePackageConfigHelpers)

get_property(_hofem_layers GLOBAL PROPERTY HOFEM_LAYERS)
set(_hofem_targets hofem_core)
foreach(_l IN LISTS _hofem_layers)
  list(APPEND _hofem_targets hofem_${_l})
  file(GLOB _headers CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${_l}/*.hpp)
  install(FILES ${_headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hofem/${_l})
endforeach()

# Eigen's fixed-size types are aligned by the instruction set (32 bytes with AVX),
# so a consumer compiled without the libraries' -march=native would disagree with
# them on the layout of the same struct: pass the flag on with the targets.
if(HOFEM_NATIVE)
  target_compile_options(hofem_core INTERFACE $<INSTALL_INTERFACE:-march=native>)
endif()

set(_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/hofem)
install(TARGETS ${_hofem_targets} EXPORT hofemTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/hofem)
install(EXPORT hofemTargets NAMESPACE hofem:: DESTINATION ${_cmake_dir})

configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/hofemConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/hofemConfig.cmake INSTALL_DESTINATION ${_cmake_dir})
# 0.x: a minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/hofemConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/hofemConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/hofemConfigVersion.cmake
              ${CMAKE_SOURCE_DIR}/cmake/HofemLibraryDependencies.cmake
              ${CMAKE_SOURCE_DIR}/cmake/HofemRequire.cmake
        DESTINATION ${_cmake_dir})
