# cmake -P script: `rumble plugins` with RUMBLE_PLUGIN_PATH = the template's build directory
# lists the template library and its type, in text and in JSON.
# Variables (-D): RUMBLE (the executable), PLUGIN_DIR, EXPECTED_ABI ("major.minor").
cmake_minimum_required(VERSION 3.25)
if(NOT EXISTS "${RUMBLE}")
  message(FATAL_ERROR "${RUMBLE} does not exist: build the rumble target first")
endif()

function(run_plugins out_var)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env RUMBLE_PLUGIN_PATH=${PLUGIN_DIR}
                          ${RUMBLE} plugins ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "rumble plugins ${ARGN} exited with ${rc}:\n${out}\n${err}")
  endif()
  set(${out_var} "${out}" PARENT_SCOPE)
endfunction()

run_plugins(text)
if(NOT text MATCHES "template_soil 0\\.1\\.0 " OR NOT text MATCHES "soil template_soil: ")
  message(FATAL_ERROR "rumble plugins does not list template_soil:\n${text}")
endif()

run_plugins(json --format json)
string(JSON n_libraries LENGTH "${json}")
if(n_libraries EQUAL 0)
  message(FATAL_ERROR "rumble plugins --format json lists no library:\n${json}")
endif()
set(found FALSE)
math(EXPR last "${n_libraries} - 1")
foreach(i RANGE ${last})
  string(JSON name GET "${json}" ${i} plugin)
  if(name STREQUAL "template_soil")
    string(JSON abi GET "${json}" ${i} abi)
    string(JSON type GET "${json}" ${i} types 0 type)
    string(JSON kind GET "${json}" ${i} types 0 kind)
    if(NOT type STREQUAL "template_soil" OR NOT kind STREQUAL "soil"
       OR NOT abi STREQUAL EXPECTED_ABI)
      message(FATAL_ERROR "template_soil listed as ${kind} '${type}', ABI ${abi}:\n${json}")
    endif()
    set(found TRUE)
  endif()
endforeach()
if(NOT found)
  message(FATAL_ERROR "rumble plugins --format json does not list template_soil:\n${json}")
endif()
