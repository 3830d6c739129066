#!/bin/sh

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Configures the ASan + UBSan build folder (clang; -DSTRATA_FUZZ=ON
# instruments all of Strata and adds the fuzzers) once: the one place both
# scripts/sanitizers.sh and scripts/fuzz.sh configure it.
#   scripts/configure-sanitize.sh BUILD_DIR
# Line tables only (-gline-tables-only): the reports' stacks keep their
# files and lines, and the build skips full debug information. No web
# viewer (-DSTRATA_BUILD_WEB_VIEWER=OFF): its npm ci and bundle are node's
# work, and its browser test does not run under the sanitizers. No programs
# (-DSTRATA_BUILD_APPS=OFF): they parse flags and print around the library
# calls the sanitized tests run; the tests that start the strata program skip.
set -eu
build=$1
root=$(cd "$(dirname "$0")/.." && pwd)
cxx=${CXX_FUZZ:-$(command -v clang++-15 || command -v clang++-14 || command -v clang++)}
cc=${CC_FUZZ:-$(command -v clang-15 || command -v clang-14 || command -v clang)}
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_FUZZ=ON \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
    -DSTRATA_BUILD_WEB_VIEWER=OFF -DSTRATA_BUILD_APPS=OFF -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" >/dev/null
fi
