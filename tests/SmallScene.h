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

} // namespace strata::test
