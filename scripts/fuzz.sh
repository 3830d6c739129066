#!/bin/sh
# Builds the mesh-reader fuzzers (clang, libFuzzer, ASan + UBSan) in
# build-fuzz/ and runs each for SECONDS (default 60) on a copy of its seed
# corpus in fuzz/corpus/<format>/. New crash inputs land in
# build-fuzz/crashes/<format>/; add a fixed one to fuzz/corpus/<format>/ so
# the meshing tests replay it.
#   scripts/fuzz.sh [SECONDS]
set -eu
seconds=${1:-60}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${STRATA_FUZZ_BUILD:-$root/build-fuzz}
cxx=${CXX_FUZZ:-$(command -v clang++-15 || command -v clang++)}
cc=${CC_FUZZ:-$(command -v clang-15 || command -v clang)}
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSTRATA_FUZZ=ON \
  -DSTRATA_BUILD_TESTS=OFF -DSTRATA_BUILD_APPS=OFF -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_C_COMPILER="$cc" >/dev/null
nice -n 10 cmake --build "$build" --target fuzzers -j "${JOBS:-2}"
status=0
for format in glb ply obj stl off; do
  work="$build/corpus/$format"
  crashes="$build/crashes/$format"
  mkdir -p "$work" "$crashes"
  cp "$root/fuzz/corpus/$format/"* "$work/"
  echo "== fuzz_$format for ${seconds}s"
  if ! "$build/fuzz/fuzz_$format" "$work" -max_total_time="$seconds" -max_len=4096 -rss_limit_mb=2048 \
      -malloc_limit_mb=512 -timeout=10 -artifact_prefix="$crashes/" -print_final_stats=1 2>"$build/fuzz_$format.log"; then
    echo "fuzz_$format FOUND A PROBLEM: see $build/fuzz_$format.log and $crashes/"
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$build/fuzz_$format.log" || true
done
exit $status
