# FindSuiteSparse: CHOLMOD, AMD, COLAMD, KLU, BTF, UMFPACK and SuiteSparse_config as
# imported targets SuiteSparse::<lib> (Debian 12 ships SuiteSparse 5.12 without CMake
# config files). Defines SuiteSparse_FOUND.
find_path(SuiteSparse_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse)
set(_ss_components cholmod klu btf umfpack amd camd colamd ccolamd suitesparseconfig)
set(_ss_required SuiteSparse_INCLUDE_DIR)
foreach(_c IN LISTS _ss_components)
  find_library(SuiteSparse_${_c}_LIBRARY ${_c})
  list(APPEND _ss_required SuiteSparse_${_c}_LIBRARY)
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(SuiteSparse REQUIRED_VARS ${_ss_required})
if(SuiteSparse_FOUND)
  foreach(_c IN LISTS _ss_components)
    if(NOT TARGET SuiteSparse::${_c})
      add_library(SuiteSparse::${_c} UNKNOWN IMPORTED)
      set_target_properties(SuiteSparse::${_c} PROPERTIES
        IMPORTED_LOCATION "${SuiteSparse_${_c}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${SuiteSparse_INCLUDE_DIR}")
    endif()
  endforeach()
endif()
mark_as_advanced(SuiteSparse_INCLUDE_DIR)
