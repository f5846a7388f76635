# UMFPACK from SuiteSparse (complex sparse LU: the FEM soil's receptance). Same fallback as
# FindCHOLMOD.cmake: Debian 12's SuiteSparse 5.12 has no CMake config.
find_package(UMFPACK CONFIG QUIET)
if(TARGET SuiteSparse::UMFPACK)
  set(UMFPACK_FOUND TRUE)
  return()
endif()
find_path(UMFPACK_INCLUDE_DIR umfpack.h PATH_SUFFIXES suitesparse)
find_library(UMFPACK_LIBRARY NAMES umfpack)
find_library(UMFPACK_AMD_LIBRARY NAMES amd)
find_library(UMFPACK_CONFIG_LIBRARY NAMES suitesparseconfig)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(UMFPACK
  REQUIRED_VARS UMFPACK_LIBRARY UMFPACK_AMD_LIBRARY UMFPACK_CONFIG_LIBRARY UMFPACK_INCLUDE_DIR)
if(UMFPACK_FOUND AND NOT TARGET SuiteSparse::UMFPACK)
  add_library(SuiteSparse::UMFPACK UNKNOWN IMPORTED)
  set_target_properties(SuiteSparse::UMFPACK PROPERTIES
    IMPORTED_LOCATION "${UMFPACK_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${UMFPACK_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${UMFPACK_AMD_LIBRARY};${UMFPACK_CONFIG_LIBRARY}")
endif()
mark_as_advanced(UMFPACK_INCLUDE_DIR UMFPACK_LIBRARY UMFPACK_AMD_LIBRARY UMFPACK_CONFIG_LIBRARY)
