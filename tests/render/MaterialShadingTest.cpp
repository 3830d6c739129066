// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The material math of the shared GLSL/C++ header (TriplanarShading.h,
// TriplanarMaterial.h), each formula at its definition and its extremes.

#include "ShadingPrelude.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace {

using namespace strata::shading;

std::vector<vec3> testNormals()
{
    std::vector<vec3> normals;
    std::uint64_t state = 99;
    auto unit = [&] {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return float(state >> 40) / float(1 << 24) * 2.0f - 1.0f;
    };
    while (normals.size() < 3000) {
        vec3 v{unit(), unit(), unit()};
        const float len = glm::length(v);
        if (len > 1e-3f && len <= 1.0f) normals.push_back(v / len);
    }
    // Axes, diagonals, and the ±0 cases.
    for (vec3 v : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1),
                   vec3(0.57735f, 0.57735f, 0.57735f), vec3(-0.57735f, 0.57735f, -0.57735f), vec3(-0.0f, 1, -0.0f)}) {
        normals.push_back(v);
    }
    return normals;
}

void expectPartitionOfUnity(const vec3& w)
{
    for (int i = 0; i < 3; ++i) {
        ASSERT_TRUE(std::isfinite(w[i]));
        ASSERT_GE(w[i], 0.0f);
    }
    ASSERT_NEAR(w.x + w.y + w.z, 1.0f, 1e-5f);
}

TEST(MaterialShading, HeightWeightsAreAPartitionOfUnityAtTheExtremes)
{
    const float denormal = std::numeric_limits<float>::denorm_min();
    std::vector<vec3> normals = testNormals();
    normals.push_back(vec3(0.0f));
    normals.push_back(vec3(denormal, 0.0f, 0.0f));
    normals.push_back(vec3(denormal, denormal, -denormal));
    normals.push_back(vec3(1e-30f, -1e-32f, 1e-31f));
    for (const vec3& n : normals) {
        for (float offset : {0.0f, 0.25f, 0.5f, 0.577f}) {
            for (float exponent : {1.0f, 8.0f, 64.0f}) {
                for (float strength : {0.0f, 0.5f, 0.99f}) {
                    for (vec3 heights : {vec3(0.0f), vec3(1.0f), vec3(0.0f, 1.0f, 0.5f), vec3(1e-30f)}) {
                        SCOPED_TRACE(::testing::Message() << n.x << "," << n.y << "," << n.z << " o" << offset << " e"
                                                          << exponent << " s" << strength);
                        expectPartitionOfUnity(triplanarWeightsHeight(n, offset, exponent, heights, strength));
                    }
                }
            }
        }
    }
}

TEST(MaterialShading, HeightWeightsMatchTheSeedFormula)
{
    const vec3 n = glm::normalize(vec3(0.6f, 0.7f, -0.3f));
    const vec3 heights{0.2f, 0.9f, 0.5f};
    const float offset = 0.1f, exponent = 3.0f, strength = 0.6f;
    vec3 w = glm::clamp(glm::abs(n) - vec3(offset), 0.0f, 1.0f);
    w *= glm::mix(vec3(1.0f), heights, strength);
    w = glm::pow(w, vec3(exponent));
    w /= w.x + w.y + w.z;
    const vec3 got = triplanarWeightsHeight(n, offset, exponent, heights, strength);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], w[i], 1e-6f);
    // Strength 0 is the plain normal blend.
    const vec3 plain = triplanarWeights(n, offset, exponent);
    const vec3 zero = triplanarWeightsHeight(n, offset, exponent, heights, 0.0f);
    for (int i = 0; i < 3; ++i) EXPECT_FLOAT_EQ(zero[i], plain[i]);
}

TEST(MaterialShading, HeightBlendFavoursTheHigherSample)
{
    // A 45° slope between X and Y: equal normal weights, so the heights decide.
    const vec3 n = glm::normalize(vec3(1.0f, 1.0f, 0.0f));
    const vec3 yHigher = triplanarWeightsHeight(n, 0.2f, 4.0f, vec3(0.2f, 0.8f, 0.5f), 0.9f);
    EXPECT_GT(yHigher.y, 0.9f);
    const vec3 xHigher = triplanarWeightsHeight(n, 0.2f, 4.0f, vec3(0.8f, 0.2f, 0.5f), 0.9f);
    EXPECT_GT(xHigher.x, 0.9f);
    // Strength 0.99 with heights 0 everywhere: weights stay those of the normal.
    const vec3 flat = triplanarWeightsHeight(n, 0.2f, 4.0f, vec3(0.0f), 0.99f);
    EXPECT_NEAR(flat.x, 0.5f, 1e-5f);
    EXPECT_NEAR(flat.y, 0.5f, 1e-5f);
}

