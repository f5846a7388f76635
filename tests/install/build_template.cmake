# cmake -P script: install the SDK into a fresh prefix, then configure and build sdk/template out
# of tree against it with a fresh CMake, as a plugin author would. Variables (-D):
#   SDK_BINARY_DIR   the engine build's sdk/ directory (its install script installs the SDK only)
#   TEMPLATE_DIR     sdk/template in the sources
#   WORK_DIR         scratch directory (emptied first): prefix/ and build/ go there
#   GENERATOR, MAKE_PROGRAM, CXX_COMPILER   the engine build's, so the test runs where it builds
cmake_minimum_required(VERSION 3.25)
foreach(var SDK_BINARY_DIR TEMPLATE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_template.cmake: -D${var}=... is required")
  endif()
endforeach()

include(${CMAKE_CURRENT_LIST_DIR}/../support/script_step.cmake)  # step(name command...)

set(prefix ${WORK_DIR}/prefix)
set(build ${WORK_DIR}/build)
file(REMOVE_RECURSE ${WORK_DIR})

step("install the SDK" ${CMAKE_COMMAND} --install ${SDK_BINARY_DIR} --prefix ${prefix})
foreach(header abi.h plugin.hpp params.hpp newmark.hpp)
  if(NOT EXISTS ${prefix}/include/rumble/${header})
    message(FATAL_ERROR "the SDK install lacks include/rumble/${header}")
  endif()
endforeach()

set(make_program)
if(MAKE_PROGRAM)
  set(make_program -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
# Warnings as errors with a strict set: the template is what authors copy.
step("configure the template" ${CMAKE_COMMAND} -S ${TEMPLATE_DIR} -B ${build} -G ${GENERATOR}
  ${make_program} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_BUILD_TYPE=Release
  -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
  -DCMAKE_COMPILE_WARNING_AS_ERROR=ON
  "-DCMAKE_CXX_FLAGS=-Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wold-style-cast")

# The package must have come from this prefix, not from a system-wide or earlier install.
file(STRINGS ${build}/CMakeCache.txt rumble_dir REGEX "^Rumble_DIR:")
string(REGEX REPLACE "^Rumble_DIR:[A-Z]+=" "" rumble_dir "${rumble_dir}")
file(REAL_PATH "${rumble_dir}" rumble_dir)
file(REAL_PATH "${prefix}" real_prefix)
string(FIND "${rumble_dir}/" "${real_prefix}/" at)
if(NOT at EQUAL 0)
  message(FATAL_ERROR "find_package(Rumble) used ${rumble_dir}, not the fresh install in ${prefix}")
endif()

step("build the template" ${CMAKE_COMMAND} --build ${build})
if(NOT EXISTS ${build}/template_soil.so)
  message(FATAL_ERROR "the template build produced no ${build}/template_soil.so")
endif()

# The template's own test (enable_testing() + add_test in its CMakeLists.txt): a third party runs
# `ctest` after building, and it must find and pass the closed-form checks.
step("the template's ctest" ${CMAKE_CTEST_COMMAND} --test-dir ${build} --output-on-failure)
if(NOT step_output MATCHES "100% tests passed, 0 tests failed out of [1-9]")
  message(FATAL_ERROR "the template's ctest ran no test:\n${step_output}")
endif()

# `cmake --install` of the plugin into the engine's prefix puts it in lib/rumble/plugins, the
# directory an installed `rumble` loads unaided and the package names as Rumble_PLUGIN_DIR.
step("install the template" ${CMAKE_COMMAND} --install ${build} --prefix ${prefix})
if(NOT EXISTS ${prefix}/lib/rumble/plugins/template_soil.so)
  message(FATAL_ERROR "cmake --install put no template_soil.so in ${prefix}/lib/rumble/plugins")
endif()
file(GLOB_RECURSE config ${prefix}/*/RumbleConfig.cmake)
file(STRINGS "${config}" plugin_dir REGEX "^set\\(Rumble_PLUGIN_DIR ")
if(NOT plugin_dir STREQUAL "set(Rumble_PLUGIN_DIR \"\${PACKAGE_PREFIX_DIR}/lib/rumble/plugins\")")
  message(FATAL_ERROR "RumbleConfig.cmake sets '${plugin_dir}', not the prefix's lib/rumble/plugins")
endif()
