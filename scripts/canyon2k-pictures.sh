#!/usr/bin/env bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The pictures of examples/worlds/canyon2k.toml in the README and
# docs/geology.md: from the canyon floor at 1.7 m eye height (a 400 m crop at
# 1 m voxels; the floor at (-680, -336) is at 16.05 m) and the whole plateau from the
# scene's orbit camera at 4 m voxels, and a closer view at 0.25 m. CPU renderer. About 4 minutes here.
# Usage: scripts/canyon2k-pictures.sh [STRATA] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
strata=${1:-build/apps/strata/strata}
out=${2:-docs}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The crop: the same scene over a smaller region; texture paths made absolute.
sed -e 's/^min = \[-1024.0, -20.0, -1024.0\]/min = [-900.0, -20.0, -520.0]/' \
    -e 's/^max = \[1024.0, 200.0, 1024.0\]/max = [-500.0, 200.0, -120.0]/' \
    -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" examples/worlds/canyon2k.toml > "$work/crop.toml"
grep -q '^min = \[-900.0' "$work/crop.toml" # the region lines were found

"$strata" generate "$work/crop.toml" -o "$work/ground" --backend cpu --size 1280x720 --fov 70 \
  --camera-position=-680,17.75,-336 --camera-target=-800,32,-330
cp "$work/ground/snapshot.png" "$out/canyon2k-ground.png"

# Closer, at 0.25 m voxels: a 240 m × 220 m crop about the same floor,
# looking up at a butte's overhanging ledges (17.5 M active voxels, about
# 2 minutes and 5.7 GB here).
sed -e 's/^min = \[-1024.0, -20.0, -1024.0\]/min = [-840.0, -20.0, -520.0]/' \
    -e 's/^max = \[1024.0, 200.0, 1024.0\]/max = [-600.0, 200.0, -300.0]/' \
    -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" examples/worlds/canyon2k.toml > "$work/close.toml"
grep -q '^min = \[-840.0' "$work/close.toml"
"$strata" generate "$work/close.toml" -o "$work/close" --quality voxel_size=0.25 --backend cpu --size 1280x720 \
  --fov 70 --camera-position=-680,17.75,-336 --camera-target=-700,70,-460
cp "$work/close/snapshot.png" "$out/canyon2k-ground-025.png"
"$strata" generate examples/worlds/canyon2k.toml -o "$work/above" --quality voxel_size=4 --backend cpu --size 1280x720
cp "$work/above/snapshot.png" "$out/canyon2k-above.png"
