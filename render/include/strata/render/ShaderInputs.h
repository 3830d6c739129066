// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// What the GL renderer's terrain program is given for a material and its
/// lighting, as plain named values: for other GL clients of the same shared
/// shading source (the web viewer that `strata bake` writes, whose GLSL ES
/// programs web/GenerateShaders.cmake generates from shaders/).

#include <strata/render/Material.h>
#include <strata/render/SnapshotOptions.h>
#include <strata/render/Texture.h>

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::render {

/// One uniform value by its GLSL name, e.g. "uMaterial.albedoTint",
/// "uLighting.lights[1].color", "uLayerSet.layers[2].altitude".
struct ShaderUniform
{
    std::string name;
    std::string type;           ///< "float", "int", "uint", "vec3", "vec4" or "mat4"
    std::vector<double> values; ///< 1, 3, 4 or 16 (column-major) components (floats as the GL renderer rounds them)
};

/// The terrain program's inputs for `material` under `lighting` with
/// positions relative to `origin` (metres; offsets computed in double as
/// the GL renderer does), the features outside `featureMask` switched off.
struct TerrainShaderInputs
{
    std::uint32_t features = 0; ///< STRATA_FEATURES: effectiveFeatures(material, featureMask)
    int layerCount = 1;         ///< STRATA_LAYER_COUNT when features has LAYERS
    /// uFrame's material part (mapScale, textureOffset, detailOffset,
    /// tileOffset), uMaterial, uLighting, uLayerSet (layered programs), and
    /// uAtmosphere's parts that do not depend on the camera or viewport
    /// (not skyRayMatrix, viewportSize).
    std::vector<ShaderUniform> uniforms;
    /// The nine map slots (MAP_* of TriplanarMaterial.h): slot k, layer i is
    /// maps[k][i]; within a slot every layer has one size and level count
    /// (the texture arrays the GL renderer uploads, stand-ins included).
    std::array<std::vector<TexturePtr>, 9> maps;
};

/// Throws strata::Error as checkMaterial() and for an atmosphere out of range.
TerrainShaderInputs terrainShaderInputs(const Material& material, const Lighting& lighting,
                                        const glm::dvec3& origin, std::uint32_t featureMask = feature::ALL);

/// uShadow (shaders/Shadow.h) as the GL renderer sets it for a mesh whose
/// vertices lie in [boundsMin, boundsMax] (metres), positions relative to
/// `origin`: the sun's orthographic view fitted to the box; enabled = 0
/// when `shadows` is off.
std::vector<ShaderUniform> shadowShaderUniforms(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax,
                                                const glm::dvec3& origin, const Lighting& lighting,
                                                const ShadowOptions& shadows);

} // namespace strata::render
