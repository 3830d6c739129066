# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Install rules and the package configuration for find_package(Strata).
include(CMakePackageConfigHelpers)

install(EXPORT StrataTargets
  NAMESPACE strata::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Strata)

configure_package_config_file(
  ${CMAKE_CURRENT_SOURCE_DIR}/cmake/StrataConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/StrataConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Strata)
write_basic_package_version_file(
  ${CMAKE_CURRENT_BINARY_DIR}/StrataConfigVersion.cmake
  VERSION ${PROJECT_VERSION}
  COMPATIBILITY SameMinorVersion)
install(FILES
  ${CMAKE_CURRENT_BINARY_DIR}/StrataConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/StrataConfigVersion.cmake
  ${CMAKE_CURRENT_SOURCE_DIR}/cmake/StrataDependencies.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/Strata)
