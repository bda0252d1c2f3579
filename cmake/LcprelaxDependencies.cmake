# Finds lcprelax's dependencies; also included by the installed lcprelaxConfig.cmake so
# that a consumer re-finds exactly what the library was built with.
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.4 NO_MODULE)
find_dependency(SuiteSparse)
if(LCPRELAX_WITH_OPENMP)
  find_dependency(OpenMP)
endif()
# Cairo (optional, scene pictures), through pkg-config as the imported target
# PkgConfig::CAIRO. In lcprelax's own build LCPRELAX_WITH_CAIRO enables the search and a
# missing Cairo only disables pictures. For a consumer of the installed package (this file
# then sits beside lcprelaxTargets.cmake) Cairo is re-found, and required, exactly when the
# exported targets link it.
if(EXISTS "${CMAKE_CURRENT_LIST_DIR}/lcprelaxTargets.cmake")
  file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/lcprelaxTargets.cmake" _lcprelax_uses_cairo REGEX "PkgConfig::CAIRO")
  if(_lcprelax_uses_cairo AND NOT TARGET PkgConfig::CAIRO)
    find_dependency(PkgConfig)
    pkg_check_modules(CAIRO QUIET IMPORTED_TARGET cairo)
    if(NOT CAIRO_FOUND)
      set(${CMAKE_FIND_PACKAGE_NAME}_NOT_FOUND_MESSAGE "lcprelax was built with Cairo, but pkg-config cannot find cairo")
      set(${CMAKE_FIND_PACKAGE_NAME}_FOUND FALSE)
      return()
    endif()
  endif()
elseif(LCPRELAX_WITH_CAIRO)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(CAIRO QUIET IMPORTED_TARGET cairo)
  endif()
  if(NOT TARGET PkgConfig::CAIRO)
    message(STATUS "lcprelax: Cairo not found (pkg-config cairo), pictures disabled")
  endif()
endif()
# PETSc and MPI (optional, LCPRELAX_WITH_PETSC): pkg-config petsc as PkgConfig::PETSC plus
# MPI::MPI_CXX (C API only). In lcprelax's own build LCPRELAX_WITH_PETSC enables the search
# and a missing PETSc or MPI disables them with a warning (the library, its tests and apps
# work without); a consumer re-finds them exactly when the exported targets link them.
if(EXISTS "${CMAKE_CURRENT_LIST_DIR}/lcprelaxTargets.cmake")
  file(STRINGS "${CMAKE_CURRENT_LIST_DIR}/lcprelaxTargets.cmake" _lcprelax_uses_petsc REGEX "PkgConfig::PETSC")
  if(_lcprelax_uses_petsc AND NOT TARGET PkgConfig::PETSC)
    set(MPI_CXX_SKIP_MPICXX ON)
    find_dependency(MPI COMPONENTS CXX)
    find_dependency(PkgConfig)
    pkg_check_modules(PETSC QUIET IMPORTED_TARGET petsc)
    if(NOT PETSC_FOUND)
      set(${CMAKE_FIND_PACKAGE_NAME}_NOT_FOUND_MESSAGE "lcprelax was built with PETSc, but pkg-config cannot find petsc")
      set(${CMAKE_FIND_PACKAGE_NAME}_FOUND FALSE)
      return()
    endif()
  endif()
elseif(LCPRELAX_WITH_PETSC)
  set(MPI_CXX_SKIP_MPICXX ON)  # the C API only
  find_package(MPI QUIET COMPONENTS CXX)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(PETSC QUIET IMPORTED_TARGET petsc)
  endif()
  if(MPI_CXX_FOUND AND TARGET PkgConfig::PETSC)
    message(STATUS "lcprelax: PETSc ${PETSC_VERSION} with MPI (MUMPS KKT backend, MPI learning)")
  else()
    message(WARNING "lcprelax: PETSc (pkg-config petsc) or MPI not found: built without them "
                    "(Debian: apt-get install libpetsc-real3.18-dev)")
    set(LCPRELAX_WITH_PETSC OFF)
  endif()
endif()
