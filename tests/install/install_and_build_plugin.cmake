# cmake -P script: install, build an external plugin against the installed package, list it.
# Inputs: TACTA_BUILD_DIR, EXTERNAL_SOURCE_DIR, WORK_DIR, GENERATOR, CXX_COMPILER, and the
# parent build's CXX_FLAGS, EXE_LINKER_FLAGS, MODULE_LINKER_FLAGS (sanitizers); PYTHON and
# PYTHON_PACKAGE_DIR (relative to the prefix) when the build has the Python module.
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
          include/tacta/models/divergence_guard.hpp lib/libtacta_models_common.a
          lib/cmake/Tacta/TactaPlugin.cmake lib/cmake/Tacta/TactaWarnings.cmake
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
set(found_model OFF)
math(EXPR last "${count} - 1")
foreach(i RANGE 0 ${last})
  string(JSON name GET "${json}" plugins ${i} name)
  if(name STREQUAL "external_free_body")
    string(JSON kind GET "${json}" plugins ${i} kind)
    if(NOT kind STREQUAL "model")
      message(FATAL_ERROR "external_free_body listed as kind '${kind}'")
    endif()
    set(found_model ON)
  endif()
  if(name STREQUAL "external_demo")
    string(JSON file GET "${json}" plugins ${i} file)
    string(JSON param GET "${json}" plugins ${i} parameters 0 name)
    if(NOT file MATCHES "tacta_external_demo\\.so$" OR NOT param STREQUAL "gain")
      message(FATAL_ERROR "external_demo listed with file '${file}', first parameter '${param}'")
    endif()
    set(found ON)
  endif()
endforeach()
if(NOT found OR NOT found_model)
  message(FATAL_ERROR "tacta plugins did not list external_demo and external_free_body:\n${json}")
endif()

# The out-of-tree model runs a scene through the installed `tacta` (found via TACTA_PLUGIN_PATH).
file(WRITE ${WORK_DIR}/free_body.yaml [=[
name: external_free_body_drop
gravity: [0, -9.81, 0]
clock: {mode: lockstep, duration_s: 0.02}
bodies:
  - name: block
    mesh: {beam_grid: {size: [0.1, 0.02, 0.02], cells: [2, 1, 1]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 1000}
    model: external_free_body
]=])
run("tacta run with the external model" ${CMAKE_COMMAND} -E env TACTA_PLUGIN_PATH=${plugin_dir}
    ${prefix}/bin/tacta run ${WORK_DIR}/free_body.yaml -q -o ${WORK_DIR}/free_body_out)
file(READ ${WORK_DIR}/free_body_out/report.json report)
if(NOT report MATCHES "external_free_body")
  message(FATAL_ERROR "report.json does not name the external model:\n${report}")
endif()

if(EXISTS ${build}/engine_user)
  run("engine user" ${build}/engine_user)
  if(NOT run_output MATCHES "\"entities\":2")
    message(FATAL_ERROR "engine_user printed: ${run_output}")
  endif()
endif()
if(PYTHON)
  # Only the installed package on the path (not build/python), run from a folder of its own. The
  # code's statements are on lines: a ';' would split the argument as a CMake list.
  set(package_root ${prefix}/${PYTHON_PACKAGE_DIR})
  run("import the installed tacta package" ${CMAKE_COMMAND} -E chdir ${WORK_DIR}
      ${CMAKE_COMMAND} -E env PYTHONPATH=${package_root} TACTA_PLUGIN_PATH=${plugin_dir} PYTHONDONTWRITEBYTECODE=1
      ${PYTHON} -c "import tacta\nassert tacta.__file__.startswith('${package_root}/'), tacta.__file__\n\
sim = tacta.Simulation('free_body.yaml')\nsim.step(5)\nprint(sim.bodies['block'].model, sim.tick)")
  if(NOT run_output MATCHES "external_free_body 5")
    message(FATAL_ERROR "the installed tacta package printed: ${run_output}")
  endif()
endif()
message(STATUS "installed package OK: external_demo listed, external_free_body ran, from ${plugin_dir}")