TEST(MaterialShading, UvDerivativesUseTheMirroringSignsWithoutOffsets)
{
    const vec3 d{1.0f, 2.0f, 3.0f};
    for (vec3 n : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)}) {
        const TriplanarUV a = triplanarUV(d, n);
        const TriplanarUV zero = triplanarUV(vec3(0.0f), n);
        const TriplanarUV dd = triplanarUVDerivative(d, n);
        EXPECT_EQ(dd.x, a.x - zero.x);
        EXPECT_EQ(dd.y, a.y - zero.y);
        EXPECT_EQ(dd.z, a.z - zero.z);
    }
}

// --- Normals -----------------------------------------------------------------

void expectVecNear(const vec3& a, const vec3& b, float tolerance)
{
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(MaterialShading, DecodeNormalAtStrengthZeroAndFlatTexels)
{
    expectVecNear(decodeNormal(vec4(0.9f, 0.1f, 0.7f, 1.0f), 0.0f), vec3(0, 0, 1), 0.0f);
    expectVecNear(decodeNormal(vec4(0.5f, 0.5f, 1.0f, 1.0f), 1.0f), vec3(0, 0, 1), 0.0f);
    const vec3 n = decodeNormal(vec4(0.75f, 0.5f, 1.0f, 1.0f), 1.0f);
    expectVecNear(n, vec3(0.5f, 0.0f, std::sqrt(0.75f)), 1e-6f);
    EXPECT_NEAR(glm::length(decodeNormal(vec4(1.0f, 1.0f, 0.0f, 1.0f), 4.0f)), 1.0f, 1e-6f);
}

/// The mapped normal m on face n rotated into world space: the tangent
/// frame of each face seen from outside (U right, V up), with U as
/// triplanarUV() orients it.
vec3 rotatedIntoWorld(vec3 m, vec3 n)
{
    vec3 tangentU, tangentV;
    if (n.x > 0.5f) {
        tangentU = vec3(0, 0, -1);
        tangentV = vec3(0, 1, 0);
    } else if (n.x < -0.5f) {
        tangentU = vec3(0, 0, 1);
        tangentV = vec3(0, 1, 0);
    } else if (n.y > 0.5f) {
        tangentU = vec3(-1, 0, 0);
        tangentV = vec3(0, 0, 1);
    } else if (n.y < -0.5f) {
        tangentU = vec3(1, 0, 0);
        tangentV = vec3(0, 0, 1);
    } else if (n.z > 0.5f) {
        tangentU = vec3(1, 0, 0);
        tangentV = vec3(0, 1, 0);
    } else {
        tangentU = vec3(-1, 0, 0);
        tangentV = vec3(0, 1, 0);
    }
    return tangentU * m.x + tangentV * m.y + n * m.z;
}

vec3 worldNormalFor(vec3 m, vec3 n, int mode)
{
    if (std::abs(n.x) > 0.5f) return worldNormalX(m, n, mode);
    if (std::abs(n.y) > 0.5f) return worldNormalY(m, n, mode);
    return worldNormalZ(m, n, mode);
}

TEST(MaterialShading, WhiteoutOnAxisPlanesRotatesTheMappedNormalIntoWorldSpace)
{
    const vec3 m = glm::normalize(vec3(0.3f, -0.2f, 0.9f));
    for (vec3 n : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)}) {
        SCOPED_TRACE(::testing::Message() << n.x << "," << n.y << "," << n.z);
        for (int mode : {NORMAL_BLEND_WHITEOUT, NORMAL_BLEND_UDN, NORMAL_BLEND_RNM}) {
            const vec3 expected =
                mode == NORMAL_BLEND_UDN ? rotatedIntoWorld(vec3(m.x, m.y, 1.0f), n) : rotatedIntoWorld(m, n);
            expectVecNear(worldNormalFor(m, n, mode), expected, 1e-6f);
        }
    }
}

