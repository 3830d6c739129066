// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// A small scene shared by the pipeline and CLI tests: hills minus worm
// tunnels over a 24 m region at 0.5 m voxels (some tunnels open to the
// surface).

namespace strata::test {

inline constexpr const char* SMALL_SCENE = R"(
seed = 7
[terrain]
root = "world"
[terrain.nodes.world]
type = "subtract"
children = ["land", "tunnels"]
[terrain.nodes.land]
type = "heightfield"
amplitude = 12.0
wavelength = 30.0
[terrain.nodes.tunnels]
type = "worms"
cell_size = 16.0
min_y = -6.0
max_y = 0.0
radius = 2.0
[region]
min = [-12.0, -10.0, -12.0]
max = [12.0, 10.0, 12.0]
[sampling]
voxel_size = 0.5
)";

/// Hills minus worm tunnels over 40 × 20 × 40 m at 0.5 m, for the bake
/// tests: with 16 m tiles, 3 × 3 columns (the last 8 m wide) of two slabs
/// (16 m and 4 m).
inline constexpr const char* BAKE_CAVE_SCENE = R"(
seed = 11
[terrain]
root = "world"
[terrain.nodes.world]
type = "subtract"
children = ["land", "tunnels"]
[terrain.nodes.land]
type = "heightfield"
amplitude = 10.0
wavelength = 25.0
[terrain.nodes.tunnels]
type = "worms"
cell_size = 16.0
min_y = -8.0
max_y = 2.0
radius = 2.0
[region]
min = [-20.0, -12.0, -20.0]
max = [20.0, 8.0, 20.0]
[sampling]
voxel_size = 0.5
)";

} // namespace strata::test
