# Installation: `cmake --install <build> --prefix P` gives
#   P/bin/coif                       the command (COIF_BUILD_TOOLS)
#   P/share/coif/assets/             its assets (the embedded default style and lights, as files)
#   P/include/coif/coif.h            the umbrella header of the runtime; the libraries' headers under
#   P/include/coif/<folder>/…        their source paths, so `#include "online/shell_renderer.h"` works as in the tree
#   P/lib/libcoif_*.a|.so            the libraries (BUILD_SHARED_LIBS picks)
#   P/lib/cmake/coif/                coifConfig.cmake, coifConfigVersion.cmake and two export sets:
#     coifRuntimeTargets    coif::core, coif::models, coif::shading, coif::shells, coif::online, coif::runtime
#     coifAuthoringTargets  coif::offline, coif::db, coif::scene (with COIF_BUILD_AUTHORING)
# find_package(coif CONFIG REQUIRED COMPONENTS runtime) loads the first alone and finds only the runtime's
# dependencies; without COMPONENTS every installed set is loaded (cmake/coifConfig.cmake.in).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# coif_install_module(<target> <folder> <runtime|authoring>): the library into its export set, the folder's headers
# (not its subfolders', which are libraries of their own; shaders/ whole, GLSL included) under include/coif/.
function(coif_install_module target folder set)
  string(SUBSTRING ${set} 0 1 first)
  string(TOUPPER ${first} first)
  string(SUBSTRING ${set} 1 -1 rest)
  install(TARGETS ${target} EXPORT coif${first}${rest}Targets COMPONENT ${set}
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  file(RELATIVE_PATH rel ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR})
  if(rel STREQUAL "shaders")
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coif/${rel} COMPONENT ${set}
            FILES_MATCHING PATTERN "*.h" PATTERN "*.glsl" PATTERN "*.vert" PATTERN "*.frag" PATTERN "*.comp")
  else()
    file(GLOB headers ${CMAKE_CURRENT_SOURCE_DIR}/*.h)
    install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/coif/${rel} COMPONENT ${set})
  endif()
endfunction()

# After every module: the export sets, the package config and its version file.
function(coif_install_package)
  set(dir ${CMAKE_INSTALL_LIBDIR}/cmake/coif)
  install(EXPORT coifRuntimeTargets NAMESPACE coif:: DESTINATION ${dir} COMPONENT runtime)
  if(COIF_BUILD_AUTHORING)
    install(EXPORT coifAuthoringTargets NAMESPACE coif:: DESTINATION ${dir} COMPONENT authoring)
  endif()
  configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/coifConfig.cmake.in ${PROJECT_BINARY_DIR}/coifConfig.cmake
                                INSTALL_DESTINATION ${dir})
  # 0.x: a minor version may break the API, so only the same minor version is compatible.
  write_basic_package_version_file(${PROJECT_BINARY_DIR}/coifConfigVersion.cmake COMPATIBILITY SameMinorVersion)
  install(FILES ${PROJECT_BINARY_DIR}/coifConfig.cmake ${PROJECT_BINARY_DIR}/coifConfigVersion.cmake DESTINATION ${dir}
          COMPONENT runtime)
endfunction()
