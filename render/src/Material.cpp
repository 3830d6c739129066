#include <strata/render/Material.h>

#include <strata/Error.h>

#include "RangeCheck.h"

#include <cmath>
#include <sstream>

namespace strata::render {

std::string featureNames(std::uint32_t features)
{
    static const char* NAMES[] = {"mask",   "mods",          "height",   "normal", "top",
                                  "detail", "detail-normal", "emission", "udn",    "rnm"};
    std::string out;
    for (int i = 0; i < 10; ++i) {
        if (features & (1u << i)) {
            if (!out.empty()) out += '+';
            out += NAMES[i];
        }
    }
    return out.empty() ? "albedo" : out;
}

std::uint32_t materialFeatures(const Material& m)
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
    if (f & (feature::NORMAL_MAP | feature::DETAIL_NORMAL)) {
        if (m.normalBlend == NormalBlend::Udn) f |= feature::NORMAL_UDN;
        if (m.normalBlend == NormalBlend::Rnm) f |= feature::NORMAL_RNM;
    }
    return f;
}

std::uint32_t normalizeFeatures(std::uint32_t f)
{
    f &= feature::ALL;
    if (!(f & feature::MASK_MAP)) f &= ~(feature::MODS | feature::HEIGHT_BLEND);
    if (f & feature::MODS) f &= ~feature::HEIGHT_BLEND;
    if (!(f & (feature::NORMAL_MAP | feature::DETAIL_NORMAL))) f &= ~(feature::NORMAL_UDN | feature::NORMAL_RNM);
    if (f & feature::NORMAL_RNM) f &= ~feature::NORMAL_UDN;
    return f;
}

std::uint32_t effectiveFeatures(const Material& material, std::uint32_t mask)
{
    return normalizeFeatures(materialFeatures(material) & mask);
}

std::vector<std::uint32_t> allFeatureSets()
{
    std::vector<std::uint32_t> sets;
    for (std::uint32_t f = 0; f <= feature::ALL; ++f) {
        if (normalizeFeatures(f) == f) sets.push_back(f);
    }
    return sets;
}

void checkMaterial(const Material& m)
{
    auto range = [](const char* key, double value, double lo, double hi) {
        detail::checkRange("material", key, value, lo, hi);
    };
    if (!(std::isfinite(m.mapScale) && m.mapScale > 0.0f)) throw Error("material: mapScale must be > 0");
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
    if (m.projections != 2 && m.projections != 3) {
        throw Error("material: projections = " + std::to_string(m.projections) + " must be 2 (biplanar) or 3 (triplanar)");
    }
    for (int c = 0; c < 3; ++c) {
        range("albedoTint", m.albedoTint[c], 0.0f, 16.0f);
        range("emissionColor", m.emissionColor[c], 0.0f, 1e4f);
    }
    const TexturePtr* maps[] = {&m.albedo,    &m.mask,   &m.normal,       &m.topAlbedo, &m.topMask,
                                &m.topNormal, &m.detail, &m.detailNormal, &m.emission};
    for (const TexturePtr* map : maps) {
        if (*map && (*map)->levels.empty()) throw Error("material: a texture has no levels");
    }
}

} // namespace strata::render
