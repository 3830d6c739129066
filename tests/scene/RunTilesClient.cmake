# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Loads a baked 3D Tiles tileset in a real client run headless by node: the TilesRenderer
# of the npm package 3d-tiles-renderer on three.js (see tiles_client.mjs).
#   cmake -DNODE=... -DNPM=... -DMODULES=<dir for node_modules> -DSCRIPT=tiles_client.mjs
#         -DBAKE_DIR=<folder the writer bakes into, removed first>
#         -DWRITER=<program baking it> -DWRITER_ARGS=<;-list, writing into BAKE_DIR>
#         [-DCLIENT_ARGS=<;-list, e.g. --strict>] -P RunTilesClient.cmake
# Without WRITER, BAKE_DIR is loaded as it is (and kept).
# The client is installed once into MODULES with npm (needs the network the first time);
# every failure says what to do.
set(TILES_RENDERER_VERSION 0.5.3)
set(THREE_VERSION 0.187.0)

foreach(var NODE NPM MODULES SCRIPT BAKE_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "RunTilesClient: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${NODE}")
  message(FATAL_ERROR "node was not found at configure time: install Debian's nodejs and npm "
                      "(scripts/install-deps.sh does) and re-run cmake")
endif()

# Installs (or re-pins) the npm packages unless MODULES holds the pinned versions.
set(wanted "")
foreach(pkg_ver "3d-tiles-renderer@${TILES_RENDERER_VERSION}" "three@${THREE_VERSION}")
  string(REGEX MATCH "^(.+)@([^@]+)$" unused "${pkg_ver}")
  set(pkg_json "${MODULES}/node_modules/${CMAKE_MATCH_1}/package.json")
  set(have "")
  if(EXISTS "${pkg_json}")
    file(READ "${pkg_json}" pkg_text)
    string(JSON have ERROR_VARIABLE json_error GET "${pkg_text}" version)
  endif()
  if(NOT have STREQUAL CMAKE_MATCH_2)
    list(APPEND wanted "${pkg_ver}")
  endif()
endforeach()
if(wanted)
  file(MAKE_DIRECTORY "${MODULES}")
  execute_process(
    COMMAND "${NPM}" install --no-audit --no-fund --save-exact --loglevel=error --prefix "${MODULES}" ${wanted}
    RESULT_VARIABLE npm_result OUTPUT_VARIABLE npm_output ERROR_VARIABLE npm_output TIMEOUT 300)
  if(NOT npm_result EQUAL 0 OR NOT EXISTS "${MODULES}/node_modules/3d-tiles-renderer/package.json"
     OR NOT EXISTS "${MODULES}/node_modules/three/package.json")
    string(REPLACE ";" " " wanted_text "${wanted}")
    message(FATAL_ERROR "cannot install the npm packages ${wanted_text} into ${MODULES} (no network?). "
                        "Run once with network: ${NPM} install --save-exact --prefix ${MODULES} ${wanted_text}\n${npm_output}")
  endif()
endif()

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
