// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The default scene's density tree built by hand with the scene's values
// (apps/strata/default_scene.toml): fBm hills, optionally terraced, warped
// sideways, minus worm tunnels. Shared by the terrain tests and benchmark.

#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/Transforms.h>

#include <memory>
#include <vector>

namespace strata::test {

inline terrain::DensityFieldPtr defaultSceneTree(bool terraces)
{
    using namespace strata::terrain;
    DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(1, NoiseHeightfieldOptions{});
    if (terraces) hills = std::make_shared<TerraceField>(hills, 7.0, 4.0);
    WarpOptions warp;
    warp.amplitude = 4.0;
    warp.wavelength = 20.0;
    warp.vertical = 0.0;
    warp.noise.octaves = 1;
    WormOptions worms;
    worms.wormsPerCell = 3.0;
    worms.minY = -24.0;
    worms.maxY = 8.0;
    worms.radius = 3.2;
    return std::make_shared<CsgField>(
        CsgOperation::SUBTRACT,
        std::vector<DensityFieldPtr>{std::make_shared<WarpField>(hills, 2, warp), std::make_shared<WormCaves>(3, worms)});
}

} // namespace strata::test
