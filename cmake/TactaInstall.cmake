# Installation and the exported CMake package `Tacta`:
#   include/tacta/...                 public headers (plugin ABI, SDK, engine API)
#   lib/libtacta_engine.a             the engine (static)
#   bin/tacta                         the command line (installed by apps/tacta)
#   include/tacta/models/...          model-plugin helpers' headers (plugins/models/common)
#   lib/libtacta_models_common.a      model-plugin helpers (static)
#   lib/tacta/plugins/*.so            plugins (installed by tacta_add_plugin)
#   lib/python3/dist-packages/tacta/  the Python module (installed by python/CMakeLists.txt)
#   lib/cmake/Tacta/                  TactaConfig.cmake, TactaConfigVersion.cmake, TactaTargets.cmake,
#                                     TactaPlugin.cmake and TactaWarnings.cmake (tacta_add_plugin)
# find_package(Tacta) gives tacta::plugin_api, tacta::engine (when its dependencies are all
# packages find_dependency can find), tacta::models_common and tacta_add_plugin() for
# out-of-tree plugins.
include(CMakePackageConfigHelpers)

set(TACTA_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Tacta)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/tacta
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h" PATTERN "*.hpp")

# The plugin folder exists even when no plugin is installed, so the loader's search is uniform.
install(DIRECTORY DESTINATION ${TACTA_PLUGIN_INSTALL_DIR})

# The engine can only be exported if everything it links is an imported target (a package) or
# exported with it; a project-internal helper library linked privately would break the export.
# Each imported target names its package (Foo::bar -> Foo, yaml-cpp -> yaml-cpp), which the
# config file finds again with find_dependency: the engine is static, so the consumer links them.
set(tacta_export_engine ON)
set(tacta_engine_packages "")
get_target_property(tacta_engine_links tacta_engine LINK_LIBRARIES)
# Imported targets are visible only in the folder that found them, so a name is judged by its form:
# Foo::bar is package Foo; a plain name is a package when find_package left <name>_DIR in the cache
# (yaml-cpp); other plain names (dl) are system libraries. Project targets are visible everywhere.
foreach(lib IN LISTS tacta_engine_links)
  if(lib MATCHES "^\\$<" OR lib MATCHES "^(tacta::plugin_api|tacta_plugin_api)$")
    continue()
  endif()
  if(TARGET ${lib})
    get_target_property(lib_imported ${lib} IMPORTED)
    if(NOT lib_imported)
      message(STATUS "Tacta package: tacta::engine not exported (links project target ${lib})")
      set(tacta_export_engine OFF)
      continue()
    endif()
  endif()
  if(lib MATCHES "::")
    string(REGEX REPLACE "::.*$" "" package ${lib})
    list(APPEND tacta_engine_packages ${package})
  elseif(DEFINED CACHE{${lib}_DIR})
    list(APPEND tacta_engine_packages ${lib})
  endif()
endforeach()
list(REMOVE_DUPLICATES tacta_engine_packages)

set(tacta_exported_targets tacta_plugin_api)
# The model helpers link only tacta::plugin_api and Eigen3 (found again by the config file).
set(TACTA_PACKAGE_HAS_MODELS_COMMON OFF)
if(TARGET tacta_models_common)
  set(TACTA_PACKAGE_HAS_MODELS_COMMON ON)
  list(APPEND tacta_exported_targets tacta_models_common)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/plugins/models/common/include/tacta
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
    FILES_MATCHING PATTERN "*.hpp")
endif()
if(tacta_export_engine)
  list(APPEND tacta_exported_targets tacta_engine)
endif()
install(TARGETS ${tacta_exported_targets} EXPORT TactaTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT TactaTargets NAMESPACE tacta:: DESTINATION ${TACTA_CMAKE_INSTALL_DIR})

# Values the config file substitutes.
set(TACTA_PACKAGE_HAS_ENGINE ${tacta_export_engine})
set(TACTA_PACKAGE_DEPENDENCIES "${tacta_engine_packages}")
set(TACTA_PACKAGE_PLUGIN_DIR ${TACTA_PLUGIN_INSTALL_DIR})
set(TACTA_PACKAGE_INCLUDE_DIR ${CMAKE_INSTALL_INCLUDEDIR})
set(TACTA_PACKAGE_BIN_DIR ${CMAKE_INSTALL_BINDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/TactaConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/TactaConfig.cmake
  INSTALL_DESTINATION ${TACTA_CMAKE_INSTALL_DIR}
  PATH_VARS TACTA_PACKAGE_PLUGIN_DIR TACTA_PACKAGE_INCLUDE_DIR TACTA_PACKAGE_BIN_DIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/TactaConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/TactaConfig.cmake
              ${PROJECT_BINARY_DIR}/cmake/TactaConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/TactaPlugin.cmake
              ${PROJECT_SOURCE_DIR}/cmake/TactaWarnings.cmake
  DESTINATION ${TACTA_CMAKE_INSTALL_DIR})
