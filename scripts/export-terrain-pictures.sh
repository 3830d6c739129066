#!/usr/bin/env bash
# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# The pictures of docs/export-terrain.md and the README: examples/worlds/
# mountains4k.toml exported for Godot (one sample per 4 m, no meshes), its
# 16 × 16 heightmap tiles and splat maps joined into one picture each with
# oiiotool (each tile's last row and column dropped: they repeat the
# neighbour's first), the splat weights shown as each layer's colour.
#   scripts/export-terrain-pictures.sh [STRATA] [OUT_DIR] [EXPORT_DIR]
# EXPORT_DIR: an export made before with the flags below (skips the export,
# about 6 CPU-minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
strata=${1:-build/apps/strata/strata}
out=${2:-docs}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

export=${3:-$work/export}
if [[ -z ${3:-} ]]; then
  "$strata" export-terrain examples/worlds/mountains4k.toml -o "$export" --engine godot --resolution 65 --no-meshes
fi

# One picture from every tile's FILE (a suffix after NAME), rows along z.
# NAMES renames the channels: no channel is alpha (no premultiplication).
mosaic() {
  local suffix=$1 target=$2 names=$3 args=()
  for z in $(seq 0 15); do
    for x in $(seq 0 15); do
      args+=("$export/${suffix/NAME/${x}_${z}}" --cut 64x64+0+0)
    done
  done
  oiiotool --no-autopremult "${args[@]}" --mosaic 16x16 --chnames "$names" -o "$target"
}
mosaic heightmaps/NAME.exr "$work/height.exr" Y
mosaic splat/NAME_0.png "$work/splat0.exr" w0,w1,w2,w3
mosaic splat/NAME_1.png "$work/splat1.exr" w4,w5,w6,w7

# Heights 0..800 m as grey.
oiiotool "$work/height.exr" --subc 0 --divc 800 --clamp:min=0:max=1 -d uint8 \
  -o "$out/export-terrain-height.png"
# Layers: base rock, sediment, grass, gullies | riverbed, snow.
oiiotool "$work/splat0.exr" "$work/splat1.exr" --chappend --ch w0,w1,w2,w3,w4,w5 -o "$work/weights.exr"
channel() {
  oiiotool "$work/weights.exr" --chsum:weight="$1" -o "$work/$2.exr"
}
channel 0.45,0.80,0.35,0.60,0.20,0.97 r
channel 0.42,0.70,0.55,0.52,0.45,0.97 g
channel 0.40,0.48,0.25,0.45,0.75,1.00 b
oiiotool "$work/r.exr" "$work/g.exr" --chappend "$work/b.exr" --chappend --chnames R,G,B -d uint8 \
  -o "$out/export-terrain-splat.png"
