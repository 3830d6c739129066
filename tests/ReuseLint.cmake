# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Runs `reuse lint` (Debian's reuse) on the source tree: every file must state
# its copyright and licence, in an SPDX header or in .reuse/dep5 (issue 31).
# Fails, naming the files, when one does not; fails when reuse is missing.
# Usage: cmake -DSOURCE_DIR=<repository root> -P ReuseLint.cmake
find_program(REUSE reuse)
if(NOT REUSE)
  message(FATAL_ERROR "reuse was not found: install Debian's reuse package "
                      "(scripts/install-deps.sh installs it); this test checks every file's licence")
endif()
execute_process(COMMAND ${REUSE} lint
  WORKING_DIRECTORY ${SOURCE_DIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  # reuse lists the offending files under headings; repeat the file lines
  # (those starting with "* " before the summary) in the failure message.
  string(REGEX REPLACE "# SUMMARY.*" "" listed "${out}")
  string(REGEX MATCHALL "\\* [^\n]+" files "${listed}")
  list(JOIN files "\n  " files_text)
  # (The SPDX tag names are not spelt out here: reuse would read them as
  # this file's own tags.)
  message(FATAL_ERROR "reuse lint failed (${rc}) in ${SOURCE_DIR}: give these files the two-line "
                      "SPDX header (FileCopyrightText: The Strata authors, License-Identifier: MIT) "
                      "or an entry in .reuse/dep5:\n  ${files_text}\n\nreuse lint said:\n${out}${err}")
endif()
message("reuse lint: every file states its copyright and licence")
