# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The determinism rules of docs/determinism.md, checked on the source tree
# and on this build's compile commands (ctest: DeterminismRules). Fails
# listing every file:line that breaks one, with the rule.
#   cmake -DSOURCE_DIR=... -DBUILD_DIR=... -P DeterminismRules.cmake
#
# 1. Every compile command of the project has -ffp-contract=off, and none
#    has fast-math (-ffast-math, -Ofast, -funsafe-math-optimizations,
#    -ffp-contract=fast).
# 2. In the libraries whose bytes are promised (common, terrain, meshing,
#    world, scene, serve): no libm transcendental function (std:: or glm::
#    sin, cos, tan, asin, acos, atan, atan2, exp, exp2, expm1, log, log2,
#    log10, log1p, pow, hypot, cbrt, sinh, cosh, tanh, erf, erfc, tgamma,
#    lgamma): strata::dmath has the deterministic ones. Files that only make
#    pictures or test shapes are listed below with their reason.
# 3. There: no float→int conversion of a floor or ceil by a cast
#    (int(std::floor(x)), std::int64_t(std::ceil(x)), static_cast<...>), and
#    no lround/llround: floorToInt<I>(), ceilToInt<I>() and roundToInt<I>()
#    (strata/IntegerMath.h) clamp, and map NaN to 0, where the cast is
#    undefined behaviour (and lround's result unspecified).
# 4. There: no standard random engines or distributions, and no Highway
#    MulAdd (a fused multiply-add on targets that have one).
cmake_minimum_required(VERSION 3.22)

set(problems "")
set(problem_count 0)
macro(problem text)
  string(APPEND problems "\n  ${text}")
  math(EXPR problem_count "${problem_count} + 1")
endmacro()

# --- 1. the compile commands ---------------------------------------------
set(commands_file "${BUILD_DIR}/compile_commands.json")
if(NOT EXISTS "${commands_file}")
  message(FATAL_ERROR "DeterminismRules: ${commands_file} is missing (CMAKE_EXPORT_COMPILE_COMMANDS is ON in the top CMakeLists.txt)")
endif()
file(STRINGS "${commands_file}" command_lines REGEX "\"command\":")
list(LENGTH command_lines command_count)
if(command_count EQUAL 0)
  message(FATAL_ERROR "DeterminismRules: no compile commands in ${commands_file}")
endif()
foreach(line IN LISTS command_lines)
  string(REGEX MATCH "[^ \"]+\\.(cpp|cc|cxx|c)\"?,?$" source "${line}")
  if(NOT line MATCHES "-ffp-contract=off")
    problem("compile command without -ffp-contract=off: ${source}")
  endif()
  if(line MATCHES "-ffast-math|-Ofast|-funsafe-math-optimizations|-ffp-contract=fast")
    problem("compile command with fast-math: ${source}")
  endif()
endforeach()

# --- 2 to 4. the sources ---------------------------------------------------
# Files that may call libm, each for its reason.
set(libm_allowed
  scene/src/ParetoPlot.cpp      # the Pareto plot's axes (a picture)
  scene/src/Scene.cpp           # the light's direction from azimuth and elevation (renders)
  scene/src/Snapshot.cpp        # the orbit camera (renders)
  scene/src/BakeRender.cpp      # the screen-space error of the whole-world render
  meshing/src/AnalyticShapes.cpp # analytic test shapes for the meshers' tests and benchmarks
)
set(libm_functions "sin|cos|tan|asin|acos|atan|atan2|exp|exp2|expm1|log|log2|log10|log1p|pow|hypot|cbrt|sinh|cosh|tanh|erf|erfc|tgamma|lgamma")
set(int_types "int|long|unsigned|std::int64_t|std::int32_t|std::uint64_t|std::uint32_t|std::size_t|std::ptrdiff_t|int64_t|int32_t|size_t")

set(sources "")
foreach(dir common terrain meshing world scene serve)
  file(GLOB_RECURSE found RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/${dir}/*.cpp" "${SOURCE_DIR}/${dir}/*.h")
  list(APPEND sources ${found})
endforeach()
list(LENGTH sources source_count)
if(source_count LESS 50)
  message(FATAL_ERROR "DeterminismRules: found ${source_count} sources under ${SOURCE_DIR}, expected the libraries")
endif()

foreach(rel IN LISTS sources)
  # One list element per line: semicolons and brackets would split or join
  # CMake's list elements, so they are replaced first (the rules need none).
  file(READ "${SOURCE_DIR}/${rel}" content)
  string(REPLACE ";" "," content "${content}")
  string(REPLACE "[" "(" content "${content}")
  string(REPLACE "]" ")" content "${content}")
  string(REPLACE "\\" "/" content "${content}")
  string(REPLACE "\n" ";" lines "${content}")
  set(number 0)
  list(FIND libm_allowed "${rel}" allowed)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    # Code only: drop line comments and string literals.
    string(REGEX REPLACE "//.*$" "" code " ${line}")
    string(REGEX REPLACE "\"([^\"\\\\]|\\\\.)*\"" "\"\"" code "${code}")
    if(allowed EQUAL -1 AND code MATCHES "[^A-Za-z0-9_:](std|glm)::(${libm_functions})f?[ ]*\\(")
      problem("${rel}:${number}: libm in a value path (use strata::dmath): ${line}")
    endif()
    if(code MATCHES "[^A-Za-z0-9_:](${int_types})[ ]*\\([ ]*(std::)?(floor|ceil)[ ]*\\("
       OR code MATCHES "static_cast<[ ]*(${int_types})[ ]*>[ ]*\\([ ]*(std::)?(floor|ceil)[ ]*\\(")
      problem("${rel}:${number}: a cast of floor/ceil to an integer (use floorToInt/ceilToInt): ${line}")
    endif()
    if(code MATCHES "[^A-Za-z0-9_]l?lround[ ]*\\(")
      problem("${rel}:${number}: lround/llround (use roundToInt): ${line}")
    endif()
    if(code MATCHES "(uniform_int_distribution|uniform_real_distribution|normal_distribution|bernoulli_distribution|random_device|mt19937|default_random_engine|[^A-Za-z0-9_:]rand[ ]*\\()")
      problem("${rel}:${number}: a standard random engine or distribution (use the integer hashes): ${line}")
    endif()
    if(code MATCHES "[^A-Za-z0-9_](MulAdd|NegMulAdd|MulSub|NegMulSub)[ ]*\\(")
      problem("${rel}:${number}: Highway's fused multiply-add: ${line}")
    endif()
  endforeach()
endforeach()

if(problem_count GREATER 0)
  message(FATAL_ERROR "DeterminismRules: ${problem_count} place(s) break the rules of docs/determinism.md:${problems}")
endif()
message(STATUS "DeterminismRules: ${command_count} compile commands and ${source_count} sources follow the rules")
