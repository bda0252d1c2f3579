# Install rules and the exported CMake package (find_package(lcprelax)).
include(CMakePackageConfigHelpers)
list(TRANSFORM LCPRELAX_LAYERS PREPEND lcprelax_ OUTPUT_VARIABLE _layer_targets)
install(TARGETS lcprelax ${_layer_targets} lcprelax_warnings
  EXPORT lcprelaxTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(_module IN LISTS LCPRELAX_LAYERS)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${_module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
set(_cfgdir ${CMAKE_INSTALL_LIBDIR}/cmake/lcprelax)
install(EXPORT lcprelaxTargets NAMESPACE lcprelax:: DESTINATION ${_cfgdir})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lcprelaxConfig.cmake.in
  ${PROJECT_BINARY_DIR}/lcprelaxConfig.cmake INSTALL_DESTINATION ${_cfgdir})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lcprelaxConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lcprelaxConfig.cmake
  ${PROJECT_BINARY_DIR}/lcprelaxConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/FindSuiteSparse.cmake
  ${PROJECT_SOURCE_DIR}/cmake/LcprelaxDependencies.cmake
  DESTINATION ${_cfgdir})
