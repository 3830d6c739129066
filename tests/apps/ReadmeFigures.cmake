# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# ctest script: the figures README.md (and docs/testing.md) print that are
# cheap to measure, checked against the code's own output, so they cannot go
# stale unnoticed:
# - the default scene's active voxels and evaluated points per active voxel
#   ("3.34 M active voxels, 2.49 evaluated points per active voxel"), from
#   `strata generate --no-snapshot`'s report.json (the run is deterministic:
#   the tolerance is the printed rounding);
# - "about N tests": within 5% of what `ctest -N` lists in this build tree.
# Update the text when a change moves a figure; the failure says the value.
#   cmake -DSTRATA=... -DSOURCE_DIR=... -DBUILD_DIR=... -DCTEST=... -DWORK_DIR=... -P ReadmeFigures.cmake

foreach(_var STRATA SOURCE_DIR BUILD_DIR CTEST WORK_DIR)
  if(NOT ${_var})
    message(FATAL_ERROR "ReadmeFigures.cmake: set ${_var}")
  endif()
endforeach()

file(READ "${SOURCE_DIR}/README.md" _readme)

# --- the default scene's sampling figures -----------------------------------
string(REGEX MATCH "\\(([0-9.]+) M active voxels, ([0-9.]+) evaluated points per active voxel\\)" _ "${_readme}")
if(NOT CMAKE_MATCH_1 OR NOT CMAKE_MATCH_2)
  message(FATAL_ERROR "README.md no longer says \"(X M active voxels, Y evaluated points per active voxel)\": "
                      "update this check with the text")
endif()
set(_readmeVoxels ${CMAKE_MATCH_1})
set(_readmeRatio ${CMAKE_MATCH_2})

file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND ${STRATA} generate -o ${WORK_DIR} --no-snapshot -q
                RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _out TIMEOUT 300)
if(NOT _rc EQUAL 0)
  message(FATAL_ERROR "strata generate (default scene) exited with ${_rc}:\n${_out}")
endif()
file(READ "${WORK_DIR}/report.json" _report)
string(JSON _active GET "${_report}" active_voxels)
string(JSON _evaluated GET "${_report}" evaluated_points)
# Fixed point in CMake's integer math: the ratio and the voxels in thousandths.
math(EXPR _ratio1000 "(${_evaluated} * 1000 + ${_active} / 2) / ${_active}")
math(EXPR _voxels1000 "(${_active} + 500) / 1000") # thousands of voxels = milli-M
string(REGEX REPLACE "^([0-9]+)\\.([0-9])([0-9])$" "\\1\\2\\30" _readmeRatio1000 "${_readmeRatio}")
string(REGEX REPLACE "^([0-9]+)\\.([0-9])([0-9])$" "\\1\\2\\30" _readmeVoxels1000 "${_readmeVoxels}")
if(NOT _readmeRatio1000 MATCHES "^[0-9]+$" OR NOT _readmeVoxels1000 MATCHES "^[0-9]+$")
  message(FATAL_ERROR "README.md's figures '${_readmeVoxels}' and '${_readmeRatio}' need two decimals")
endif()
math(EXPR _ratioOff "${_ratio1000} - ${_readmeRatio1000}")
math(EXPR _voxelsOff "${_voxels1000} - ${_readmeVoxels1000}")
message(STATUS "default scene: ${_active} active voxels, ${_evaluated} evaluated points "
               "(${_ratio1000}/1000 per voxel); README.md: ${_readmeVoxels} M, ${_readmeRatio}")
if(_ratioOff GREATER 5 OR _ratioOff LESS -5)
  message(FATAL_ERROR "README.md says ${_readmeRatio} evaluated points per active voxel; the default scene now "
                      "evaluates ${_evaluated} points for ${_active} active voxels (${_ratio1000}/1000): update README.md")
endif()
if(_voxelsOff GREATER 5 OR _voxelsOff LESS -5)
  message(FATAL_ERROR "README.md says ${_readmeVoxels} M active voxels; the default scene now has ${_active}: "
                      "update README.md")
endif()

# --- "about N tests" ----------------------------------------------------------
execute_process(COMMAND ${CTEST} -N --test-dir ${BUILD_DIR}
                RESULT_VARIABLE _rc OUTPUT_VARIABLE _list ERROR_VARIABLE _list)
string(REGEX MATCH "Total Tests: ([0-9]+)" _ "${_list}")
if(NOT _rc EQUAL 0 OR NOT CMAKE_MATCH_1)
  message(FATAL_ERROR "ctest -N failed (${_rc}):\n${_list}")
endif()
set(_tests ${CMAKE_MATCH_1})
foreach(_doc README.md docs/testing.md)
  file(READ "${SOURCE_DIR}/${_doc}" _text)
  string(REGEX MATCH "runs? the whole suite[^(]*\\(about ([0-9]+) tests|runs everything \\(about ([0-9]+) tests" _ "${_text}")
  set(_said "${CMAKE_MATCH_1}${CMAKE_MATCH_2}")
  if(NOT _said)
    message(FATAL_ERROR "${_doc} no longer says \"(about N tests\" where it describes the whole suite: "
                        "update this check with the text")
  endif()
  math(EXPR _low "${_tests} * 95 / 100")
  math(EXPR _high "${_tests} * 105 / 100")
  message(STATUS "${_doc}: about ${_said} tests; ctest -N: ${_tests}")
  if(_said LESS _low OR _said GREATER _high)
    message(FATAL_ERROR "${_doc} says about ${_said} tests; ctest -N lists ${_tests} here: update ${_doc}")
  endif()
endforeach()
