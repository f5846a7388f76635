# For the tests' `cmake -P` scripts (include it): install_tree(<build dir> <prefix>) installs what
# `cmake --install <build dir> --prefix <prefix>` installs, without writing into the build tree.
# CMake's script for the top directory of a build tree ends by writing the list of what it
# installed to <build dir>/install_manifest.txt, and CMake 3.25 has no option against it: a test
# installing the engine wrote into the build tree it tests, and two such tests at once
# (ctest -j) wrote the same file. The top directory's script does nothing else here but include
# its subdirectories' scripts, which write no manifest; each is run as
# `cmake --install <build dir>/<subdir>`, in the same order. Should the top directory install
# something itself one day, this stops and says so.
include(${CMAKE_CURRENT_LIST_DIR}/script_step.cmake)  # step(name command...)

function(install_tree build_dir prefix)
  file(READ ${build_dir}/cmake_install.cmake top)
  if(top MATCHES "file\\(INSTALL")
    message(FATAL_ERROR "install_tree: the top directory of ${build_dir} installs files itself; "
                        "install_tree installs only its subdirectories")
  endif()
  string(REGEX MATCHALL "include\\(\"[^\"]+/cmake_install\\.cmake\"\\)" includes "${top}")
  if(NOT includes)
    message(FATAL_ERROR "install_tree: ${build_dir}/cmake_install.cmake includes no subdirectory")
  endif()
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "include\\(\"([^\"]+)/cmake_install\\.cmake\"\\)" "\\1" dir "${line}")
    step("install ${dir}" ${CMAKE_COMMAND} --install ${dir} --prefix ${prefix})
  endforeach()
endfunction()
