// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the public Material/Lighting as the shared header's parameter
// structs (strata::shading::MaterialParams, LightingParams).

#include "ShadingPrelude.h"

#include <strata/render/Material.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace strata::render::detail {

inline shading::MaterialParams toShading(const Material& m)
{
    shading::MaterialParams p{};
    p.albedoTint = m.albedoTint;
    p.blendOffset = m.blendOffset;
    p.blendExponent = m.blendExponent;
    p.heightStrength = m.heightStrength;
    p.metallic = m.metallic;
    p.smoothness = m.smoothness;
    p.occlusionStrength = m.occlusionStrength;
    p.normalStrength = m.normalStrength;
    p.detailScale = m.detailScale;
    p.detailAlbedo = m.detailAlbedo;
    p.detailSmoothness = m.detailSmoothness;
    p.detailNormalStrength = m.detailNormalStrength;
    p.biplanar = m.projections == 2 ? 1.0f : 0.0f;
    p.antiTilingSharpness = m.antiTilingSharpness;
    p.emissionColor = m.emissionColor;
    p.fresnelStrength = m.fresnelStrength;
    return p;
}

inline glm::vec3 unitOr(glm::vec3 v, glm::vec3 fallback)
{
    const float len = glm::length(v);
    return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

inline shading::LightingParams toShading(const Lighting& l)
{
    shading::LightingParams p{};
    p.lights[0].direction = unitOr(l.sunDirection, glm::vec3(0.0f, 1.0f, 0.0f));
    p.lights[0].color = l.sunColor;
    int count = 1;
    for (const DirectionalLightSource& light : l.extraLights) {
        if (count == STRATA_MAX_LIGHTS) break;
        p.lights[count].direction = unitOr(light.direction, glm::vec3(0.0f, 1.0f, 0.0f));
        p.lights[count].color = light.color;
        ++count;
    }
    for (int i = count; i < STRATA_MAX_LIGHTS; ++i) {
        p.lights[i].direction = glm::vec3(0.0f, 1.0f, 0.0f);
        p.lights[i].color = glm::vec3(0.0f);
    }
    p.lightCount = count;
    p.skyAmbient = l.skyAmbient;
    p.groundAmbient = l.groundAmbient;
    p.exposure = l.exposure;
    return p;
}

} // namespace strata::render::detail
