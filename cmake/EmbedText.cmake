# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# cmake -DINPUT=file -DOUTPUT=header -DNAME=IDENTIFIER -P EmbedText.cmake
# Writes a header declaring `inline constexpr std::string_view NAME` holding
# the file's text, so a program carries its default data without asset files.
file(READ "${INPUT}" content)
set(delimiter "strata_embed")
string(FIND "${content}" ")${delimiter}\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter )${delimiter}\"")
endif()
file(WRITE "${OUTPUT}.tmp"
  "// Generated from ${INPUT} by EmbedText.cmake. Do not edit.\n"
  "#pragma once\n#include <string_view>\n"
  "inline constexpr std::string_view ${NAME} = R\"${delimiter}(${content})${delimiter}\";\n")
file(RENAME "${OUTPUT}.tmp" "${OUTPUT}")
