#pragma once
// Internal: a layered Material as the shared header's LayerSetParams for one
// mesh origin (shaders/TerrainLayers.h), shared by the GL and the CPU
// renderer; and LayerSetBlock, its std140 mirror for the GL uniform block.

#include "UniformBlocks.h"

#include <strata/render/Material.h>

#include <glm/vec3.hpp>

#include <cstddef>

namespace strata::render::detail {

static_assert(sizeof(shading::LayerParams) == 144, "LayerParams must match its std140 layout");
static_assert(offsetof(shading::LayerParams, altitude) == 0);
static_assert(offsetof(shading::LayerParams, noise) == 64);
static_assert(offsetof(shading::LayerParams, detailOffset) == 112);
static_assert(offsetof(shading::LayerParams, mapScale) == 128);
static_assert(offsetof(shading::LayerParams, features) == 136);
static_assert(offsetof(shading::LayerParams, seed) == 140);

/// Binding point of the layer block in layered terrain programs.
inline constexpr unsigned LAYER_BLOCK_BINDING = 5;

/// LayerBlock { LayerSetParams uLayerSet; } (TerrainLayers.h): the C++
/// MaterialParams is 76 bytes, its std140 form (MaterialBlock) 80.
struct LayerSetBlock
{
    shading::LayerParams layers[STRATA_MAX_LAYERS]; // 0, stride 144
    MaterialBlock materials[STRATA_MAX_LAYERS];     // 1152, stride 80
    std::int32_t count;                             // 1792
    float blendDepth;                               // 1796
    float padding0;
    float padding1;
};
static_assert(offsetof(LayerSetBlock, materials) == 1152);
static_assert(offsetof(LayerSetBlock, count) == 1792);
static_assert(offsetof(LayerSetBlock, blendDepth) == 1796);
static_assert(sizeof(LayerSetBlock) == 1808);

/// The layers of `material` (layer 0 its base) for a mesh at `origin`:
/// altitudes, texture and noise offsets relative to it (in double), each
/// layer's feature set with the bits outside `mask` off. Unbounded band
/// sides become ±1e30. The material must have passed checkMaterial().
shading::LayerSetParams makeLayerSet(const Material& material, const glm::dvec3& origin, std::uint32_t mask);

LayerSetBlock toBlock(const shading::LayerSetParams& p);

} // namespace strata::render::detail
