# The layer graph: one target lcprelax_<layer> per folder <layer>/, from the bottom up, and
# the layers each may use (its direct and indirect dependencies). Read by the top-level
# CMakeLists.txt (lcprelax_add_layer links exactly these) and by cmake/check_layers.cmake
# (which fails on an include outside them and on a cycle). docs/architecture.md explains it.
set(LCPRELAX_LAYERS core mpi sparse kkt lcp io world contact models scenes learn)
set(LCPRELAX_LAYER_USES_core "")
set(LCPRELAX_LAYER_USES_mpi core)
set(LCPRELAX_LAYER_USES_sparse core mpi)
set(LCPRELAX_LAYER_USES_kkt core mpi sparse)
set(LCPRELAX_LAYER_USES_lcp core sparse kkt)
set(LCPRELAX_LAYER_USES_io core sparse kkt)
set(LCPRELAX_LAYER_USES_world core)
set(LCPRELAX_LAYER_USES_contact core world)
set(LCPRELAX_LAYER_USES_models core sparse kkt lcp io world contact)
set(LCPRELAX_LAYER_USES_scenes core world contact models)
set(LCPRELAX_LAYER_USES_learn core mpi sparse kkt lcp world contact models scenes)

# lcprelax_add_layer(<layer> [SOURCES src/a.cpp ...] [LINKS <other targets> ...]): the
# target lcprelax_<layer> (alias lcprelax::<layer>) from the listed sources (header only
# without SOURCES), its public include directory <layer>/include, linked to the layers it
# may use and to LINKS (external libraries).
function(lcprelax_add_layer layer)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINKS" ${ARGN})
  set(target lcprelax_${layer})
  set(uses ${LCPRELAX_LAYER_USES_${layer}})
  list(TRANSFORM uses PREPEND lcprelax_)
  if(ARG_SOURCES)
    add_library(${target} STATIC ${ARG_SOURCES})
    if(LCPRELAX_UNITY_BUILD)
      # Unity batches share one translation unit: file-local helpers must have unique names
      # (shared ones live in a header).
      set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
    endif()
    set(scope PUBLIC)
    target_link_libraries(${target} PRIVATE $<BUILD_INTERFACE:lcprelax_warnings>)
  else()
    add_library(${target} INTERFACE)
    set(scope INTERFACE)
  endif()
  add_library(lcprelax::${layer} ALIAS ${target})
  target_include_directories(${target} ${scope}
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${target} ${scope} ${uses} ${ARG_LINKS})
endfunction()
