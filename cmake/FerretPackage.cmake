include(CMakePackageConfigHelpers)
set(FERRET_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ferret)
install(EXPORT ferretTargets NAMESPACE ferret:: DESTINATION ${FERRET_CMAKE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ferretConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/ferretConfig.cmake INSTALL_DESTINATION ${FERRET_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ferretConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ferretConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/ferretConfigVersion.cmake
        DESTINATION ${FERRET_CMAKE_DIR})
