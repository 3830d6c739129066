# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# ctest script: strata-view opens a window under Xvfb, renders frames and
# writes a non-constant screenshot of the size asked for; --help works and a
# bad scene path is exit code 2.
#   cmake -DVIEWER=... -DXVFB_RUN=... -DIINFO=... -DSCENE=... -DOUTPUT=... -P ViewerScreenshotTest.cmake

foreach(_var VIEWER SCENE OUTPUT)
  if(NOT ${_var})
    message(FATAL_ERROR "ViewerScreenshotTest.cmake: set ${_var}")
  endif()
endforeach()
# The tools are found at configure time; a missing one fails the test by name.
if(NOT XVFB_RUN OR NOT EXISTS "${XVFB_RUN}")
  message(FATAL_ERROR "xvfb-run is missing (install xvfb and xauth: scripts/install-deps.sh), then re-run cmake")
endif()
if(NOT IINFO OR NOT EXISTS "${IINFO}")
  message(FATAL_ERROR "iinfo is missing (install openimageio-tools: scripts/install-deps.sh), then re-run cmake")
endif()

execute_process(COMMAND ${VIEWER} --help RESULT_VARIABLE _rc OUTPUT_VARIABLE _help ERROR_VARIABLE _help)
if(NOT _rc EQUAL 0 OR NOT _help MATCHES "--screenshot" OR NOT _help MATCHES "wireframe")
  message(FATAL_ERROR "strata-view --help failed (${_rc}):\n${_help}")
endif()

execute_process(COMMAND ${VIEWER} ${SCENE}.missing RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out)
if(NOT _rc EQUAL 2)
  message(FATAL_ERROR "strata-view with a missing scene exited with ${_rc}, not 2:\n${_out}")
endif()

get_filename_component(_dir "${OUTPUT}" DIRECTORY)
file(REMOVE_RECURSE "${_dir}")
file(MAKE_DIRECTORY "${_dir}")
execute_process(
  COMMAND ${XVFB_RUN} -a ${VIEWER} ${SCENE} --size 200x120 --samples 4 --frames 3 --screenshot ${OUTPUT}
  RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out TIMEOUT 120)
message(STATUS "${_out}")
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "strata-view under xvfb-run exited with ${_rc}:\n${_out}")
endif()
if(NOT EXISTS "${OUTPUT}")
  message(FATAL_ERROR "strata-view wrote no screenshot ${OUTPUT}")
endif()
file(GLOB _leftovers "${_dir}/*.tmp*")
if(_leftovers)
  message(FATAL_ERROR "temporary files left beside the screenshot: ${_leftovers}")
endif()

execute_process(COMMAND ${IINFO} --stats ${OUTPUT} RESULT_VARIABLE _rc OUTPUT_VARIABLE _stats ERROR_VARIABLE _stats)
message(STATUS "${_stats}")
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "iinfo cannot read ${OUTPUT}:\n${_stats}")
endif()
if(NOT _stats MATCHES "200 x +120")
  message(FATAL_ERROR "the screenshot is not 200x120:\n${_stats}")
endif()
if(NOT _stats MATCHES "Constant: No")
  message(FATAL_ERROR "the screenshot is constant:\n${_stats}")
endif()
# Terrain, not just sky: the red channel spans a wide range (sky is one colour).
string(REGEX MATCH "Stats Min: ([0-9]+)" _ "${_stats}")
set(_min ${CMAKE_MATCH_1})
string(REGEX MATCH "Stats Max: ([0-9]+)" _ "${_stats}")
set(_max ${CMAKE_MATCH_1})
math(EXPR _range "${_max} - ${_min}")
if(_range LESS 60)
  message(FATAL_ERROR "the screenshot's red channel spans only ${_range} levels:\n${_stats}")
endif()
