# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Runs the Khronos glTF validator on the .glb files a command writes.
#   cmake -DNODE=... -DNPM=... -DMODULES=<dir for node_modules> -DSCRIPT=validate_gltf.js
#         -DWRITER=<program writing the files> -DWRITER_ARGS=<;-list> -DFILES=<;-list> -P RunGltfValidator.cmake
# Optional: a second command WRITER2/WRITER2_ARGS run after the first, and
# EXPECT2, a regular expression its output must match.
# The validator is installed into MODULES by `npm ci` from the committed
# lockfile tests/npm/package-lock.json (tests/npm/NpmCi.cmake; needs the
# network the first time and after the lockfile changes); every failure says
# what to do.
foreach(var NODE NPM MODULES SCRIPT FILES)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "RunGltfValidator: ${var} is not set")
  endif()
endforeach()
if(NOT EXISTS "${NODE}")
  message(FATAL_ERROR "node was not found at configure time: install Debian's nodejs and npm "
                      "(scripts/install-deps.sh does) and re-run cmake")
endif()

include("${CMAKE_CURRENT_LIST_DIR}/../npm/NpmCi.cmake")
strata_npm_ci("${NPM}" "${MODULES}")
if(NOT EXISTS "${MODULES}/node_modules/gltf-validator/package.json")
  message(FATAL_ERROR "npm ci did not install gltf-validator into ${MODULES}: is it in tests/npm/package.json?")
endif()

if(DEFINED WRITER AND NOT "${WRITER}" STREQUAL "")
  execute_process(COMMAND "${WRITER}" ${WRITER_ARGS} RESULT_VARIABLE writer_result)
  if(NOT writer_result EQUAL 0)
    message(FATAL_ERROR "RunGltfValidator: '${WRITER} ${WRITER_ARGS}' failed (${writer_result})")
  endif()
endif()

if(DEFINED WRITER2 AND NOT "${WRITER2}" STREQUAL "")
  execute_process(COMMAND "${WRITER2}" ${WRITER2_ARGS} RESULT_VARIABLE writer_result
                  OUTPUT_VARIABLE writer_output ERROR_VARIABLE writer_output)
  message(STATUS "${writer_output}")
  if(NOT writer_result EQUAL 0)
    message(FATAL_ERROR "RunGltfValidator: '${WRITER2} ${WRITER2_ARGS}' failed (${writer_result})")
  endif()
  if(DEFINED EXPECT2 AND NOT writer_output MATCHES "${EXPECT2}")
    message(FATAL_ERROR "RunGltfValidator: the output of '${WRITER2}' does not match '${EXPECT2}'")
  endif()
endif()

set(ENV{NODE_PATH} "${MODULES}/node_modules")
execute_process(COMMAND "${NODE}" "${SCRIPT}" ${FILES} RESULT_VARIABLE node_result)
if(NOT node_result EQUAL 0)
  message(FATAL_ERROR "the glTF validator reported errors (or could not run): exit code ${node_result}")
endif()
