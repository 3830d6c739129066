// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "LayerSetup.h"

#include <algorithm>
#include <cmath>

namespace strata::render::detail {

namespace {

constexpr double UNBOUNDED = 1e30;
constexpr double NOISE_PERIOD = 256.0; // latticeHash()'s period, in cells

float bound(double value) { return float(std::clamp(value, -UNBOUNDED, UNBOUNDED)); }

/// A band as the shader reads it, `shift` subtracted from its bounds.
glm::vec4 band(const LayerBand& b, double shift = 0.0)
{
    if (!b.enabled) return glm::vec4(-1e30f, 1e30f, 0.0f, 0.0f);
    return glm::vec4(bound(double(b.min) - shift), bound(double(b.max) - shift), b.softness, 1.0f);
}


shading::LayerParams layerParams(const Material& m, const LayerRule* rule, const glm::dvec3& origin,
                                 std::uint32_t features)
{
    shading::LayerParams l = ruleParams(rule, origin);
    const TextureRebase rebase = rebaseTextures(m.mapScale, m.detailScale, origin);
    l.textureOffset = glm::vec4(rebase.textureOffset, 0.0f);
    l.detailOffset = glm::vec4(rebase.detailOffset, 0.0f);
    l.tileOffset = glm::vec4(rebase.tileOffset, 0.0f);
    l.mapScale = m.mapScale;
    l.features = features;
    return l;
}

} // namespace

shading::LayerParams ruleParams(const LayerRule* rule, const glm::dvec3& origin)
{
    shading::LayerParams l{};
    l.opacity = 1.0f;
    l.altitude = band(LayerBand{});
    l.slope = l.altitude;
    l.cavity = l.altitude;
    l.cover = l.altitude;
    l.flow = l.altitude;
    l.wear = l.altitude;
    l.deposition = l.altitude;
    l.water = l.altitude;
    l.hardness = l.altitude;
    l.bed = l.altitude;
    if (rule) {
        l.altitude = band(rule->altitude, origin.y);
        l.slope = band(rule->slope);
        l.cavity = band(rule->cavity);
        l.cover = band(rule->cover);
        l.flow = band(rule->flow);
        l.wear = band(rule->wear);
        l.deposition = band(rule->deposition);
        l.water = band(rule->water);
        l.hardness = band(rule->hardness);
        l.bed = band(rule->bed);
        l.opacity = rule->opacity;
        l.seed = rule->noiseSeed;
        if (rule->noiseFrequency > 0.0f) {
            l.noise = glm::vec4(rule->noiseFrequency, rule->noiseThreshold, rule->noiseSoftness, 1.0f);
            // The lattice repeats every NOISE_PERIOD cells: rebase modulo it.
            const glm::dvec3 cells = origin * double(rule->noiseFrequency);
            l.noiseOffset = glm::vec4(glm::vec3(cells - glm::floor(cells / NOISE_PERIOD) * NOISE_PERIOD), 0.0f);
        }
    }
    return l;
}

TextureRebase rebaseTextures(float mapScale, float detailScale, const glm::dvec3& origin)
{
    const glm::dvec3 scaled = origin * double(mapScale);
    const glm::dvec3 whole = glm::floor(scaled);
    const glm::dvec3 detail = whole * double(detailScale);
    TextureRebase r;
    r.textureOffset = glm::vec3(scaled - whole);
    r.detailOffset = glm::vec3(detail - glm::floor(detail));
    r.tileOffset = glm::vec3(whole - glm::floor(whole / 256.0) * 256.0);
    return r;
}

shading::LayerSetParams makeLayerSet(const Material& material, const glm::dvec3& origin, std::uint32_t mask)
{
    shading::LayerSetParams set{};
    set.count = 1 + int(std::min<std::size_t>(material.layers.size(), STRATA_MAX_LAYERS - 1));
    set.blendDepth = material.layerBlendDepth;
    set.layers[0] = layerParams(material, nullptr, origin, layerFeatures(material, 0, mask));
    set.materials[0] = toShading(material);
    for (int i = 1; i < set.count; ++i) {
        const MaterialLayer& layer = material.layers[std::size_t(i - 1)];
        set.layers[i] = layerParams(layer.material, &layer.rule, origin, layerFeatures(material, i, mask));
        set.materials[i] = toShading(layer.material);
    }
    return set;
}

LayerSetBlock toBlock(const shading::LayerSetParams& p)
{
    LayerSetBlock b{};
    for (int i = 0; i < STRATA_MAX_LAYERS; ++i) {
        b.layers[i] = p.layers[i];
        b.materials[i] = toBlock(p.materials[i]);
    }
    b.count = p.count;
    b.blendDepth = p.blendDepth;
    return b;
}

} // namespace strata::render::detail
