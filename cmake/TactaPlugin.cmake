# tacta_add_plugin(NAME <name> SOURCES <files...> [LIBS <targets...>] [OUTPUT_DIR <dir>]
#                  [NO_INSTALL])
# Builds one plugin as a MODULE library named tacta_<name>.so (default folder: the tree's
# build/lib/tacta/plugins, where the loader looks first, or <build>/lib/tacta/plugins out of tree)
# and installs it to lib/tacta/plugins. Plugins see only the public headers (tacta::plugin_api),
# never engine/src. The one definition: the source tree includes it, and it is installed with the
# package, where TactaConfig.cmake includes it for out-of-tree plugins.
include_guard(GLOBAL)
include(GNUInstallDirs)
include(${CMAKE_CURRENT_LIST_DIR}/TactaWarnings.cmake)

function(tacta_add_plugin)
  cmake_parse_arguments(P "NO_INSTALL" "NAME;OUTPUT_DIR" "SOURCES;LIBS" ${ARGN})
  if(NOT P_NAME OR NOT P_SOURCES)
    message(FATAL_ERROR "tacta_add_plugin: NAME and SOURCES are required")
  endif()
  set(target tacta_${P_NAME})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE tacta::plugin_api ${P_LIBS})
  # The tree sets these folders; an out-of-tree project gets the same layout under its build.
  set(out ${CMAKE_BINARY_DIR}/lib/tacta/plugins)
  if(TACTA_PLUGIN_BUILD_DIR)
    set(out ${TACTA_PLUGIN_BUILD_DIR})
  endif()
  if(P_OUTPUT_DIR)
    set(out ${P_OUTPUT_DIR})
  endif()
  set(install_dir ${CMAKE_INSTALL_LIBDIR}/tacta/plugins)
  if(TACTA_PLUGIN_INSTALL_DIR)
    set(install_dir ${TACTA_PLUGIN_INSTALL_DIR})
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY ${out}
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  tacta_set_warnings(${target})
  if(NOT P_NO_INSTALL)
    install(TARGETS ${target} LIBRARY DESTINATION ${install_dir})
  endif()
endfunction()
