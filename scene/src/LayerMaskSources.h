// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the mask sources a scene's layer rules read, for the stages
// that compute the masks away from meshTerrain() (the bake's tiles, the
// terrain export's splat maps).

#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>

#include <cstdint>
#include <memory>
#include <optional>

namespace strata::scene::detail {

/// The landform source (flow, wear, deposition, water) and the rock source
/// (hardness, bed) for `seed` when a layer rule reads them, else null.
/// Throws as needsLandform() and needsRock() do when a rule reads a source
/// the terrain lacks.
struct LayerMaskSources
{
    std::shared_ptr<const terrain::LandformMasks> landform;
    std::shared_ptr<const terrain::RockMasks> rock;
};

inline LayerMaskSources layerMaskSources(const Scene& scene, std::optional<std::uint64_t> seed)
{
    return {needsLandform(scene) ? landformMasksForSeed(scene, seed) : nullptr,
            needsRock(scene) ? rockMasksForSeed(scene, seed) : nullptr};
}

} // namespace strata::scene::detail
