# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Finds every third-party package Strata uses. Shared by the build tree and,
# through StrataConfig.cmake, by projects that find_package(Strata).
# Debian 12 quirks are handled where they bite (comments below).

# TBB's config package must come before OpenVDB's find module, which would
# otherwise create a second set of TBB targets.
find_package(TBB CONFIG REQUIRED)

# OpenVDB ships only a find module, outside CMake's default module path.
find_path(STRATA_OPENVDB_MODULE_DIR FindOpenVDB.cmake
  PATHS /usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB /usr/local/lib/cmake/OpenVDB
        /usr/local/lib64/cmake/OpenVDB
  NO_DEFAULT_PATH)
if(STRATA_OPENVDB_MODULE_DIR)
  list(APPEND CMAKE_MODULE_PATH ${STRATA_OPENVDB_MODULE_DIR})
endif()
# FindOpenVDB sets BUILD_SHARED_LIBS=ON in the caller's scope: keep ours.
set(_strata_saved_shared "${BUILD_SHARED_LIBS}")
find_package(OpenVDB REQUIRED)
set(BUILD_SHARED_LIBS "${_strata_saved_shared}")

find_package(glm CONFIG REQUIRED)
# Google Highway: the noise kernels' SIMD, dispatched at run time (terrain).
find_package(hwy CONFIG REQUIRED)
# zlib: deflated members of NumPy .npz elevation files (terrain's ElevationFile).
find_package(ZLIB REQUIRED)
# libcrypto: SHA-256 for the bake manifest (strata::common).
find_package(OpenSSL REQUIRED COMPONENTS Crypto)
find_package(OpenMesh CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)
# libpng: PNG files are decoded by it directly, with a per-read error handler
# (render's ImageFileInput; OpenImageIO 2.4 lets libpng print on stderr).
find_package(PNG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
# Debian's OpenImageIO config lists /usr/include/opencv4, which only exists
# when OpenCV is installed: drop missing include directories.
if(TARGET OpenImageIO::OpenImageIO)
  get_target_property(_oiio_inc OpenImageIO::OpenImageIO INTERFACE_INCLUDE_DIRECTORIES)
  if(_oiio_inc)
    set(_oiio_kept "")
    foreach(_dir IN LISTS _oiio_inc)
      if(EXISTS "${_dir}" OR _dir MATCHES "^\\$<")
        list(APPEND _oiio_kept "${_dir}")
      endif()
    endforeach()
    set_target_properties(OpenImageIO::OpenImageIO PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${_oiio_kept}")
  endif()
endif()

set(OpenGL_GL_PREFERENCE GLVND)
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(PkgConfig REQUIRED)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
# Windows with an OpenGL context (strata::render's GlfwContext, strata-view).
find_package(glfw3 CONFIG REQUIRED)

# strata::scene reads TOML scene files and writes JSON reports (header-only
# libraries, but its exported static target names them).
find_package(tomlplusplus CONFIG REQUIRED)
# GDAL: digital elevation models for the dem_heightfield node (scene's
# DemFile.cpp); left out where STRATA_WITH_GDAL is OFF.
if(STRATA_WITH_GDAL)
  find_package(GDAL CONFIG REQUIRED)
endif()
find_package(nlohmann_json CONFIG REQUIRED)
