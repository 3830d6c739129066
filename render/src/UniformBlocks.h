// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: C++ mirrors of the terrain program's std140 uniform blocks
// (shaders/TerrainFrame.glsl and terrain.frag), with every offset checked
// against the std140 rules at compile time. The GL driver's own offsets are
// compared with these at run time in tests/render/GlRendererTest.cpp.
//
// std140 in brief: scalars align to 4, vec2 to 8, vec3 and vec4 to 16; a
// struct and an array element align to 16 and their size rounds up to 16;
// a float may follow a vec3 in its last 4 bytes.

#include "ShadingBridge.h"

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>

namespace strata::render::detail {

/// Binding points of the uniform blocks (layout(binding = N) in the GLSL).
inline constexpr unsigned FRAME_BLOCK_BINDING = 0;
inline constexpr unsigned MATERIAL_BLOCK_BINDING = 1;
inline constexpr unsigned LIGHTING_BLOCK_BINDING = 2;
/// Texture units 0..MATERIAL_MAP_UNITS-1 hold the material's maps (MAP_* slots).
inline constexpr unsigned MATERIAL_MAP_UNITS = 9;

/// FrameBlock (TerrainFrame.glsl): per draw.
struct FrameBlock
{
    glm::mat4 viewProjection;  // offset 0
    glm::vec4 cameraPosition;  // 64, xyz relative to the mesh origin
    glm::vec4 textureOffset;   // 80, xyz
    glm::vec4 wireColor;       // 96
    float mapScale;            // 112
    std::int32_t debugView;    // 116
    std::int32_t wireframePass; // 120
    std::int32_t explicitLod;  // 124: 1 = terrain.frag's own level of detail (textureLod), 0 = the GPU's (textureGrad)
    glm::vec4 detailOffset;    // 128, xyz
    glm::vec4 tileOffset;      // 144, xyz
};
static_assert(offsetof(FrameBlock, viewProjection) == 0);
static_assert(offsetof(FrameBlock, cameraPosition) == 64);
static_assert(offsetof(FrameBlock, textureOffset) == 80);
static_assert(offsetof(FrameBlock, wireColor) == 96);
static_assert(offsetof(FrameBlock, mapScale) == 112);
static_assert(offsetof(FrameBlock, debugView) == 116);
static_assert(offsetof(FrameBlock, wireframePass) == 120);
static_assert(offsetof(FrameBlock, detailOffset) == 128);
static_assert(offsetof(FrameBlock, tileOffset) == 144);
static_assert(sizeof(FrameBlock) == 160);

/// MaterialBlock { MaterialParams uMaterial; } (terrain.frag).
struct MaterialBlock
{
    glm::vec3 albedoTint;       // 0
    float blendOffset;          // 12 (after a vec3)
    float blendExponent;        // 16
    float heightStrength;       // 20
    float metallic;             // 24
    float smoothness;           // 28
    float occlusionStrength;    // 32
    float normalStrength;       // 36
    float detailScale;          // 40
    float detailAlbedo;         // 44
    float detailSmoothness;     // 48
    float detailNormalStrength; // 52
    float biplanar;             // 56
    float antiTilingSharpness;  // 60
    glm::vec3 emissionColor;    // 64
    float fresnelStrength;      // 76
};
static_assert(offsetof(MaterialBlock, albedoTint) == 0);
static_assert(offsetof(MaterialBlock, blendOffset) == 12);
static_assert(offsetof(MaterialBlock, blendExponent) == 16);
static_assert(offsetof(MaterialBlock, heightStrength) == 20);
static_assert(offsetof(MaterialBlock, metallic) == 24);
static_assert(offsetof(MaterialBlock, smoothness) == 28);
static_assert(offsetof(MaterialBlock, occlusionStrength) == 32);
static_assert(offsetof(MaterialBlock, normalStrength) == 36);
static_assert(offsetof(MaterialBlock, detailScale) == 40);
static_assert(offsetof(MaterialBlock, detailAlbedo) == 44);
static_assert(offsetof(MaterialBlock, detailSmoothness) == 48);
static_assert(offsetof(MaterialBlock, detailNormalStrength) == 52);
static_assert(offsetof(MaterialBlock, biplanar) == 56);
static_assert(offsetof(MaterialBlock, antiTilingSharpness) == 60);
static_assert(offsetof(MaterialBlock, emissionColor) == 64);
static_assert(offsetof(MaterialBlock, fresnelStrength) == 76);
static_assert(sizeof(MaterialBlock) == 80); // a struct's size rounds up to 16

/// One DirectionalLight of LightingParams: a struct, so 16-aligned, size 32.
struct LightBlock
{
    glm::vec3 direction; // 0
    float padding0;      // 12
    glm::vec3 color;     // 16
    float padding1;      // 28
};
static_assert(offsetof(LightBlock, direction) == 0);
static_assert(offsetof(LightBlock, color) == 16);
static_assert(sizeof(LightBlock) == 32);

/// LightingBlock { LightingParams uLighting; } (terrain.frag).
struct LightingBlock
{
    LightBlock lights[STRATA_MAX_LIGHTS]; // 0, stride 32
    std::int32_t lightCount;              // 128
    std::int32_t padding0[3];             // 132: the vec3 below aligns to 16
    glm::vec3 skyAmbient;                 // 144
    float padding1;                       // 156
    glm::vec3 groundAmbient;              // 160
    float exposure;                       // 172 (after a vec3)
};
static_assert(STRATA_MAX_LIGHTS == 4);
static_assert(offsetof(LightingBlock, lights) == 0);
static_assert(offsetof(LightingBlock, lightCount) == 128);
static_assert(offsetof(LightingBlock, skyAmbient) == 144);
static_assert(offsetof(LightingBlock, groundAmbient) == 160);
static_assert(offsetof(LightingBlock, exposure) == 172);
static_assert(sizeof(LightingBlock) == 176);

inline MaterialBlock toBlock(const shading::MaterialParams& p)
{
    MaterialBlock b{};
    b.albedoTint = p.albedoTint;
    b.blendOffset = p.blendOffset;
    b.blendExponent = p.blendExponent;
    b.heightStrength = p.heightStrength;
    b.metallic = p.metallic;
    b.smoothness = p.smoothness;
    b.occlusionStrength = p.occlusionStrength;
    b.normalStrength = p.normalStrength;
    b.detailScale = p.detailScale;
    b.detailAlbedo = p.detailAlbedo;
    b.detailSmoothness = p.detailSmoothness;
    b.detailNormalStrength = p.detailNormalStrength;
    b.biplanar = p.biplanar;
    b.antiTilingSharpness = p.antiTilingSharpness;
    b.emissionColor = p.emissionColor;
    b.fresnelStrength = p.fresnelStrength;
    return b;
}

inline LightingBlock toBlock(const shading::LightingParams& p)
{
    LightingBlock b{};
    for (int i = 0; i < STRATA_MAX_LIGHTS; ++i) {
        b.lights[i].direction = p.lights[i].direction;
        b.lights[i].color = p.lights[i].color;
    }
    b.lightCount = p.lightCount;
    b.skyAmbient = p.skyAmbient;
    b.groundAmbient = p.groundAmbient;
    b.exposure = p.exposure;
    return b;
}

} // namespace strata::render::detail
