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

# The licence and the third-party notices (issue 31), in share/doc/strata:
# GNUInstallDirs' own default would be share/doc/Strata (the project name);
# a CMAKE_INSTALL_DOCDIR given by the user wins.
if("$CACHE{CMAKE_INSTALL_DOCDIR}" STREQUAL "")
  set(STRATA_INSTALL_DOCDIR ${CMAKE_INSTALL_DATAROOTDIR}/doc/strata)
else()
  set(STRATA_INSTALL_DOCDIR ${CMAKE_INSTALL_DOCDIR})
endif()
install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/LICENSE ${CMAKE_CURRENT_SOURCE_DIR}/THIRD_PARTY.md
  DESTINATION ${STRATA_INSTALL_DOCDIR})
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/LICENSES DESTINATION ${STRATA_INSTALL_DOCDIR})
