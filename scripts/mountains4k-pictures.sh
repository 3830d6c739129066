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
