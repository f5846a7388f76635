# cmake -P script: a third party's whole path with an SDK example, sdk/examples/prescribed_load.
# Installs the Rumble build into a fresh prefix (without writing into the build tree:
# tests/support/install_tree.cmake); copies the example out of the prefix's share/rumble; builds
# it out of tree against the installed SDK with a fresh CMake and strict warnings, as
# tests/new_plugin/scaffold_build.cmake builds scaffolds; runs its own ctest; installs it into the
# prefix, where the installed rumble finds it unaided; runs its lamb.json there. The results are
# checked against Lamb's closed form by sdk_examples.PrescribedLoadLamb.* (lamb_run_test.cpp).
# Variables (-D): BUILD_DIR (the engine build), WORK_DIR (emptied first), MESH_CACHE (the FEM
# soil's mesh cache), GENERATOR, MAKE_PROGRAM, CXX_COMPILER (the engine build's).
cmake_minimum_required(VERSION 3.25)
foreach(var BUILD_DIR WORK_DIR MESH_CACHE GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_and_run_example.cmake: -D${var}=... is required")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../support/script_step.cmake)  # step(name command...)
include(${CMAKE_CURRENT_LIST_DIR}/../support/install_tree.cmake)  # install_tree(build prefix)

set(prefix ${WORK_DIR}/prefix)
set(project ${WORK_DIR}/prescribed_load)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
install_tree(${BUILD_DIR} ${prefix})
set(shipped ${prefix}/share/rumble/examples/prescribed_load)
foreach(file CMakeLists.txt README.md prescribed_load.cpp prescribed_load_test.cpp lamb.json)
  if(NOT EXISTS ${shipped}/${file})
    message(FATAL_ERROR "the install lacks share/rumble/examples/prescribed_load/${file}")
  endif()
endforeach()
file(COPY ${shipped}/ DESTINATION ${project})

set(make_program)
if(MAKE_PROGRAM)
  set(make_program -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
# Warnings as errors with a strict set: examples are what authors copy.
step("configure the example" ${CMAKE_COMMAND} -S ${project} -B ${project}/build -G ${GENERATOR}
  ${make_program} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
  -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_COMPILE_WARNING_AS_ERROR=ON
  "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wold-style-cast")
step("build the example" ${CMAKE_COMMAND} --build ${project}/build)
step("the example's ctest" ${CMAKE_CTEST_COMMAND} --test-dir ${project}/build --output-on-failure)
if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of [1-9]")
  message(FATAL_ERROR "the example's ctest ran no test:\n${step_output}")
endif()

# Into the engine's prefix: lib/rumble/plugins, which the installed rumble loads unaided. (CMake
# writes ${project}/build/install_manifest.txt: the plugin's own build folder, as for any
# project; README.md says so.)
step("install the example" ${CMAKE_COMMAND} --install ${project}/build --prefix ${prefix})
if(NOT EXISTS ${prefix}/lib/rumble/plugins/prescribed_load.so)
  message(FATAL_ERROR "cmake --install put no prescribed_load.so in ${prefix}/lib/rumble/plugins")
endif()

step("rumble run lamb.json" ${CMAKE_COMMAND} -E env RUMBLE_MESH_CACHE=${MESH_CACHE}
  ${prefix}/bin/rumble run ${project}/lamb.json --no-progress)
foreach(file summary.json receivers.csv footprint_force.csv)
  if(NOT EXISTS ${project}/lamb_results/${file})
    message(FATAL_ERROR "the Lamb run wrote no ${file}:\n${step_output}")
  endif()
endforeach()
message(STATUS "${step_output}")
