#!/usr/bin/env bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The README's pictures of examples/worlds/mountains4k.toml, at 4 m voxels
# over the whole 4 km: the showcase without its caves and its 1 m erosion
# detail (both are voxel-scale features: sample them at 1 m, by baking).
# Usage: scripts/mountains4k-pictures.sh [STRATA] [OUT_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
strata=${1:-build/apps/strata/strata}
out=${2:-docs}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Root the tree at the eroded land and drop the nodes only the caves and the
# detail use (an unused node is an error). Texture paths are made absolute.
awk '
  /^\[terrain\.nodes\.(world|caves|detailed)\]/ { skip = 1; next }
  /^\[/ { skip = 0 }
  !skip' examples/worlds/mountains4k.toml |
  sed -e 's/^root = "world"/root = "rough"/' \
      -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" > "$work/preview.toml"

"$strata" generate "$work/preview.toml" -o "$work/out" --quality voxel_size=4 --no-snapshot -q
"$strata" render "$work/preview.toml" --mesh "$work/out/terrain.glb" -o "$out/mountains4k.png" --size 960x540 --backend cpu
"$strata" render "$work/preview.toml" --mesh "$work/out/terrain.glb" -o "$out/mountains4k-top.png" --size 640x640 \
  --view top --backend cpu
"$strata" render "$work/preview.toml" --mesh "$work/out/terrain.glb" -o "$out/mountains4k-flow.png" --size 640x640 \
  --view top --debug-view flow --backend cpu

# From the ground: the whole scene (caves, 1 m droplet detail, talus) on
# the 512 m crop x 704..1216, z -1472..-960 at 1 m voxels, from a valley
# floor at 1.7 m eye height (the ground at (1128, -1400) is at 81.74 m)
# looking up across the range, 300 m above it. About 25 s here.
sed -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" \
    -e 's/^min = \[-2048.0, -40.0, -2048.0\]/min = [704.0, -40.0, -1472.0]/' \
    -e 's/^max = \[2048.0, 880.0, 2048.0\]/max = [1216.0, 880.0, -960.0]/' examples/worlds/mountains4k.toml > "$work/ground.toml"
grep -q '^min = \[704.0' "$work/ground.toml" # the region lines were found
"$strata" generate "$work/ground.toml" -o "$work/ground" --backend cpu --size 1280x720 --fov 70 \
  --camera-position=1128,83.44,-1400 --camera-target=850,220,-1100 -q
cp "$work/ground/snapshot.png" "$out/mountains4k-ground.png"

# Closer, at 0.25 m voxels: a 236 m square about the same eye, looking up
# the river's bed between its rock slopes (21 M active voxels; about 3
# minutes and 7 GB here).
sed -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" \
    -e 's/^min = \[-2048.0, -40.0, -2048.0\]/min = [980.0, -40.0, -1472.0]/' \
    -e 's/^max = \[2048.0, 880.0, 2048.0\]/max = [1216.0, 880.0, -1236.0]/' examples/worlds/mountains4k.toml > "$work/close.toml"
grep -q '^min = \[980.0' "$work/close.toml"
"$strata" generate "$work/close.toml" -o "$work/close" --quality voxel_size=0.25 --backend cpu --size 1280x720 --fov 70 \
  --camera-position=1128,83.44,-1400 --camera-target=1030,115,-1420 -q
cp "$work/close/snapshot.png" "$out/mountains4k-ground-025.png"

# The crests node (docs/geology.md, "Crests"): the eroded land alone, on a
# 512 m crop at 2 m voxels, as the erode grid's spline leaves its ridges
# (rounded) and through a crests node (sharp). They keep the example's noise
# version 1 landscape, whose spur they were framed on.
for variant in rounded sharp; do
  awk '
    /^\[terrain\.nodes\.(world|caves|detailed|rough|outcrops|grain)\]/ || /^\[camera\]/ { skip = 1; next }
    /^\[/ { skip = 0 }
    !skip' examples/worlds/mountains4k.toml |
    sed -e "s|\"\\.\\./\\.\\./docs/|\"$PWD/docs/|" -e 's/^noise_version = 2 .*$/noise_version = 1/' \
        -e 's/^min = \[-2048.0, -40.0, -2048.0\]/min = [-512.0, -40.0, 0.0]/' \
        -e 's/^max = \[2048.0, 880.0, 2048.0\]/max = [0.0, 880.0, 512.0]/' > "$work/$variant.toml"
  if [[ $variant == sharp ]]; then
    sed -i 's/^root = "world"/root = "crested"/' "$work/$variant.toml"
    printf '\n[terrain.nodes.crested]\ntype = "crests"\nheight = "eroded"\nreach = 16.0\nmax_lift = 15.0\n' >> "$work/$variant.toml"
  else
    sed -i 's/^root = "world"/root = "eroded"/' "$work/$variant.toml"
  fi
  printf '\n[camera]\nposition = [-420.0, 520.0, 420.0]\ntarget = [-200.0, 330.0, 150.0]\nfov = 45.0\n' >> "$work/$variant.toml"
  "$strata" generate "$work/$variant.toml" -o "$work/$variant" --quality voxel_size=2 --no-snapshot -q
  "$strata" render "$work/$variant.toml" --mesh "$work/$variant/terrain.glb" -o "$out/crests-$variant.png" \
    --size 640x360 --backend cpu
done
