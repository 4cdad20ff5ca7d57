# FindSuiteSparse
# ---------------
# Debian's SuiteSparse 5.x ships no CMake configuration. This module finds
# SuiteSparse_config and the requested components (CHOLMOD, UMFPACK, AMD,
# COLAMD, CAMD, CCOLAMD) and defines imported targets:
#   SuiteSparse::Config, SuiteSparse::CHOLMOD, SuiteSparse::UMFPACK, ...
# and SuiteSparse_FOUND, SuiteSparse_INCLUDE_DIR, SuiteSparse_<C>_FOUND.

find_path(SuiteSparse_INCLUDE_DIR NAMES SuiteSparse_config.h
  PATH_SUFFIXES suitesparse)
find_library(SuiteSparse_Config_LIBRARY NAMES suitesparseconfig)

set(_ss_headers_CHOLMOD cholmod.h)
set(_ss_headers_UMFPACK umfpack.h)
set(_ss_headers_AMD amd.h)
set(_ss_headers_COLAMD colamd.h)
set(_ss_headers_CAMD camd.h)
set(_ss_headers_CCOLAMD ccolamd.h)
# Link dependencies between components (static archives need them spelled out).
set(_ss_deps_CHOLMOD AMD COLAMD CAMD CCOLAMD)
set(_ss_deps_UMFPACK CHOLMOD AMD)

set(_ss_components ${SuiteSparse_FIND_COMPONENTS})
foreach(_c IN LISTS SuiteSparse_FIND_COMPONENTS)
  list(APPEND _ss_components ${_ss_deps_${_c}})
endforeach()
list(REMOVE_DUPLICATES _ss_components)

set(_ss_required_vars SuiteSparse_INCLUDE_DIR SuiteSparse_Config_LIBRARY)
foreach(_c IN LISTS _ss_components)
  string(TOLOWER "${_c}" _lc)
  find_library(SuiteSparse_${_c}_LIBRARY NAMES ${_lc})
  if(SuiteSparse_${_c}_LIBRARY AND EXISTS "${SuiteSparse_INCLUDE_DIR}/${_ss_headers_${_c}}")
    set(SuiteSparse_${_c}_FOUND TRUE)
  else()
    set(SuiteSparse_${_c}_FOUND FALSE)
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse
  REQUIRED_VARS ${_ss_required_vars}
  HANDLE_COMPONENTS)

if(SuiteSparse_FOUND)
  if(NOT TARGET SuiteSparse::Config)
    add_library(SuiteSparse::Config UNKNOWN IMPORTED)
    set_target_properties(SuiteSparse::Config PROPERTIES
      IMPORTED_LOCATION "${SuiteSparse_Config_LIBRARY}"
      INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
  endif()
  foreach(_c IN LISTS _ss_components)
    if(SuiteSparse_${_c}_FOUND AND NOT TARGET SuiteSparse::${_c})
      add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_c} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
    endif()
  endforeach()
  # Second pass: every component target exists now, so links can name them.
  foreach(_c IN LISTS _ss_components)
    if(TARGET SuiteSparse::${_c})
      set(_links SuiteSparse::Config)
      foreach(_d IN LISTS _ss_deps_${_c})
        if(TARGET SuiteSparse::${_d})
          list(APPEND _links SuiteSparse::${_d})
        endif()
      endforeach()
      set_property(TARGET SuiteSparse::${_c} PROPERTY INTERFACE_LINK_LIBRARIES "${_links}")
    endif()
  endforeach()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR SuiteSparse_Config_LIBRARY)