TEST(MaterialShading, MirroringIsFixedForNormalsOnAllSixFaces)
{
    // A normal tilted towards +U must tilt towards the face's "right" seen
    // from outside, which is the direction in which triplanarUV's U grows.
    const vec3 m = glm::normalize(vec3(0.5f, 0.0f, 0.8f));
    const vec3 p{0.3f, 0.4f, 0.2f};
    for (vec3 n : {vec3(1, 0, 0), vec3(-1, 0, 0), vec3(0, 1, 0), vec3(0, -1, 0), vec3(0, 0, 1), vec3(0, 0, -1)}) {
        const vec3 world = worldNormalFor(m, n, NORMAL_BLEND_WHITEOUT);
        const vec3 tilt = world - n * glm::dot(world, n);
        // Moving along `tilt` must increase the projection's U.
        const float step = 0.01f;
        const TriplanarUV a = triplanarUV(p, n);
        const TriplanarUV b = triplanarUV(p + tilt * step, n);
        const float du = std::abs(n.x) > 0.5f ? b.x.x - a.x.x : std::abs(n.y) > 0.5f ? b.y.x - a.y.x : b.z.x - a.z.x;
        EXPECT_GT(du, 0.0f) << "face " << n.x << "," << n.y << "," << n.z;
    }
}

TEST(MaterialShading, FlatNormalMapReturnsTheSurfaceNormal)
{
    const vec3 flatMap{0.0f, 0.0f, 1.0f};
    for (const vec3& n : testNormals()) {
        for (int mode : {NORMAL_BLEND_WHITEOUT, NORMAL_BLEND_UDN, NORMAL_BLEND_RNM}) {
            const vec3 w = triplanarWeights(n, 0.2f, 4.0f);
            const vec3 sum = worldNormalX(flatMap, n, mode) * w.x + worldNormalY(flatMap, n, mode) * w.y +
                             worldNormalZ(flatMap, n, mode) * w.z;
            expectVecNear(safeNormalize(sum, n), n, 2e-6f);
        }
    }
}

TEST(MaterialShading, RnmIsUnitAndIdentityWithAFlatDetail)
{
    const vec3 base = glm::normalize(vec3(0.2f, -0.4f, 0.8f));
    expectVecNear(blendNormalRnm(base, vec3(0, 0, 1)), base, 1e-6f);
    expectVecNear(blendNormalRnm(vec3(0, 0, 1), base), base, 1e-6f);
    const vec3 detail = glm::normalize(vec3(-0.3f, 0.1f, 0.9f));
    EXPECT_NEAR(glm::length(blendNormalRnm(base, detail)), 1.0f, 1e-5f);
}

// --- Detail ------------------------------------------------------------------

TEST(MaterialShading, DetailValueHalfChangesNothing)
{
    const vec3 albedo{0.2f, 0.5f, 0.9f};
    for (float strength : {0.0f, 0.5f, 1.0f}) {
        for (float mask : {0.0f, 0.3f, 1.0f}) {
            const vec3 a = applyDetailAlbedo(albedo, 0.5f, strength, mask);
            expectVecNear(a, albedo, 1e-6f);
            EXPECT_NEAR(applyDetailSmoothness(0.37f, 0.5f, strength, mask), 0.37f, 1e-7f);
        }
    }
    // Full strength: 1 drives to white, 0 to black, in sqrt space.
    expectVecNear(applyDetailAlbedo(albedo, 1.0f, 1.0f, 1.0f), vec3(1.0f), 1e-6f);
    expectVecNear(applyDetailAlbedo(albedo, 0.0f, 1.0f, 1.0f), vec3(0.0f), 1e-6f);
    // Half way: mix(sqrt(a), 1, 0.5)².
    const float expected = std::pow(0.5f * (std::sqrt(0.25f) + 1.0f), 2.0f);
    EXPECT_NEAR(applyDetailAlbedo(vec3(0.25f), 0.75f, 1.0f, 1.0f).x, expected, 1e-6f);
    // The mask scales the effect.
    EXPECT_NEAR(applyDetailSmoothness(0.4f, 1.0f, 1.0f, 0.5f), 0.7f, 1e-6f);
}

// --- BRDF --------------------------------------------------------------------

