# cmake -P script: what the installed Rumble package promises a plugin project, checked on the
# coupler template (no params, so no rumble/params.hpp) and the soil template (params):
#   1. nlohmann_json is needed only for the "params" component: the coupler configures, builds and
#      passes its ctest with nlohmann_json made unfindable; the soil then fails to configure with
#      the package's message that names the component, the package and the fix;
#   2. rumble_add_plugin() optimises (-O2) a plugin configured without a build type, and leaves
#      an explicit build type or an -O flag in CMAKE_CXX_FLAGS alone.
# Variables (-D): PREFIX (the SDK installed by build_template.cmake), SDK_SOURCE_DIR (sdk/),
# WORK_DIR (emptied first), GENERATOR, MAKE_PROGRAM, CXX_COMPILER.
cmake_minimum_required(VERSION 3.25)
foreach(var PREFIX SDK_SOURCE_DIR WORK_DIR GENERATOR CXX_COMPILER)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "sdk_package_checks.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK_DIR})

set(make_program)
if(MAKE_PROGRAM)
  set(make_program -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM})
endif()
# configure(<name> <source dir> <expect: ok|fail> [cmake args...]) -> ${WORK_DIR}/<name>;
# sets `output` in the caller.
function(configure name source expect)
  execute_process(COMMAND ${CMAKE_COMMAND} -S ${source} -B ${WORK_DIR}/${name} -G ${GENERATOR}
      ${make_program} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${PREFIX}
      -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_EXPORT_COMPILE_COMMANDS=ON ${ARGN}
    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(expect STREQUAL "ok" AND NOT rc EQUAL 0)
    message(FATAL_ERROR "configuring ${name} failed (${rc}):\n${ARGN}\n${out}")
  elseif(expect STREQUAL "fail" AND rc EQUAL 0)
    message(FATAL_ERROR "configuring ${name} succeeded, but must fail:\n${ARGN}\n${out}")
  endif()
  set(output "${out}" PARENT_SCOPE)
endfunction()

# The compile command of <source file> in <build>'s compile_commands.json -> `command`.
function(compile_command build source_file)
  file(READ ${build}/compile_commands.json json)
  string(JSON n LENGTH "${json}")
  math(EXPR last "${n} - 1")
  foreach(i RANGE ${last})
    string(JSON file GET "${json}" ${i} file)
    if(file MATCHES "/${source_file}$")
      string(JSON cmd GET "${json}" ${i} command)
      set(command "${cmd}" PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "${build}/compile_commands.json has no ${source_file}")
endfunction()

# 1. No nlohmann_json: the coupler builds and passes its test; the soil says what it lacks.
set(coupler ${SDK_SOURCE_DIR}/template_coupler)
configure(no_json ${coupler} ok -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON)
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/no_json RESULT_VARIABLE rc
  OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the coupler template did not build without nlohmann_json:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_CTEST_COMMAND} --test-dir ${WORK_DIR}/no_json --output-on-failure
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "100% tests passed, 0 tests failed out of [1-9]")
  message(FATAL_ERROR "the coupler template's ctest failed (${rc}):\n${out}")
endif()
message(STATUS "coupler template without nlohmann_json: configured, built, tested")

configure(no_json_params ${SDK_SOURCE_DIR}/template fail -DCMAKE_DISABLE_FIND_PACKAGE_nlohmann_json=ON)
string(REGEX REPLACE "[ \n]+" " " output "${output}")  # CMake wraps long messages
foreach(part "the component 'params' \\(Rumble::params, for rumble/params.hpp\\) needs nlohmann_json"
             "apt install nlohmann-json3-dev" "drop COMPONENTS params")
  if(NOT output MATCHES "${part}")
    message(FATAL_ERROR "no '${part}' in the configure error:\n${output}")
  endif()
endforeach()
message(STATUS "soil template without nlohmann_json: refused with the package's message")

# 2. Optimisation: -O2 without a build type (the configure above had none), else untouched.
compile_command(${WORK_DIR}/no_json template_coupler.cpp)
if(NOT command MATCHES " -O2( |$)")
  message(FATAL_ERROR "no build type, yet the plugin is compiled without -O2:\n${command}")
endif()
configure(debug ${coupler} ok -DCMAKE_BUILD_TYPE=Debug)
compile_command(${WORK_DIR}/debug template_coupler.cpp)
if(command MATCHES " -O2( |$)" OR NOT command MATCHES " -g( |$)")
  message(FATAL_ERROR "CMAKE_BUILD_TYPE=Debug must compile with -g and no -O2:\n${command}")
endif()
configure(own_flags ${coupler} ok "-DCMAKE_CXX_FLAGS=-O1 -Wall")
compile_command(${WORK_DIR}/own_flags template_coupler.cpp)
if(command MATCHES " -O2( |$)" OR NOT command MATCHES " -O1( |$)")
  message(FATAL_ERROR "the user's -O1 in CMAKE_CXX_FLAGS must be left alone:\n${command}")
endif()
message(STATUS "optimisation: -O2 without a build type; Debug and the user's -O1 untouched")
