# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# ctest script: a figure README.md and docs/testing.md print, checked against
# this build so it cannot go stale unnoticed: "about N tests", within 5% of
# what `ctest -N` lists in this build tree. (The default scene's sampling
# figures are checked in determinism_tests, ReadmeFiguresTest.cpp, so that
# every compiler and CPU of the golden table checks them.)
# Update the text when a change moves a figure; the failure says the value.
#   cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DCTEST=... -P ReadmeFigures.cmake

foreach(_var SOURCE_DIR BUILD_DIR CTEST)
  if(NOT ${_var})
    message(FATAL_ERROR "ReadmeFigures.cmake: set ${_var}")
  endif()
endforeach()

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
