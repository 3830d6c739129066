#!/bin/sh

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Sanitizers and fuzzers, bounded in time (CI runs this after the README's
# test command, on 2 cores; docs/testing.md has the coverage and the times):
#  1. ASan + UBSan (clang) in build-sanitize/: the libraries' test executables
#     (ASAN_SUITES below), without the strata program (-DSTRATA_BUILD_APPS=OFF:
#     it only parses flags around the library calls tested here; the tests
#     that run it begin with STRATA_REQUIRE_PROGRAM() and skip), then their
#     tests except ASAN_SLOW, each excluded for the reason given there. LeakSanitizer is on, with fuzz/lsan.supp (exact
#     OpenVDB functions, never a whole library). -DSTRATA_FUZZ=ON instruments
#     all of Strata, so the same build makes the fuzzers.
#  2. Each fuzzer for FUZZ_SECONDS (default 5 in CI; 0 skips them) on its
#     seed corpus (scripts/fuzz.sh), with libFuzzer's seed FUZZ_SEED (default
#     1: reproducible; FUZZ_SEED=0 explores anew). Longer runs are by hand and
#     documented in docs/testing.md ("Longer fuzzing"), e.g.
#       FUZZ_SECONDS=600 FUZZ_SEED=0 scripts/sanitizers.sh
#       scripts/fuzz.sh 3600 vdb
#  3. ThreadSanitizer (gcc) in build-tsan/ over every test of world_tests
#     (the World's workers, edits and queries, and its TBB sampling) and of
#     tile_workers_tests (the bake's and the terrain export's tile pool on
#     TBB: tiles at once, progress, the interrupt, failures, a tile's
#     parallel_for inside the pool's arena; one file to build; run with
#     ignore_noninstrumented_modules=1: at exit of the pool's entry thread,
#     libtbb's own teardown (delete[] against a worker's memcmp, both called
#     from libtbb, no Strata frame) is reported otherwise, an edge inside
#     the uninstrumented library), after
#     a canary (tests/world/TsanCanary.cpp) whose deliberate races in Strata
#     functions must be reported under tests/world/tsan.supp.
#     NOT YET under TSan: terrain_tests (sampling, erosion), scene_tests (the
#     pipeline, the bake's tiles and its CLI), meshing and the CPU
#     renderer. Run over them (TSAN_SUITES below, issue 30), TSan reported
#     69 races in 68 of their 255 tests, every one at a tbb::parallel_for's
#     fork or join: a write before the parallel_for against a read in its
#     body, or a body's write against a read after it returns. libtbb is not
#     built with TSan, so the happens-before edges its scheduler provides
#     are invisible; the World declares them itself (common/include/strata/detail/TsanHandOver.h)
#     and is clean. Until the other libraries declare them too (the same
#     annotations around their ~30 parallel_for calls, or an ITT-to-TSan
#     bridge: TBB_USE_PROFILING_TOOLS=2 makes TBB's headers report spawn,
#     join and wait to r1::call_itt_notify), those suites would only report
#     TBB's invisible edges. The bake's tests (Bake.*, issue 26) report the
#     same kind only: sampleLevelSet's parallel_for fork (a vector written
#     before it, read in its body), OpenVDB's own parallel prune
#     (TolerancePruneOp) reading the leaves sampleLevelSet added, the CPU
#     renderer's procedural textures (makeBuiltinSet's join) and
#     OpenImageIO's own threads (readHeightImageFile). The helper is now in
#     common/, where terrain and render can include it; what is left is
#     annotating their parallel_for sites and suppressions naming OpenVDB's
#     and OpenImageIO's functions. By hand:
#       TSAN_SUITES='world_tests|terrain_tests|scene_tests' scripts/sanitizers.sh
# A sanitizer report fails the step; the reports stay in the build folders
# (build-*/Testing/Temporary/LastTest.log).
#   scripts/sanitizers.sh                          (CI: .ci/run runs it)
#   SANITIZE_TESTS=REGEX scripts/sanitizers.sh     (only the ASan tests matching REGEX)
#   JOBS=4 FUZZ_SECONDS=0 scripts/sanitizers.sh    (more cores, no fuzzing)
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${JOBS:-2}
fuzz_seconds=${FUZZ_SECONDS:-5}
tests=${SANITIZE_TESTS:-.}
san=$root/build-sanitize
tsan=$root/build-tsan
now() { date +%s; }
begin=$(now)

# The GoogleTest executables (ctest labels, tests/CMakeLists.txt) run under
# ASan + UBSan: the libraries', where all of Strata's code lives (apps/ only
# parses flags and prints). Not here, each for a reason:
#  - app_tests, viewer_tests (the CLI and strata-view): flag parsing and
#    printing around the library calls run here; their hostile flags and
#    files run in CI's main run, the files' readers under the fuzzers too.
#  - InstalledPackage.*, Slurm.*, Python.*, GltfValidator.*, TilesClient.*,
#    WebViewer.*, ReadmeFigures.MatchWhatTheCodeMeasures (no label): an
#    uninstrumented compiler, python3, Blender, node, Chromium or ctest does
#    the work; CI's main run has them. (The README's sampling figures are
#    checked here: determinism_tests' ReadmeFigures.*.)
#  - render_tests (issue 39 made room in CI's hour for the aarch64 golden
#    table): the renderers' tests are Mesa's and the CPU renderer's work over
#    whole images (232 tests, 156 CPU-s under ASan, plus about 5 CPU-minutes
#    to build them instrumented); the render library itself still runs
#    instrumented under scene_tests (snapshots, bake previews, the terrain
#    export's images) and the image readers under fuzz_heightmap.
#  - meshing_tests (the same reason): 420 CPU-s to build instrumented (its
#    VDB file test alone 135 s), 57 CPU-s to run. Its readers run under
#    ASan in six fuzzers (vdb, ply, obj, stl, off, glb), its meshers
#    instrumented under world_tests, scene_tests and determinism_tests.
#    By hand: ASAN_SUITES='...|render_tests|meshing_tests' scripts/sanitizers.sh
ASAN_SUITES=${ASAN_SUITES:-'common_tests|terrain_tests|world_tests|scene_tests|tile_workers_tests|serve_tests|determinism_tests'}
# Tests of those suites that run in CI's main run only (23 of them; the
# shader variants, the CPU renderer's combinations, TerrainLayers,
# MaterialShading and the meshers' goldens are render_tests' and
# meshing_tests', named for a run that adds those suites): each takes 2 s or
# more in Release (3 to 6 times that under ASan) and repeats, on a whole
# scene or bake, code that the suite's smaller tests run here:
#  - every shader variant on llvmpipe (Mesa's compiler at work, not Strata;
#    the program cache's code runs in the other GlRendererCache tests), and
#    GL/CPU parity over every feature combination or the default scene;
#  - bakes of whole worlds (one bake, TheTilesetIsValid3DTiles, and the
#    compact tile format stay), resumes, renders from tiles, georeferencing;
#  - sampling the beds, every node or every SIMD target over a region
#    (the same code runs in the small SampleLevelSet and DensityNodes tests);
#  - the chunk meshers' byte goldens over many grids (their bytes are gcc's
#    and aarch64's concern: the golden table; the meshers' own tests stay),
#    the World splitting and merging chunks along a long walk (twice), the
#    noise throughput measurement, many processes racing for one lock.
ASAN_SLOW='^Shards/GlRendererVariants\.|^GlRendererCache\.EachVariant|^CpuRenderer\.EveryFeatureCombination|^SnapshotParity\.|^TerrainLayers\.(FarFromTheOrigin|GlMatchesTheCpuWithFour)|^MaterialShading\.HeightWeightsAreAPartition|^Bake\.(Resume|EveryTile|AnotherScene|TheWorldRenders)|^BakeTileFormat\.DecodedCompactTiles|^BakeViewer\.WritesThePage|^Georeference\.TheBakesTileset|^Pipeline\.(AMapLarger|ABadMaterialMap)|^Scene(Material\.MapFiles|Layers\.FourLayers)|^SampleLevelSet\.(Beds|SameBitsOnEverySimd|Pruning)|^SampleRegions\.Renormalisation|^BlockEvaluation\.EveryNodeType|^FastNoiseLiteReference\.TheThroughput|^ChunkMeshGolden\.|^World\.NoHolesWhileChunksSplitAndMerge|^OutputLock\.ManyProcesses|^World\.DeterministicAcrossThreadCounts'
#  ThreadSanitizer: no test excluded.
# The GoogleTest executables run under ThreadSanitizer (ctest labels).
tsan_suites=${TSAN_SUITES:-world_tests}

start=$(now)
echo "== ASan + UBSan build ($san): $ASAN_SUITES"
sh "$root/scripts/configure-sanitize.sh" "$san"
nice -n 10 cmake --build "$san" -j "$jobs" --target $(echo "$ASAN_SUITES" | tr '|' ' ')
echo "   built in $(($(now) - start)) s"

start=$(now)
echo "== ASan + UBSan: $ASAN_SUITES, the tests matching '$tests', except '$ASAN_SLOW'"
ASAN_OPTIONS="detect_leaks=1:${ASAN_OPTIONS:-}" LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:${LSAN_OPTIONS:-}" UBSAN_OPTIONS="print_stacktrace=1:${UBSAN_OPTIONS:-}" \
  nice -n 10 ctest --test-dir "$san" --output-on-failure -j "$jobs" -L "^($ASAN_SUITES)\$" -R "$tests" -E "$ASAN_SLOW"
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
  # Full debug information (-g), not -g1: with -g1 gcc names inlined frames
  # without their namespaces and classes (enqueue_task, not
  # tbb::detail::d1::enqueue_task<...>::enqueue_task), so tsan.supp's
  # qualified TBB names stop matching and TBB's task recycling is reported
  # (a CI run failed so).
  cmake -S "$root" -B "$tsan" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_TSAN=ON -DSTRATA_BUILD_APPS=OFF \
    -DSTRATA_BUILD_WEB_VIEWER=OFF >/dev/null
fi
# scene_tests runs the strata executable: it needs the apps.
case "$tsan_suites" in *scene_tests*) cmake -S "$root" -B "$tsan" -DSTRATA_BUILD_APPS=ON >/dev/null ;; esac
nice -n 10 cmake --build "$tsan" --target $(echo "$tsan_suites" | tr '|' ' ') tile_workers_tests tsan_canary -j "$jobs"
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
echo "== ThreadSanitizer: every test of $tsan_suites"
# Each GoogleTest executable labels its tests with its name (tests/CMakeLists.txt).
TSAN_OPTIONS="suppressions=$root/tests/world/tsan.supp halt_on_error=1 ${TSAN_OPTIONS:-}" \
  nice -n 10 ctest --test-dir "$tsan" --output-on-failure -j "$jobs" -L "^($tsan_suites)\$"
echo "== ThreadSanitizer: the bake's tile pool (tile_workers_tests)"
TSAN_OPTIONS="suppressions=$root/tests/world/tsan.supp halt_on_error=1 ignore_noninstrumented_modules=1 ${TSAN_OPTIONS:-}" \
  nice -n 10 ctest --test-dir "$tsan" --output-on-failure -j "$jobs" -L '^tile_workers_tests$'
echo "   ran in $(($(now) - start)) s"
echo "== sanitizers and fuzzers: $(($(now) - begin)) s in all"
