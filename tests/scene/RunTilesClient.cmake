# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Loads a baked 3D Tiles tileset in a real client run headless by node: the TilesRenderer
# of the npm package 3d-tiles-renderer on three.js (see tiles_client.mjs).
#   cmake -DNODE=... -DNPM=... -DMODULES=<dir for node_modules> -DSCRIPT=tiles_client.mjs
#         -DBAKE_DIR=<folder the writer bakes into, removed first>
#         -DWRITER=<program baking it> -DWRITER_ARGS=<;-list, writing into BAKE_DIR>
#         [-DCLIENT_ARGS=<;-list, e.g. --strict>] -P RunTilesClient.cmake
# Without WRITER, BAKE_DIR is loaded as it is (and kept).
# The client is installed into MODULES by `npm ci` from the committed lockfile
# tests/npm/package-lock.json (tests/npm/NpmCi.cmake; needs the network the first
# time and after the lockfile changes); every failure says what to do.

foreach(var NODE NPM MODULES SCRIPT BAKE_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "RunTilesClient: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${NODE}")
  message(FATAL_ERROR "node was not found at configure time: install Debian's nodejs and npm "
                      "(scripts/install-deps.sh does) and re-run cmake")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/../npm/NpmCi.cmake")
strata_npm_ci("${NPM}" "${MODULES}")
# The versions the lockfile pins, for the messages below.
foreach(pkg 3d-tiles-renderer three)
  set(pkg_json "${MODULES}/node_modules/${pkg}/package.json")
  if(NOT EXISTS "${pkg_json}")
    message(FATAL_ERROR "npm ci did not install ${pkg} into ${MODULES}: is it in tests/npm/package.json?")
  endif()
  file(READ "${pkg_json}" pkg_text)
  string(JSON version_${pkg} GET "${pkg_text}" version)
endforeach()
set(TILES_RENDERER_VERSION ${version_3d-tiles-renderer})
set(THREE_VERSION ${version_three})

if(DEFINED WRITER AND NOT "${WRITER}" STREQUAL "")
  file(REMOVE_RECURSE "${BAKE_DIR}")
  execute_process(COMMAND "${WRITER}" ${WRITER_ARGS} RESULT_VARIABLE writer_result)
  if(NOT writer_result EQUAL 0)
    string(REPLACE ";" " " args_text "${WRITER_ARGS}")
    message(FATAL_ERROR "RunTilesClient: '${WRITER} ${args_text}' failed (${writer_result})")
  endif()
endif()
if(NOT EXISTS "${BAKE_DIR}/tileset.json")
  message(FATAL_ERROR "RunTilesClient: no tileset.json in ${BAKE_DIR}")
endif()

# ES modules ignore NODE_PATH; tiles_client.mjs reads it itself to find the packages.
set(ENV{NODE_PATH} "${MODULES}/node_modules")
execute_process(COMMAND "${NODE}" "${SCRIPT}" "${BAKE_DIR}" ${CLIENT_ARGS} RESULT_VARIABLE node_result)
if(NOT node_result EQUAL 0)
  message(FATAL_ERROR "the 3D Tiles client (3d-tiles-renderer ${TILES_RENDERER_VERSION}, three ${THREE_VERSION}) "
                      "did not load ${BAKE_DIR} as expected (exit code ${node_result}): see the FAIL line above")
endif()
