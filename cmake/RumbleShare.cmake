# rumble_share_files(<target> DESTINATION <subdir> FILES <files...> [PROGRAMS])
#
# Data the engine reads at run time (plot scripts, plugin templates) lives in share/rumble next
# to bin/, installed or not: the engine looks in exactly one place, <dir of rumble>/../share/rumble,
# and no source path is compiled into it. So each file is copied into the build tree's
# share/rumble/<subdir> when <target> builds (and again whenever it changes), and installed
# to the same relative place. Always share/, never CMAKE_INSTALL_DATADIR: that is where the
# engine looks, whatever the platform's convention.
set(RUMBLE_SHARE_OUTPUT_DIR ${CMAKE_BINARY_DIR}/share/rumble)
set(RUMBLE_SHARE_INSTALL_DIR share/rumble)

function(rumble_share_files target)
  cmake_parse_arguments(ARG "PROGRAMS" "DESTINATION" "FILES" ${ARGN})
  set(subdir "")
  if(ARG_DESTINATION)
    set(subdir "/${ARG_DESTINATION}")
  endif()
  set(outputs)
  foreach(file IN LISTS ARG_FILES)
    get_filename_component(source ${file} ABSOLUTE)
    get_filename_component(file_name ${file} NAME)
    set(output ${RUMBLE_SHARE_OUTPUT_DIR}${subdir}/${file_name})
    add_custom_command(OUTPUT ${output}
      COMMAND ${CMAKE_COMMAND} -E copy ${source} ${output}
      DEPENDS ${source}
      COMMENT "share/rumble${subdir}/${file_name}")
    list(APPEND outputs ${output})
  endforeach()
  if(NOT TARGET ${target})
    add_custom_target(${target} ALL)
  endif()
  string(MAKE_C_IDENTIFIER "${target}${subdir}" stage)
  add_custom_target(${stage}_files DEPENDS ${outputs})
  add_dependencies(${target} ${stage}_files)
  if(ARG_PROGRAMS)
    install(PROGRAMS ${ARG_FILES} DESTINATION ${RUMBLE_SHARE_INSTALL_DIR}${subdir})
  else()
    install(FILES ${ARG_FILES} DESTINATION ${RUMBLE_SHARE_INSTALL_DIR}${subdir})
  endif()
endfunction()
