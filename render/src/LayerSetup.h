// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: a layered Material as the shared header's LayerSetParams for one
// mesh origin (shaders/TerrainLayers.h), shared by the GL and the CPU
// renderer; and LayerSetBlock, its std140 mirror for the GL uniform block.

#include "UniformBlocks.h"

#include <strata/render/Material.h>

#include <glm/vec3.hpp>

#include <cstddef>

namespace strata::render::detail {

static_assert(sizeof(shading::LayerParams) == 256, "LayerParams must match its std140 layout");
static_assert(offsetof(shading::LayerParams, altitude) == 0);
static_assert(offsetof(shading::LayerParams, cover) == 48);
static_assert(offsetof(shading::LayerParams, flow) == 64);
static_assert(offsetof(shading::LayerParams, water) == 112);
static_assert(offsetof(shading::LayerParams, hardness) == 128);
static_assert(offsetof(shading::LayerParams, bed) == 144);
static_assert(offsetof(shading::LayerParams, noise) == 160);
static_assert(offsetof(shading::LayerParams, detailOffset) == 208);
static_assert(offsetof(shading::LayerParams, tileOffset) == 224);
static_assert(offsetof(shading::LayerParams, mapScale) == 240);
static_assert(offsetof(shading::LayerParams, features) == 248);
static_assert(offsetof(shading::LayerParams, seed) == 252);

/// Texture space for a mesh at `origin` (TerrainFrame.glsl's FrameBlock
/// and each layer): the origin's whole texture repeats are dropped in
/// double precision, leaving the fraction (textureOffset), its share of
/// the detail maps' repeats (detailOffset) and the dropped repeats modulo
/// 256 for the anti-tiling lattice (tileOffset).
struct TextureRebase
{
    glm::vec3 textureOffset;
    glm::vec3 detailOffset;
    glm::vec3 tileOffset;
};
TextureRebase rebaseTextures(float mapScale, float detailScale, const glm::dvec3& origin);

/// Binding point of the layer block in layered terrain programs.
inline constexpr unsigned LAYER_BLOCK_BINDING = 5;

/// LayerBlock { LayerSetParams uLayerSet; } (TerrainLayers.h): the C++
/// MaterialParams is 76 bytes, its std140 form (MaterialBlock) 80.
struct LayerSetBlock
{
    shading::LayerParams layers[STRATA_MAX_LAYERS]; // 0, stride 256
    MaterialBlock materials[STRATA_MAX_LAYERS];     // 2048, stride 80
    std::int32_t count;                             // 2688
    float blendDepth;                               // 2692
    float padding0;
    float padding1;
};
static_assert(offsetof(LayerSetBlock, materials) == 2048);
static_assert(offsetof(LayerSetBlock, count) == 2688);
static_assert(offsetof(LayerSetBlock, blendDepth) == 2692);
static_assert(sizeof(LayerSetBlock) == 2704);

/// The placement part of a layer's parameters (bands, opacity, noise mask)
/// for a mesh at `origin`; layer 0 (`rule` null) covers everything.
/// Texture fields are left zero.
shading::LayerParams ruleParams(const LayerRule* rule, const glm::dvec3& origin);

/// The layers of `material` (layer 0 its base) for a mesh at `origin`:
/// altitudes, texture and noise offsets relative to it (in double), each
/// layer's feature set with the bits outside `mask` off. Unbounded band
/// sides become ±1e30. The material must have passed checkMaterial().
shading::LayerSetParams makeLayerSet(const Material& material, const glm::dvec3& origin, std::uint32_t mask);

LayerSetBlock toBlock(const shading::LayerSetParams& p);

} // namespace strata::render::detail
