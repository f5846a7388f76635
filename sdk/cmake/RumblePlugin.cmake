# rumble_add_plugin(<name> SOURCES <files...>)
#
# Builds a Rumble plugin: a MODULE library named <name>.so with hidden visibility, linked only
# to Rumble::sdk, so that the one entry point exported by RUMBLE_PLUGIN() is all it shows (link
# Rumble::params too with target_link_libraries() to use rumble/params.hpp).
# Output goes to RUMBLE_PLUGIN_OUTPUT_DIR when set (the engine's build tree does), otherwise to
# the caller's binary directory. Point RUMBLE_PLUGIN_PATH at that directory to use it.
# `cmake --install` puts it in <prefix>/lib/rumble/plugins (or RUMBLE_PLUGIN_INSTALL_DIR when
# set): installed into the prefix the engine was installed in, `rumble` finds it unaided. Always
# lib/, never lib64: that is where the engine looks, next to its bin/.
#
# Built without a build type (a single-config generator and no CMAKE_BUILD_TYPE, which is what
# a plain `cmake -S . -B build` gives), CMake would compile with no optimisation at all: a plugin
# then runs many times slower inside every co-simulation step with nothing to tell why. So the
# plugin gets -O2 in that case only; an explicit build type or an -O flag of the user's in
# CMAKE_CXX_FLAGS is left alone.

function(rumble_add_plugin name)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "rumble_add_plugin(${name}): give SOURCES")
  endif()
  add_library(${name} MODULE ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE Rumble::sdk)
  set_target_properties(${name} PROPERTIES
    PREFIX ""
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    POSITION_INDEPENDENT_CODE ON)
  get_property(multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
  if(NOT multi_config AND NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CXX_FLAGS MATCHES "(^| )-O")
    target_compile_options(${name} PRIVATE -O2)
  endif()
  if(RUMBLE_PLUGIN_OUTPUT_DIR)
    set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY ${RUMBLE_PLUGIN_OUTPUT_DIR})
  endif()
  if(RUMBLE_PLUGIN_INSTALL_DIR)
    install(TARGETS ${name} LIBRARY DESTINATION ${RUMBLE_PLUGIN_INSTALL_DIR})
  else()
    install(TARGETS ${name} LIBRARY DESTINATION lib/rumble/plugins)
  endif()
  # Refuse symbols left undefined at link time (the loader uses RTLD_NOW anyway, but failing
  # here names the missing symbol at build time), and export the entry point only.
  set(version_script "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/rumble_plugin.map")
  # Clang links the sanitizer runtimes into executables only (its AddressSanitizer docs): a
  # sanitized plugin's __asan_* symbols come from the host when it is loaded, so a Clang
  # sanitizer build cannot refuse undefined symbols.
  set(no_undefined -Wl,--no-undefined)
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang" AND "${CMAKE_CXX_FLAGS} ${CMAKE_MODULE_LINKER_FLAGS}"
                                               MATCHES "-fsanitize=")
    set(no_undefined)
  endif()
  target_link_options(${name} PRIVATE ${no_undefined} -Wl,--version-script=${version_script})
  set_property(TARGET ${name} APPEND PROPERTY LINK_DEPENDS ${version_script})
endfunction()
