# cmake -P script: a third party's whole path from an installed Rumble to a running plugin.
# Installs the Rumble build into a fresh prefix; with that rumble, scaffolds one plugin of each
# kind (rumble new-plugin), builds each out of tree against the installed SDK with a fresh CMake
# and runs its own ctest; `rumble plugins` then lists the three types, and a scenario with the
# scaffolded vehicle and coupler gives the very numbers of single_wheel + gauss_seidel (the
# templates are the same equation and the same scheme, written independently).
# Variables (-D): BUILD_DIR (the engine build), WORK_DIR (emptied first), GENERATOR,
# MAKE_PROGRAM, CXX_COMPILER (the engine build's, so the test runs where it builds).
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "scaffold_build.cmake: -D${var}=... is required")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../support/script_step.cmake)  # step(name command...)
include(${CMAKE_CURRENT_LIST_DIR}/../support/install_tree.cmake)  # install_tree(build prefix)

set(prefix ${WORK_DIR}/prefix)
set(rumble ${prefix}/bin/rumble)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
# The whole tree, as `cmake --install ${BUILD_DIR}` would, but without its install_manifest.txt
# in the build tree under test (tests/support/install_tree.cmake).
install_tree(${BUILD_DIR} ${prefix})
foreach(file bin/rumble share/rumble/plot_results.py share/rumble/plot_frf.py)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()

set(make_program)
if(MAKE_PROGRAM)
  set(make_program -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
set(plugin_path)
foreach(kind soil vehicle coupler)
  set(project ${WORK_DIR}/my_${kind})
  step("rumble new-plugin ${kind}" ${rumble} new-plugin ${kind} my_${kind} ${project})
  # Warnings as errors with a strict set: scaffolds are what authors start from.
  step("configure my_${kind}" ${CMAKE_COMMAND} -S ${project} -B ${project}/build -G ${GENERATOR}
    ${make_program} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_COMPILE_WARNING_AS_ERROR=ON
    "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wold-style-cast")
  step("build my_${kind}" ${CMAKE_COMMAND} --build ${project}/build)
  step("ctest of my_${kind}" ${CMAKE_CTEST_COMMAND} --test-dir ${project}/build --output-on-failure)
  if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of [1-9]")
    message(FATAL_ERROR "my_${kind}'s ctest ran no test:\n${step_output}")
  endif()
  list(APPEND plugin_path ${project}/build)
endforeach()
string(REPLACE ";" ":" plugin_path "${plugin_path}")

step("rumble plugins" ${CMAKE_COMMAND} -E env RUMBLE_PLUGIN_PATH=${plugin_path} ${rumble} plugins)
foreach(kind soil vehicle coupler)
  if(NOT step_output MATCHES "\n  ${kind} my_${kind}: ")
    message(FATAL_ERROR "rumble plugins does not list the ${kind} my_${kind}:\n${step_output}")
  endif()
endforeach()

# The same run twice: in-tree single_wheel + gauss_seidel, then the scaffolded vehicle + coupler.
set(track [=[{"sleepers": {"count": 20, "spacing": 0.6, "mass": 150.0,
                           "footprint": {"length": 2.6, "width": 0.26}},
              "rail": {"E": 2.1e11, "I": 3.055e-5, "mass_per_length": 60.34},
              "railpad": {"k": 2e8, "c": 2.8e4}, "ballast": {"k": 4e7, "c": 4.7e4}}]=])
foreach(run in_tree scaffolded)
  if(run STREQUAL "in_tree")
    set(vehicle [=[{"type": "single_wheel", "speed": 20.0, "start": 3.0,
                    "params": {"mass": 750.0, "static_load": 50000.0}}]=])
    set(coupling [=[{"type": "gauss_seidel"}]=])
  else()
    set(vehicle [=[{"type": "my_vehicle", "speed": 20.0, "start": 3.0,
                    "params": {"mass": 750.0, "preload": 50000.0}}]=])
    set(coupling [=[{"type": "my_coupler"}]=])
  endif()
  file(WRITE ${WORK_DIR}/${run}.json "{\"schema_version\": 1, \"name\": \"${run}\",
  \"time\": {\"end\": 0.05, \"macro_step\": 1e-3}, \"vehicles\": [${vehicle}], \"track\": ${track},
  \"soil\": {\"type\": \"winkler\", \"params\": {\"k\": 1e8, \"c\": 2e5}},
  \"coupling\": ${coupling}, \"outputs\": {\"directory\": \"${run}_results\", \"plots\": false}}\n")
  step("rumble run (${run})" ${CMAKE_COMMAND} -E env RUMBLE_PLUGIN_PATH=${plugin_path}
    ${rumble} run ${WORK_DIR}/${run}.json --no-progress)
endforeach()
file(GLOB csv_files RELATIVE ${WORK_DIR}/in_tree_results ${WORK_DIR}/in_tree_results/*.csv)
list(LENGTH csv_files n_csv)
if(n_csv LESS 4)
  message(FATAL_ERROR "the in-tree run wrote ${n_csv} CSV files: ${csv_files}")
endif()
foreach(csv IN LISTS csv_files)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files
    ${WORK_DIR}/in_tree_results/${csv} ${WORK_DIR}/scaffolded_results/${csv} RESULT_VARIABLE differ)
  if(differ)
    message(FATAL_ERROR "${csv} differs between single_wheel + gauss_seidel and the scaffolded "
                        "my_vehicle + my_coupler (in ${WORK_DIR})")
  endif()
endforeach()
message(STATUS "${n_csv} result files identical")
