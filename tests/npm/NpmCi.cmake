# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The npm packages the tests run (the Khronos glTF validator for
# GltfValidator.*, 3d-tiles-renderer and three for TilesClient.*), pinned by
# the committed package.json and package-lock.json next to this file (exact
# versions and integrity hashes of every package, dependencies included) and
# installed with `npm ci` into MODULES in the build tree, never into the
# source tree. Included by tests/meshing/RunGltfValidator.cmake and
# tests/scene/RunTilesClient.cmake (cmake -P scripts):
#   strata_npm_ci(<npm> <modules folder>)
# `npm ci` runs again whenever the lockfile changes (MODULES keeps a copy of
# the one it installed); otherwise MODULES is used as it is, offline.
# To change a version: edit package.json here, run
#   npm install --package-lock-only --ignore-scripts
# in this folder and commit both files.
set(STRATA_NPM_DIR "${CMAKE_CURRENT_LIST_DIR}")

function(strata_npm_ci npm modules)
  set(lock "${STRATA_NPM_DIR}/package-lock.json")
  if(EXISTS "${modules}/package-lock.json" AND EXISTS "${modules}/node_modules/.package-lock.json")
    file(SHA256 "${lock}" wanted)
    file(SHA256 "${modules}/package-lock.json" have)
    if(wanted STREQUAL have)
      return()
    endif()
  endif()
  file(MAKE_DIRECTORY "${modules}")
  file(COPY "${STRATA_NPM_DIR}/package.json" "${lock}" DESTINATION "${modules}")
  execute_process(
    COMMAND "${npm}" ci --no-audit --no-fund --ignore-scripts --loglevel=error
    WORKING_DIRECTORY "${modules}"
    RESULT_VARIABLE npm_result OUTPUT_VARIABLE npm_output ERROR_VARIABLE npm_output TIMEOUT 300)
  if(NOT npm_result EQUAL 0 OR NOT EXISTS "${modules}/node_modules/.package-lock.json")
    file(REMOVE "${modules}/package-lock.json") # so the next run tries again
    message(FATAL_ERROR "cannot install the tests' npm packages (${STRATA_NPM_DIR}/package-lock.json) into "
                        "${modules} with npm ci (no network?). Run once with network: cd ${modules} && ${npm} ci\n"
                        "${npm_output}")
  endif()
endfunction()
