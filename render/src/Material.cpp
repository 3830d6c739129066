// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/Material.h>

#include <strata/Error.h>

#include "MaterialMaps.h"
#include "RangeCheck.h"

#include <cmath>
#include <sstream>

namespace strata::render {

std::string featureNames(std::uint32_t features)
{
    static const char* NAMES[] = {"mask", "mods", "height", "normal", "top",    "detail",
                                  "detail-normal", "emission", "udn", "rnm", "layers", "anti-tiling"};
    std::string out;
    for (int i = 0; i < 12; ++i) {
        if (features & (1u << i)) {
            if (!out.empty()) out += '+';
            out += NAMES[i];
        }
    }
    return out.empty() ? "albedo" : out;
}

namespace {

/// The feature set of one material, its layers aside.
std::uint32_t ownFeatures(const Material& m)
{
    std::uint32_t f = 0;
    if (m.mask || m.topMask) f |= feature::MASK_MAP;
    if ((f & feature::MASK_MAP) && m.maskLayout == MaskLayout::Mods) f |= feature::MODS;
    if ((f & feature::MASK_MAP) && m.maskLayout == MaskLayout::Mohs && m.heightStrength > 0.0f)
        f |= feature::HEIGHT_BLEND;
    if (m.normal || m.topNormal) f |= feature::NORMAL_MAP;
    if (m.topAlbedo || m.topMask || m.topNormal) f |= feature::TOP_MAPS;
    if (m.detail) f |= feature::DETAIL;
    if (m.detailNormal) f |= feature::DETAIL_NORMAL;
    if (m.emission) f |= feature::EMISSION;
    if (m.antiTiling) f |= feature::ANTI_TILING;
    if (f & (feature::NORMAL_MAP | feature::DETAIL_NORMAL)) {
        if (m.normalBlend == NormalBlend::Udn) f |= feature::NORMAL_UDN;
        if (m.normalBlend == NormalBlend::Rnm) f |= feature::NORMAL_RNM;
    }
    return f;
}

} // namespace

std::uint32_t materialFeatures(const Material& m)
{
    if (m.layers.empty()) {
        return ownFeatures(m);
    }
    std::uint32_t f = ownFeatures(m) | feature::LAYERS;
    for (const MaterialLayer& layer : m.layers) f |= ownFeatures(layer.material);
    return normalizeFeatures(f);
}

std::uint32_t layerFeatures(const Material& material, int index, std::uint32_t mask)
{
    const Material& m = index == 0 ? material : material.layers.at(std::size_t(index - 1)).material;
    return normalizeFeatures(ownFeatures(m) & mask & ~feature::LAYERS);
}

std::uint32_t normalizeFeatures(std::uint32_t f)
{
    f &= feature::ALL;
    if (!(f & feature::MASK_MAP)) f &= ~(feature::MODS | feature::HEIGHT_BLEND);
    if (!(f & (feature::NORMAL_MAP | feature::DETAIL_NORMAL))) f &= ~(feature::NORMAL_UDN | feature::NORMAL_RNM);
    // A layered program serves layers of either mask layout and any normal
    // blend (each layer's own set decides at run time): no exclusions.
    if (!(f & feature::LAYERS)) {
        if (f & feature::MODS) f &= ~feature::HEIGHT_BLEND;
        if (f & feature::NORMAL_RNM) f &= ~feature::NORMAL_UDN;
    }
    return f;
}

std::uint32_t effectiveFeatures(const Material& material, std::uint32_t mask)
{
    const std::uint32_t all = materialFeatures(material);
    if (!(all & mask & feature::LAYERS)) {
        return layerFeatures(material, 0, mask); // the base alone
    }
    return normalizeFeatures(all & mask);
}

std::vector<std::uint32_t> allFeatureSets()
{
    std::vector<std::uint32_t> sets;
    for (std::uint32_t f = 0; f <= feature::ALL; ++f) {
        if (normalizeFeatures(f) == f) sets.push_back(f);
    }
    return sets;
}

bool usesLandform(const LayerRule& rule)
{
    return rule.flow.enabled || rule.wear.enabled || rule.deposition.enabled || rule.water.enabled;
}

bool usesRock(const LayerRule& rule)
{
    return rule.hardness.enabled || rule.bed.enabled;
}

namespace {

void checkBand(const std::string& what, const char* key, const LayerBand& band)
{
    if (!band.enabled) return;
    if (std::isnan(band.min) || std::isnan(band.max) || band.min > band.max) {
        throw Error(ErrorKind::BadInput, what + ": " + key + " band [" + std::to_string(band.min) + ", " + std::to_string(band.max) +
                    "] needs min <= max");
    }
    if (!(band.softness >= 0.0f && std::isfinite(band.softness))) {
        throw Error(ErrorKind::BadInput, what + ": " + key + " softness " + std::to_string(band.softness) + " must be finite and >= 0");
    }
}

void checkOne(const Material& m, const std::string& what)
{
    auto range = [&what](const char* key, double value, double lo, double hi) {
        detail::checkRange(what.c_str(), key, value, lo, hi);
    };
    if (!(std::isfinite(m.mapScale) && m.mapScale > 0.0f)) throw Error(ErrorKind::BadInput, what + ": mapScale must be > 0");
    range("blendOffset", m.blendOffset, 0.0f, 0.5f);
    range("blendExponent", m.blendExponent, 1.0f, 64.0f);
    range("heightStrength", m.heightStrength, 0.0f, 0.99f);
    range("metallic", m.metallic, 0.0f, 1.0f);
    range("smoothness", m.smoothness, 0.0f, 1.0f);
    range("occlusionStrength", m.occlusionStrength, 0.0f, 1.0f);
    range("normalStrength", m.normalStrength, 0.0f, 4.0f);
    range("detailScale", m.detailScale, 1e-4f, 1e4f);
    range("detailAlbedo", m.detailAlbedo, 0.0f, 1.0f);
    range("detailSmoothness", m.detailSmoothness, 0.0f, 1.0f);
    range("detailNormalStrength", m.detailNormalStrength, 0.0f, 1.0f);
    range("fresnelStrength", m.fresnelStrength, 0.0f, 1.0f);
    range("antiTilingSharpness", m.antiTilingSharpness, 1.0f, 16.0f);
    if (m.projections != 2 && m.projections != 3) {
        throw Error(ErrorKind::BadInput, what + ": projections = " + std::to_string(m.projections) + " must be 2 (biplanar) or 3 (triplanar)");
    }
    for (int c = 0; c < 3; ++c) {
        range("albedoTint", m.albedoTint[c], 0.0f, 16.0f);
        range("emissionColor", m.emissionColor[c], 0.0f, 1e4f);
    }
    const TexturePtr* maps[] = {&m.albedo,    &m.mask,   &m.normal,       &m.topAlbedo, &m.topMask,
                                &m.topNormal, &m.detail, &m.detailNormal, &m.emission};
    for (const TexturePtr* map : maps) {
        if (*map && (*map)->levels.empty()) throw Error(ErrorKind::BadInput, what + ": a texture has no levels");
    }
}

} // namespace

void checkMaterial(const Material& m)
{
    checkOne(m, "material");
    if (m.layers.empty()) return;
    if (int(m.layers.size()) + 1 > MAX_MATERIAL_LAYERS) {
        throw Error(ErrorKind::BadInput, "material: " + std::to_string(m.layers.size()) + " layers over the base; at most " +
                    std::to_string(MAX_MATERIAL_LAYERS - 1));
    }
    detail::checkRange("material", "layerBlendDepth", m.layerBlendDepth, 1e-3, 100.0);
    for (std::size_t i = 0; i < m.layers.size(); ++i) {
        const MaterialLayer& layer = m.layers[i];
        const std::string what = "material layer '" + (layer.name.empty() ? std::to_string(i + 1) : layer.name) + "'";
        checkOne(layer.material, what);
        if (!layer.material.layers.empty()) throw Error(ErrorKind::BadInput, what + ": layers cannot have layers of their own");
        const LayerRule& r = layer.rule;
        checkBand(what, "altitude", r.altitude);
        checkBand(what, "slope", r.slope);
        checkBand(what, "cavity", r.cavity);
        checkBand(what, "cover", r.cover);
        checkBand(what, "flow", r.flow);
        checkBand(what, "wear", r.wear);
        checkBand(what, "deposition", r.deposition);
        checkBand(what, "water", r.water);
        checkBand(what, "hardness", r.hardness);
        checkBand(what, "bed", r.bed);
        detail::checkRange(what.c_str(), "opacity", r.opacity, 0.0, 1.0);
        detail::checkRange(what.c_str(), "noiseFrequency", r.noiseFrequency, 0.0, 1e3);
        detail::checkRange(what.c_str(), "noiseThreshold", r.noiseThreshold, 0.0, 1.0);
        detail::checkRange(what.c_str(), "noiseSoftness", r.noiseSoftness, 0.0, 1.0);
    }
    detail::planLayerSlots(m); // the maps of each slot can share a texture array
}

} // namespace strata::render