TEST(MaterialShading, BrdfFollowsTheMinimalistCookTorrance)
{
    const vec3 albedo{0.5f, 0.4f, 0.3f};
    const Brdf dielectric = makeBrdf(albedo, 0.0f, 0.5f);
    expectVecNear(dielectric.diffuse, albedo * 0.96f, 1e-6f);
    expectVecNear(dielectric.specular, vec3(0.04f), 1e-7f);
    EXPECT_FLOAT_EQ(dielectric.roughness, 0.25f);
    const Brdf metal = makeBrdf(albedo, 1.0f, 1.0f);
    expectVecNear(metal.diffuse, vec3(0.0f), 1e-7f);
    expectVecNear(metal.specular, albedo, 1e-7f);
    EXPECT_FLOAT_EQ(metal.fresnel, 1.0f);

    // Specular strength against the formula, head-on light and view.
    const vec3 n{0, 0, 1};
    const vec3 l = glm::normalize(vec3(0.3f, 0.0f, 1.0f));
    const vec3 v = glm::normalize(vec3(-0.2f, 0.1f, 1.0f));
    const float r = 0.3f;
    const vec3 h = glm::normalize(l + v);
    const float nh2 = glm::dot(n, h) * glm::dot(n, h);
    const float lh2 = glm::dot(l, h) * glm::dot(l, h);
    const float d = nh2 * (r * r - 1.0f) + 1.00001f;
    const float expected = r * r / (d * d * std::max(0.1f, lh2) * (4.0f * r + 2.0f));
    EXPECT_NEAR(specularStrength(n, v, l, r), expected, 1e-5f * expected);
    // Finite for a perfectly smooth surface (roughness 0) and for light from behind.
    EXPECT_TRUE(std::isfinite(specularStrength(n, n, n, 0.0f)));
    EXPECT_EQ(glm::length(directLight(dielectric, n, v, vec3(0, 0, -1), vec3(1.0f))), 0.0f);
}

TEST(MaterialShading, OcclusionAffectsIndirectLightOnly)
{
    const Brdf b = makeBrdf(vec3(0.5f), 0.0f, 0.5f);
    const vec3 n{0, 1, 0};
    const vec3 v = glm::normalize(vec3(0, 1, 1));
    const vec3 full = indirectLight(b, n, v, vec3(0.4f), vec3(0.1f), 1.0f, 1.0f);
    const vec3 half = indirectLight(b, n, v, vec3(0.4f), vec3(0.1f), 0.5f, 1.0f);
    expectVecNear(half, full * 0.5f, 1e-6f);
    // lightSurface: occlusion 0 leaves exactly the direct light.
    SurfaceOutput o{};
    o.albedo = vec3(0.5f);
    o.normal = n;
    o.metallic = 0.0f;
    o.smoothness = 0.5f;
    o.occlusion = 0.0f;
    o.emission = vec3(0.0f);
    LightingParams l{};
    l.lights[0].direction = n;
    l.lights[0].color = vec3(1.0f);
    l.lightCount = 1;
    l.skyAmbient = vec3(0.4f);
    l.groundAmbient = vec3(0.1f);
    l.exposure = 1.0f;
    expectVecNear(lightSurface(o, v, l, 1.0f), directLight(b, n, v, n, vec3(1.0f)), 1e-6f);
    // Hemisphere: sky straight up, ground straight down.
    expectVecNear(hemisphere(vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, 1)), vec3(1, 0, 0), 0.0f);
    expectVecNear(hemisphere(vec3(0, -1, 0), vec3(1, 0, 0), vec3(0, 0, 1)), vec3(0, 0, 1), 0.0f);
}

TEST(MaterialShading, ToneMapAndSrgb)
{
    expectVecNear(toneMap(vec3(0.0f), 1.0f), vec3(0.0f), 1e-6f);
    expectVecNear(toneMap(vec3(-5.0f), 1.0f), vec3(0.0f), 1e-6f);
    EXPECT_LE(toneMap(vec3(1e6f), 1.0f).x, 1.0f);
    EXPECT_NEAR(toneMap(vec3(0.5f), 2.0f).x, toneMapAces(vec3(1.0f)).x, 1e-7f);
    EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
    EXPECT_NEAR(linearToSrgb(1.0f), 1.0f, 1e-6f);
    EXPECT_NEAR(linearToSrgb(0.2140411f), 0.5f, 1e-5f); // sRGB 0.5 decodes to 0.214041
}

// --- The whole material, per feature set ----------------------------------------

