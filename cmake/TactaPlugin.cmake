# tacta_add_plugin(NAME <name> SOURCES <files...> [LIBS <targets...>] [NO_INSTALL])
# Builds one plugin as a MODULE library named tacta_<name>.so in build/lib/tacta/plugins,
# where the loader looks first, and installs it to lib/tacta/plugins.
# Plugins see only the public headers (tacta::plugin_api), never engine/src.
function(tacta_add_plugin)
  cmake_parse_arguments(P "NO_INSTALL" "NAME;OUTPUT_DIR" "SOURCES;LIBS" ${ARGN})
  set(target tacta_${P_NAME})
  add_library(${target} MODULE ${P_SOURCES})
  target_link_libraries(${target} PRIVATE tacta::plugin_api ${P_LIBS})
  set(out ${TACTA_PLUGIN_BUILD_DIR})
  if(P_OUTPUT_DIR)
    set(out ${P_OUTPUT_DIR})
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY ${out}
    C_VISIBILITY_PRESET hidden
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  tacta_set_warnings(${target})
  if(NOT P_NO_INSTALL)
    install(TARGETS ${target} LIBRARY DESTINATION ${TACTA_PLUGIN_INSTALL_DIR})
  endif()
endfunction()
