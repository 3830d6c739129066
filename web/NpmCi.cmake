# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Installs the web viewer's npm packages (three, 3d-tiles-renderer, esbuild,
# and puppeteer-core for the browser test), pinned by web/package-lock.json,
# with `npm ci` into MODULES in the build tree (never the source tree).
#   cmake -DNPM=<npm> -DLOCK_DIR=<web> -DMODULES=<dir> -P NpmCi.cmake
# Runs npm only when the lockfile differs from the one MODULES holds.
# To change a version: edit web/package.json, run
#   npm install --package-lock-only --ignore-scripts
# in web/ and commit both files.

foreach(var NPM LOCK_DIR MODULES)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "NpmCi.cmake: ${var} is not set")
  endif()
endforeach()
include("${CMAKE_CURRENT_LIST_DIR}/../cmake/NpmCi.cmake")
strata_npm_ci_folder("${NPM}" "${LOCK_DIR}" "${MODULES}" 600
                     "Run once with network, or configure with -DSTRATA_BUILD_WEB_VIEWER=OFF (bakes then write no viewer/).")