/// Constant maps, one value per slot, for evaluating the material in C++.
struct ConstantMaps
{
    vec4 values[STRATA_MAP_COUNT];
    std::uint32_t features = 0xffffffffu;
    mutable int samples[STRATA_MAP_COUNT] = {};

    vec4 sample(int map, vec2, vec2, vec2) const
    {
        ++samples[map];
        return values[map];
    }
};

MaterialParams defaultParams()
{
    MaterialParams m{};
    m.albedoTint = vec3(1.0f);
    m.blendOffset = 0.2f;
    m.blendExponent = 4.0f;
    m.heightStrength = 0.5f;
    m.metallic = 1.0f;
    m.smoothness = 1.0f;
    m.occlusionStrength = 1.0f;
    m.normalStrength = 1.0f;
    m.detailScale = 4.0f;
    m.detailAlbedo = 1.0f;
    m.detailSmoothness = 1.0f;
    m.detailNormalStrength = 1.0f;
    m.emissionColor = vec3(2.0f);
    m.fresnelStrength = 1.0f;
    return m;
}

ConstantMaps makeMaps()
{
    ConstantMaps maps;
    maps.values[MAP_ALBEDO] = vec4(0.8f, 0.1f, 0.1f, 1.0f);
    maps.values[MAP_MASK] = vec4(0.0f, 0.5f, 0.5f, 0.4f);
    maps.values[MAP_NORMAL] = vec4(0.7f, 0.4f, 1.0f, 1.0f);
    maps.values[MAP_TOP_ALBEDO] = vec4(0.1f, 0.8f, 0.1f, 1.0f);
    maps.values[MAP_TOP_MASK] = vec4(0.0f, 1.0f, 0.9f, 0.2f);
    maps.values[MAP_TOP_NORMAL] = vec4(0.5f, 0.5f, 1.0f, 1.0f);
    maps.values[MAP_DETAIL] = vec4(0.5f, 0.5f, 0.5f, 1.0f);
    maps.values[MAP_DETAIL_NORMAL] = vec4(0.5f, 0.5f, 1.0f, 1.0f);
    maps.values[MAP_EMISSION] = vec4(0.0f, 0.5f, 1.0f, 1.0f);
    return maps;
}

SurfaceInput surfaceAt(vec3 n)
{
    SurfaceInput s{};
    s.p = vec3(0.3f, 0.6f, 0.9f);
    s.dpdx = vec3(0.01f, 0.0f, 0.0f);
    s.dpdy = vec3(0.0f, 0.01f, 0.0f);
    s.n = n;
    s.viewDir = n;
    return s;
}

TEST(MaterialShading, DisabledFeaturesSampleNothing)
{
    ConstantMaps maps = makeMaps();
    const SurfaceInput s = surfaceAt(glm::normalize(vec3(0.3f, 0.8f, 0.5f)));
    const SurfaceOutput o = evaluateSurface<0u>(maps, s, defaultParams());
    for (int map = 1; map < STRATA_MAP_COUNT; ++map) EXPECT_EQ(maps.samples[map], 0) << "map " << map;
    EXPECT_GT(maps.samples[MAP_ALBEDO], 0);
    expectVecNear(o.normal, s.n, 0.0f); // no normal map: no normal blend at all
    EXPECT_EQ(o.metallic, 1.0f);        // the parameters themselves
    EXPECT_EQ(o.occlusion, 1.0f);
    // The run-time bits gate the all-features instantiation the same way.
    ConstantMaps runtime = makeMaps();
    runtime.features = 0;
    const SurfaceOutput r = evaluateSurface<0xffffffffu>(runtime, s, defaultParams());
    for (int map = 1; map < STRATA_MAP_COUNT; ++map) EXPECT_EQ(runtime.samples[map], 0) << "map " << map;
    expectVecNear(r.albedo, o.albedo, 0.0f);
}

