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

include("${CMAKE_CURRENT_LIST_DIR}/../../cmake/NpmCi.cmake")

function(strata_npm_ci npm modules)
  strata_npm_ci_folder("${npm}" "${STRATA_NPM_DIR}" "${modules}" 300
                       "Run once with network: cd ${modules} && ${npm} ci")
endfunction()
