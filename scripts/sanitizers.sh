#!/bin/sh

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Sanitizers and fuzzers, bounded in time (2 cores, a cold ccache):
#  1. ASan + UBSan (clang) in build-sanitize/: the same build also makes the
#     fuzzers (-DSTRATA_FUZZ=ON instruments all of Strata). Runs the tests
#     matching SANITIZE_TESTS: by default the fast ones that cover the input
#     side (the error type, atomic writes and the lock, stderr capture, the
#     mesh and .vdb readers and their fuzz corpora, the scene parser, the
#     heightmap and material map loaders).
#  2. Each fuzzer for FUZZ_SECONDS (default 60; 0 skips them) on its seed
#     corpus (scripts/fuzz.sh), with libFuzzer's seed FUZZ_SEED (default 1:
#     reproducible; FUZZ_SEED=0 explores anew).
#  3. ThreadSanitizer (gcc) in build-tsan/: the world tests, with
#     tests/world/tsan.supp (TBB's and OpenVDB's own frames only, no Strata
#     frame), after a canary (tests/world/TsanCanary.cpp) whose deliberate
#     race in a Strata function must be reported under those suppressions.
# A sanitizer report fails the step; the reports stay in the build folders.
#   scripts/sanitizers.sh            (CI: .ci/run runs it after the README's test command)
#   SANITIZE_TESTS=. FUZZ_SECONDS=60 scripts/sanitizers.sh   (every test built and run, longer fuzzing)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${JOBS:-2}
fuzz_seconds=${FUZZ_SECONDS:-60}
tests=${SANITIZE_TESTS:-'^(AtomicFile|OutputLock|StderrCapture|FuzzCorpus|MeshReadErrors|MeshFile|PlyIO|GltfIO|GridIO|WriteFailure|Scene|SceneErrors|SceneTerrain|SceneMaterial|SceneLayers|SurfaceAttributes|NodeRegistry|ElevationFile|LandformAttributes)\.'}
san=$root/build-sanitize
tsan=$root/build-tsan
cxx=$(command -v clang++-15 || command -v clang++-14 || command -v clang++)
cc=$(command -v clang-15 || command -v clang-14 || command -v clang)
now() { date +%s; }

start=$(now)
echo "== ASan + UBSan build ($san)"
if [ ! -f "$san/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$san" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_FUZZ=ON \
    -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" >/dev/null
fi
if [ "$tests" = "." ]; then
  nice -n 10 cmake --build "$san" -j "$jobs" # every test
else
  nice -n 10 cmake --build "$san" --target common_tests meshing_tests scene_tests terrain_tests fuzzers -j "$jobs"
fi
echo "   built in $(($(now) - start)) s"

start=$(now)
echo "== ASan + UBSan tests matching $tests"
ASAN_OPTIONS="detect_leaks=1:${ASAN_OPTIONS:-}" LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:${LSAN_OPTIONS:-}" UBSAN_OPTIONS="print_stacktrace=1:${UBSAN_OPTIONS:-}" \
  ctest --test-dir "$san" --output-on-failure -j "$jobs" -R "$tests"
echo "   ran in $(($(now) - start)) s"

if [ "$fuzz_seconds" -gt 0 ]; then
  start=$(now)
  echo "== fuzzers, ${fuzz_seconds} s each"
  FUZZ_SEED=${FUZZ_SEED:-1} STRATA_FUZZ_BUILD="$san" JOBS="$jobs" sh "$root/scripts/fuzz.sh" "$fuzz_seconds"
  echo "   fuzzed in $(($(now) - start)) s"
fi

start=$(now)
echo "== ThreadSanitizer build ($tsan)"
if [ ! -f "$tsan/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$tsan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_TSAN=ON -DSTRATA_BUILD_APPS=OFF >/dev/null
fi
nice -n 10 cmake --build "$tsan" --target world_tests tsan_canary -j "$jobs"
echo "   built in $(($(now) - start)) s"
echo "== ThreadSanitizer canary: deliberate races must be reported"
for kind in thread tbb; do
  canary=$tsan/tsan_canary_$kind.log
  if TSAN_OPTIONS="suppressions=$root/tests/world/tsan.supp halt_on_error=1" "$tsan/tests/world/tsan_canary" $kind >"$canary" 2>&1 ||
     ! grep -q "strata::world::canary" "$canary"; then
    echo "the canary's race ($kind) was not reported (is TSan active? does tests/world/tsan.supp hide Strata frames?):"
    cat "$canary"
    exit 1
  fi
  echo "   $kind: reported, as it must be"
done
start=$(now)
echo "== ThreadSanitizer: world tests"
TSAN_OPTIONS="suppressions=$root/tests/world/tsan.supp halt_on_error=1 ${TSAN_OPTIONS:-}" "$tsan/tests/world/world_tests"
echo "   ran in $(($(now) - start)) s"
