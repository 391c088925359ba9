# coif_add_module(<folder> [ALIAS <name>] [EXPORT runtime|authoring] DEPS <targets...>)
# One library per source folder: coif_<alias>, alias coif::<alias>, static or shared as BUILD_SHARED_LIBS says. The
# folder's own .cpp files are globbed (not its subfolders: a subfolder with a CMakeLists.txt is a library of its own,
# e.g. models/core), so adding a file to a folder needs no edit here. A folder with no .cpp yet is an INTERFACE
# library. With EXPORT, the library and the folder's headers (and the GLSL they include) are installed in that
# export set (cmake/CoifInstall.cmake): `#include "models/core/error.h"` works the same in the tree and installed.
function(coif_add_module folder)
  cmake_parse_arguments(ARG "" "ALIAS;EXPORT" "DEPS" ${ARGN})
  if(NOT ARG_ALIAS)
    set(ARG_ALIAS ${folder})
  endif()
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cpp)
  set(target coif_${ARG_ALIAS})
  set(includes $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}> $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/generated>
               $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/coif>)
  if(sources)
    add_library(${target} ${sources})
    target_include_directories(${target} PUBLIC ${includes})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    coif_set_warnings(${target})
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${includes})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${ARG_ALIAS})
  add_library(coif::${ARG_ALIAS} ALIAS ${target})
  if(ARG_EXPORT)
    coif_install_module(${target} ${folder} ${ARG_EXPORT})
  endif()
endfunction()
