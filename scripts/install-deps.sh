#!/usr/bin/env bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Installs the Debian 12 packages Strata needs to build, test and run.
# Idempotent: apt-get runs only when something is missing.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build ccache pkg-config
  libopenvdb-dev libboost-iostreams-dev libtbb-dev
  libopenmesh-dev libglm-dev libhwy-dev libmeshoptimizer-dev libtinygltf-dev
  libopenimageio-dev openimageio-tools libpng-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev libglfw3-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libfmt-dev
  libgtest-dev libbenchmark-dev libssl-dev
  libcpp-httplib-dev
  libgdal-dev
  clang libclang-rt-dev llvm
  slurm-wlm munge python3 python3-yaml
  iproute2 qemu-user
  python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest blender
  python-matplotlib-data
  xvfb xauth
  chromium
  reuse
)
# python3-dev, python3-pybind11, pybind11-dev: build `import strata` (python/);
# python3-numpy and python3-pytest run its tests; blender (Debian's, on the
# system Python) runs the add-on's headless test (python/blender).
# libcpp-httplib-dev: cpp-httplib, the HTTP server under `strata serve`
# (serve/; Debian builds it as libcpp-httplib.so with zlib and brotli).
# chromium: Debian's headless browser, driven by puppeteer-core (web/package-lock.json),
# draws the bake's web viewer on software WebGL in tests/web (WebViewer.*).
# libgdal-dev: GDAL reads digital elevation models (GeoTIFF and other rasters)
# for the dem_heightfield node (scene/src/DemFile.cpp).
# iproute2 (network namespaces) and qemu-user: the cluster tests, whose ARM
# node runs the aarch64 build (tests/apps/slurm_cluster_test.sh;
# scripts/determinism-builds.sh aarch64 installs the cross compiler).
# reuse runs `reuse lint` (ctest's ReuseLint): every file states its licence.
# python-matplotlib-data ships a real DEM (sample_data/jacksboro_fault_dem.npz)
# that tests/apps/BenchLandformsCommandTest.cpp measures (docs/landform-statistics.md).
# clang with its sanitizer and libFuzzer runtimes (libclang-rt-dev) and
# llvm-symbolizer (llvm) build and run scripts/sanitizers.sh, which CI runs.
# Node.js and npm run the Khronos glTF validator and 3D Tiles client tests
# (`npm ci` installs the versions tests/npm/package-lock.json pins into the
# build tree). A machine may already have them from
# another source (e.g. a nodejs package that bundles npm, where Debian's npm
# package would conflict): only ask Debian when the commands are missing.
if ! command -v node >/dev/null 2>&1; then PACKAGES+=(nodejs); fi
if ! command -v npm >/dev/null 2>&1; then PACKAGES+=(npm); fi

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$'; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