TEST(MaterialShading, TopMapsOnlyWhereNormalPointsUp)
{
    constexpr unsigned F = FEATURE_TOP_MAPS;
    MaterialParams m = defaultParams();
    m.blendOffset = 0.0f;
    m.blendExponent = 1.0f;
    ConstantMaps up = makeMaps();
    const SurfaceOutput top = evaluateSurface<F>(up, surfaceAt(vec3(0, 1, 0)), m);
    expectVecNear(top.albedo, vec3(0.1f, 0.8f, 0.1f), 1e-6f);
    EXPECT_GT(up.samples[MAP_TOP_ALBEDO], 0);
    ConstantMaps down = makeMaps();
    const SurfaceOutput bottom = evaluateSurface<F>(down, surfaceAt(vec3(0, -1, 0)), m);
    expectVecNear(bottom.albedo, vec3(0.8f, 0.1f, 0.1f), 1e-6f);
    EXPECT_EQ(down.samples[MAP_TOP_ALBEDO], 0);
    ConstantMaps side = makeMaps();
    evaluateSurface<F>(side, surfaceAt(vec3(1, 0, 0)), m);
    EXPECT_EQ(side.samples[MAP_TOP_ALBEDO], 0);
}

TEST(MaterialShading, NormalStrengthZeroGivesTheSurfaceNormal)
{
    constexpr unsigned F = FEATURE_NORMAL_MAP;
    MaterialParams m = defaultParams();
    m.normalStrength = 0.0f;
    for (const vec3& n : testNormals()) {
        ConstantMaps maps = makeMaps();
        const SurfaceOutput o = evaluateSurface<F>(maps, surfaceAt(n), m);
        expectVecNear(o.normal, n, 2e-6f);
    }
    // With strength the mapped normal does tilt it.
    ConstantMaps maps = makeMaps();
    const SurfaceOutput tilted = evaluateSurface<F>(maps, surfaceAt(vec3(0, 0, 1)), defaultParams());
    EXPECT_LT(tilted.normal.z, 0.99f);
}

TEST(MaterialShading, MaskLayoutsOcclusionDetailAndEmission)
{
    MaterialParams m = defaultParams();
    m.occlusionStrength = 0.5f;
    ConstantMaps maps = makeMaps();
    const vec3 n{0, 0, 1};
    const SurfaceOutput mohs = evaluateSurface<FEATURE_MASK_MAP>(maps, surfaceAt(n), m);
    EXPECT_NEAR(mohs.occlusion, 0.75f, 1e-6f); // mix(1, 0.5, 0.5)
    EXPECT_NEAR(mohs.smoothness, 0.4f, 1e-6f);
    EXPECT_EQ(mohs.metallic, 0.0f);

    // MODS: the detail mask is B (0.5 here) and scales the detail.
    maps.values[MAP_DETAIL] = vec4(1.0f, 0.5f, 1.0f, 1.0f);
    constexpr unsigned MODS = FEATURE_MASK_MAP | FEATURE_MODS | FEATURE_DETAIL;
    const SurfaceOutput mods = evaluateSurface<MODS>(maps, surfaceAt(n), m);
    const float expectedR = std::pow(0.5f * (std::sqrt(0.8f) + 1.0f), 2.0f);
    EXPECT_NEAR(mods.albedo.x, expectedR, 1e-5f);
    EXPECT_NEAR(mods.smoothness, 0.7f, 1e-6f); // mix(0.4, 1, 0.5)

    const SurfaceOutput lit = evaluateSurface<FEATURE_EMISSION>(maps, surfaceAt(n), m);
    expectVecNear(lit.emission, vec3(0.0f, 1.0f, 2.0f), 1e-6f);
}

TEST(MaterialShading, ShadeFragmentIsFiniteForEveryFeatureSet)
{
    LightingParams l{};
    l.lights[0].direction = glm::normalize(vec3(0.3f, 0.8f, 0.2f));
    l.lights[0].color = vec3(3.0f);
    l.lights[1].direction = vec3(-1, 0, 0);
    l.lights[1].color = vec3(0.5f);
    l.lightCount = 2;
    l.skyAmbient = vec3(0.4f);
    l.groundAmbient = vec3(0.1f);
    l.exposure = 1.0f;
    const std::vector<vec3> normals = testNormals();
    for (unsigned features = 0; features < 1024u; features += 7u) {
        ConstantMaps maps = makeMaps();
        maps.features = features;
        for (std::size_t i = 0; i < normals.size(); i += 97) {
            const vec3 c = shadeFragment<0xffffffffu>(maps, surfaceAt(normals[i]), defaultParams(), l);
            for (int k = 0; k < 3; ++k) {
                ASSERT_TRUE(std::isfinite(c[k]) && c[k] >= 0.0f && c[k] <= 1.0f) << features;
            }
        }
    }
}

} // namespace
