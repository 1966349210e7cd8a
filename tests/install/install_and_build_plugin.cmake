# cmake -P script: install, build an external plugin against the installed package, list it.
# Inputs: TACTA_BUILD_DIR, EXTERNAL_SOURCE_DIR, WORK_DIR, GENERATOR, CXX_COMPILER, and the
# parent build's CXX_FLAGS, EXE_LINKER_FLAGS, MODULE_LINKER_FLAGS (sanitizers).
cmake_minimum_required(VERSION 3.25)

function(run step)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${step} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/external_build)
set(plugin_dir ${build}/plugins)

run("install" ${CMAKE_COMMAND} --install ${TACTA_BUILD_DIR} --prefix ${prefix})
foreach(f bin/tacta include/tacta/plugin.h include/tacta/sdk/model.hpp lib/libtacta_engine.a
          lib/cmake/Tacta/TactaConfig.cmake lib/cmake/Tacta/TactaConfigVersion.cmake
          lib/cmake/Tacta/TactaTargets.cmake)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "install did not produce ${prefix}/${f}")
  endif()
endforeach()

# The external project's CMakeLists is stored as .in (see its header); give it its real name.
set(source ${WORK_DIR}/external_source)
file(COPY ${EXTERNAL_SOURCE_DIR}/ DESTINATION ${source})
file(RENAME ${source}/CMakeLists.txt.in ${source}/CMakeLists.txt)
run("configure external project" ${CMAKE_COMMAND} -S ${source} -B ${build}
    -G ${GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
    -DCMAKE_PREFIX_PATH=${prefix} -DEXTERNAL_PLUGIN_DIR=${plugin_dir}
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXE_LINKER_FLAGS}"
    "-DCMAKE_MODULE_LINKER_FLAGS=${MODULE_LINKER_FLAGS}")
run("build external project" ${CMAKE_COMMAND} --build ${build} -j2)

run("tacta plugins" ${prefix}/bin/tacta plugins --json --path ${plugin_dir})
set(json "${run_output}")
string(JSON count LENGTH "${json}" plugins)
set(found OFF)
math(EXPR last "${count} - 1")
foreach(i RANGE 0 ${last})
  string(JSON name GET "${json}" plugins ${i} name)
  if(name STREQUAL "external_demo")
    string(JSON file GET "${json}" plugins ${i} file)
    string(JSON param GET "${json}" plugins ${i} parameters 0 name)
    if(NOT file MATCHES "tacta_external_demo\\.so$" OR NOT param STREQUAL "gain")
      message(FATAL_ERROR "external_demo listed with file '${file}', first parameter '${param}'")
    endif()
    set(found ON)
  endif()
endforeach()
if(NOT found)
  message(FATAL_ERROR "tacta plugins did not list external_demo:\n${json}")
endif()

if(EXISTS ${build}/engine_user)
  run("engine user" ${build}/engine_user)
  if(NOT run_output MATCHES "\"entities\":2")
    message(FATAL_ERROR "engine_user printed: ${run_output}")
  endif()
endif()
message(STATUS "installed package OK: external_demo listed from ${plugin_dir}")
