#!/bin/sh

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Builds the fuzzers (clang, libFuzzer, ASan + UBSan; -DSTRATA_FUZZ=ON) in
# build-sanitize/ and runs each for SECONDS (default 60) on a copy of its
# seed corpus in fuzz/corpus/<name>/. New crash inputs land in
# build-sanitize/crashes/<name>/; add a fixed one to fuzz/corpus/<name>/ so
# the tests (FuzzCorpus.*) replay it. Sanitizer reports go to
# build-sanitize/fuzz_<name>.sanitizer.* (the image readers capture stderr
# while OpenImageIO runs, so a report printed there would be lost).
# FUZZ_SEED fixes libFuzzer's seed (scripts/sanitizers.sh, for CI, uses 1:
# the same inputs on every run of the same code, so a CI run replays what
# was checked before it landed); unset, each run explores anew.
#   scripts/fuzz.sh [SECONDS] [NAME ...]     NAME: glb ply obj stl off scene vdb heightmap elevation
set -eu
seconds=${1:-60}
[ $# -gt 0 ] && shift
names=${*:-glb ply obj stl off scene vdb heightmap elevation}
root=$(cd "$(dirname "$0")/.." && pwd)
build=${STRATA_FUZZ_BUILD:-$root/build-sanitize}
sh "$root/scripts/configure-sanitize.sh" "$build"
nice -n 10 cmake --build "$build" --target fuzzers -j "${JOBS:-2}"
status=0
for name in $names; do
  work="$build/corpus/$name"
  crashes="$build/crashes/$name"
  mkdir -p "$work" "$crashes" "$build/fuzz-cwd"
  cp "$root/fuzz/corpus/$name/"* "$work/"
  case $name in
    vdb) max_len=16384 ;;
    *) max_len=4096 ;;
  esac
  log="$build/fuzz_$name.log"
  rm -f "$build/fuzz_$name.sanitizer".*
  echo "== fuzz_$name for ${seconds}s"
  # In an empty folder: file names in fuzzed scenes resolve there.
  if ! (cd "$build/fuzz-cwd" &&
        ASAN_OPTIONS="log_path=$build/fuzz_$name.sanitizer:${ASAN_OPTIONS:-}" \
        LSAN_OPTIONS="suppressions=$root/fuzz/lsan.supp:${LSAN_OPTIONS:-}" \
        UBSAN_OPTIONS="log_path=$build/fuzz_$name.sanitizer:print_stacktrace=1:${UBSAN_OPTIONS:-}" \
        "$build/fuzz/fuzz_$name" "$work" -max_total_time="$seconds" -max_len=$max_len -rss_limit_mb=2048 \
          -malloc_limit_mb=1024 -timeout=10 -seed="${FUZZ_SEED:-0}" -artifact_prefix="$crashes/" -print_final_stats=1 2>"$log"); then
    echo "fuzz_$name FOUND A PROBLEM: see $log, $build/fuzz_$name.sanitizer.* and $crashes/"
    cat "$build/fuzz_$name.sanitizer".* 2>/dev/null | head -40 || true
    status=1
  fi
  grep -E "stat::number_of_executed_units|stat::average_exec_per_sec|stat::peak_rss_mb" "$log" || true
done
exit $status
