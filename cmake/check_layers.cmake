# Fails when a layer includes a header of a layer it may not use (an upward include) or
# when the allowed uses form a cycle. Run as
#   cmake -DSOURCE_DIR=<repository> -P cmake/check_layers.cmake
# (ctest: architecture_layers). The layer graph is cmake/LcprelaxLayers.cmake, the same map
# from which each layer's target links the layers below it.
cmake_minimum_required(VERSION 3.25)
include("${CMAKE_CURRENT_LIST_DIR}/LcprelaxLayers.cmake")
set(_layers ${LCPRELAX_LAYERS})
foreach(_layer IN LISTS _layers)
  set(_allowed_${_layer} ${LCPRELAX_LAYER_USES_${_layer}})
endforeach()

set(_violations "")
foreach(_layer IN LISTS _layers)
  file(GLOB_RECURSE _files "${SOURCE_DIR}/${_layer}/*.hpp" "${SOURCE_DIR}/${_layer}/*.cpp")
  if(NOT EXISTS "${SOURCE_DIR}/${_layer}")
    string(APPEND _violations "  layer folder ${_layer}/ is missing\n")
  endif()
  foreach(_file IN LISTS _files)
    file(STRINGS "${_file}" _includes REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]lcprelax/")
    foreach(_line IN LISTS _includes)
      string(REGEX MATCH "lcprelax/([a-z_]+)/" _m "${_line}")
      set(_target "${CMAKE_MATCH_1}")
      if(NOT _target STREQUAL _layer AND NOT _target IN_LIST _allowed_${_layer})
        file(RELATIVE_PATH _rel "${SOURCE_DIR}" "${_file}")
        string(APPEND _violations "  ${_rel}: '${_line}' (layer ${_layer} may use: ${_allowed_${_layer}})\n")
      endif()
    endforeach()
  endforeach()
endforeach()

# No cycles: every layer may only use layers listed before it in _layers.
set(_seen "")
foreach(_layer IN LISTS _layers)
  foreach(_dep IN LISTS _allowed_${_layer})
    if(NOT _dep IN_LIST _seen)
      string(APPEND _violations "  layer ${_layer} uses ${_dep}, which is not below it (cycle)\n")
    endif()
  endforeach()
  list(APPEND _seen ${_layer})
endforeach()

if(_violations)
  message(FATAL_ERROR "layer violations:\n${_violations}")
endif()
list(LENGTH _layers _n)
message(STATUS "architecture_layers: ${_n} layers, no upward include, no cycle")
