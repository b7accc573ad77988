# CHOLMOD (SuiteSparse) as one imported target, kerf::cholmod: its header folder, libcholmod and
# the libsuitesparseconfig it needs. Debian 12's SuiteSparse (5.12) ships no CMake package, so
# we look for the files ourselves. The build includes this file, and so does the installed
# kerfConfig.cmake, so that a project linking the (static) kerf library finds the same CHOLMOD.
# Sets KERF_CHOLMOD_FOUND; the cache variables below can point at another SuiteSparse.
if(NOT TARGET kerf::cholmod)
  find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
  find_library(CHOLMOD_LIBRARY cholmod)
  find_library(SUITESPARSECONFIG_LIBRARY suitesparseconfig)
  if(CHOLMOD_INCLUDE_DIR AND CHOLMOD_LIBRARY AND SUITESPARSECONFIG_LIBRARY)
    add_library(kerf::cholmod UNKNOWN IMPORTED)
    set_target_properties(kerf::cholmod PROPERTIES
      IMPORTED_LOCATION "${CHOLMOD_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${CHOLMOD_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${SUITESPARSECONFIG_LIBRARY}")
  endif()
endif()
if(TARGET kerf::cholmod)
  set(KERF_CHOLMOD_FOUND TRUE)
else()
  set(KERF_CHOLMOD_FOUND FALSE)
endif()
