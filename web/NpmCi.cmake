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
set(lock "${LOCK_DIR}/package-lock.json")
if(EXISTS "${MODULES}/package-lock.json" AND EXISTS "${MODULES}/node_modules/.package-lock.json")
  file(SHA256 "${lock}" wanted)
  file(SHA256 "${MODULES}/package-lock.json" have)
  if(wanted STREQUAL have)
    return()
  endif()
endif()
file(MAKE_DIRECTORY "${MODULES}")
file(COPY "${LOCK_DIR}/package.json" "${lock}" DESTINATION "${MODULES}")
execute_process(
  COMMAND "${NPM}" ci --no-audit --no-fund --ignore-scripts --loglevel=error
  WORKING_DIRECTORY "${MODULES}"
  RESULT_VARIABLE npm_result OUTPUT_VARIABLE npm_output ERROR_VARIABLE npm_output TIMEOUT 600)
if(NOT npm_result EQUAL 0 OR NOT EXISTS "${MODULES}/node_modules/.package-lock.json")
  file(REMOVE "${MODULES}/package-lock.json") # so the next run tries again
  message(FATAL_ERROR "cannot install the web viewer's npm packages (${lock}) into ${MODULES} with npm ci "
                      "(no network?). Run once with network, or configure with -DSTRATA_BUILD_WEB_VIEWER=OFF "
                      "(bakes then write no viewer/).\n${npm_output}")
endif()
