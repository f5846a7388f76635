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
#
# After each link the plugin's manifest, <name>.so.manifest.json, is written next to it (and
# installed with it) by `rumble plugins --manifest`: the engine then knows the plugin's types
# without loading it, and loads it only for a scenario that uses one of them
# (docs/plugin-guide.md, "The manifest"). The rumble that writes it: RUMBLE_MANIFEST_COMMAND
# when set (a command list; the engine's own build sets it), else the rumble installed with this
# SDK (Rumble_EXECUTABLE). Without either there is no manifest and the engine loads the plugin
# at start-up, as it loads every plugin without one.

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
  _rumble_plugin_manifest(${name})
endfunction()

function(_rumble_plugin_manifest name)
  set(command ${RUMBLE_MANIFEST_COMMAND})
  if(NOT command AND Rumble_EXECUTABLE AND EXISTS "${Rumble_EXECUTABLE}")
    set(command "${Rumble_EXECUTABLE}")
  endif()
  if(NOT command)
    return()
  endif()
  # Where the library goes (OUTPUT may not name the target's file by a generator expression).
  get_target_property(dir ${name} LIBRARY_OUTPUT_DIRECTORY)
  if(NOT dir)
    set(dir ${CMAKE_CURRENT_BINARY_DIR})
  endif()
  get_property(multi_config GLOBAL PROPERTY GENERATOR_IS_MULTI_CONFIG)
  if(multi_config)
    string(APPEND dir "/$<CONFIG>")
  endif()
  set(manifest "${dir}/${name}${CMAKE_SHARED_MODULE_SUFFIX}.manifest.json")
  add_custom_command(OUTPUT ${manifest}
    COMMAND ${command} plugins --manifest $<TARGET_FILE:${name}> --output ${manifest}
    DEPENDS ${name} ${RUMBLE_MANIFEST_DEPENDS}
    COMMENT "Writing the manifest of plugin ${name}"
    VERBATIM)
  add_custom_target(${name}_manifest ALL DEPENDS ${manifest})
  if(RUMBLE_PLUGIN_INSTALL_DIR)
    install(FILES ${manifest} DESTINATION ${RUMBLE_PLUGIN_INSTALL_DIR} OPTIONAL)
  else()
    install(FILES ${manifest} DESTINATION lib/rumble/plugins OPTIONAL)
  endif()
endfunction()
