# Finds lcprelax's dependencies; also included by the installed lcprelaxConfig.cmake so
# that a consumer re-finds exactly what the library was built with.
include(CMakeFindDependencyMacro)
find_dependency(Eigen3 3.4 NO_MODULE)
find_dependency(SuiteSparse)
if(LCPRELAX_WITH_OPENMP)
  find_dependency(OpenMP)
endif()
