#!/bin/sh

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The golden table (tests/scene/DeterminismGoldenTest.cpp, docs/determinism.md)
# in builds other than the README's: each builds only the libraries and
# determinism_tests, then runs it. The table was recorded with gcc 12
# Release on x86-64; a build that parts from it fails naming the crop and
# the stage.
#   scripts/determinism-builds.sh                 (all three below)
#   scripts/determinism-builds.sh O0 aarch64      (some of them)
# Builds (each in its own folder):
#   clang    build-clang/    clang Release (-O3)
#   O0       build-O0/       gcc at -O0, assertions on, no debug information
#   aarch64  build-aarch64/  g++-aarch64-linux-gnu Release (-O3) against
#            arm64 Debian packages unpacked into build-aarch64/sysroot by
#            mmdebstrap (about 1 GB, 80 s here), run under qemu-user with
#            the sysroot's own loader and libraries
#            (cmake/toolchain-aarch64-linux-gnu.cmake). Installs qemu-user,
#            g++-aarch64-linux-gnu and mmdebstrap when missing (root).
# No programs, Python module, web viewer or GDAL (DEMs) in these builds: the
# table needs none of them (and the arm64 sysroot holds no GDAL); but the
# aarch64 build makes strata too, for the cluster tests' ARM node
# (tests/apps/slurm_cluster_test.sh, ctest -L cluster).
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
jobs=${JOBS:-2}
builds=${*:-clang O0 aarch64}
now() { date +%s; }
common="-G Ninja -DSTRATA_BUILD_APPS=OFF -DSTRATA_BUILD_PYTHON=OFF -DSTRATA_BUILD_WEB_VIEWER=OFF -DSTRATA_WITH_GDAL=OFF"

# The arm64 packages the libraries and the test link against.
ARM64_PACKAGES=libopenvdb-dev,libtbb-dev,libhwy-dev,libglm-dev,zlib1g-dev,libssl-dev,libopenmesh-dev,\
libtinygltf-dev,libmeshoptimizer-dev,libpng-dev,libopenimageio-dev,openimageio-tools,libegl-dev,libgl-dev,\
libepoxy-dev,libglfw3-dev,libtomlplusplus-dev,nlohmann-json3-dev,libgtest-dev,libbenchmark-dev,\
libboost-iostreams-dev,libcpp-httplib-dev,libcli11-dev,libstdc++-12-dev,libc6-dev

arm64_sysroot() {
  sysroot=$1
  missing=""
  for p in qemu-aarch64:qemu-user aarch64-linux-gnu-g++:g++-aarch64-linux-gnu mmdebstrap:mmdebstrap; do
    command -v "${p%%:*}" >/dev/null || missing="$missing ${p#*:}"
  done
  if [ -n "$missing" ]; then
    echo "   installing$missing"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -q $missing >/dev/null
  fi
  if [ ! -f "$sysroot/.complete" ]; then
    echo "   unpacking arm64 packages into $sysroot"
    rm -rf "$sysroot"
    mkdir -p "$sysroot" # mmdebstrap resolves the target's absolute path: its parent must exist
    sources=/etc/apt/sources.list.d/debian.sources
    [ -f "$sources" ] || sources=/etc/apt/sources.list
    mmdebstrap --quiet --variant=extract --arch=arm64 --include="$ARM64_PACKAGES" bookworm "$sysroot" "$sources"
    # Extracting runs no maintainer scripts, so the alternatives that name
    # BLAS and LAPACK (which OpenCV, under OpenImageIO, links) are missing.
    lib=$sysroot/usr/lib/aarch64-linux-gnu
    for d in blas lapack; do
      for f in "$lib/$d"/lib*.so*; do
        [ -e "$lib/${f##*/}" ] || ln -s "$d/${f##*/}" "$lib/${f##*/}"
      done
    done
    touch "$sysroot/.complete"
  fi
}

status=0
for b in $builds; do
  start=$(now)
  case $b in
  clang)
    dir=$root/build-clang
    [ -f "$dir/CMakeCache.txt" ] || cmake -S "$root" -B "$dir" $common -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_COMPILER="$(command -v clang++-15 || command -v clang++-14 || command -v clang++)" >/dev/null
    ;;
  O0)
    dir=$root/build-O0
    [ -f "$dir/CMakeCache.txt" ] || cmake -S "$root" -B "$dir" $common -DCMAKE_BUILD_TYPE=Debug \
      -DCMAKE_CXX_FLAGS_DEBUG=-O0 >/dev/null
    ;;
  aarch64)
    dir=$root/build-aarch64
    sysroot=${STRATA_ARM64_SYSROOT:-$dir/sysroot}
    arm64_sysroot "$sysroot"
    [ -f "$dir/CMakeCache.txt" ] || STRATA_ARM64_SYSROOT="$sysroot" cmake -S "$root" -B "$dir" $common \
      -DCMAKE_BUILD_TYPE=Release -DSTRATA_ARM64_SYSROOT="$sysroot" -DSTRATA_BUILD_APPS=ON \
      -DCMAKE_TOOLCHAIN_FILE="$root/cmake/toolchain-aarch64-linux-gnu.cmake" >/dev/null
    ;;
  *)
    echo "determinism-builds.sh: unknown build '$b' (clang, O0, aarch64)" >&2
    exit 2
    ;;
  esac
  echo "== $b ($dir)"
  # The aarch64 build's strata also runs on the cluster tests' ARM node.
  targets=determinism_tests
  [ "$b" = aarch64 ] && targets="determinism_tests strata"
  nice -n 10 cmake --build "$dir" -j "$jobs" --target $targets
  echo "   built in $(($(now) - start)) s"
  start=$(now)
  if ! ctest --test-dir "$dir" --output-on-failure -j "$jobs" -L '^determinism_tests$'; then
    echo "   $b: the golden table parts (above: the crop and the stage)"
    status=1
  fi
  echo "   ran in $(($(now) - start)) s"
done
exit $status
