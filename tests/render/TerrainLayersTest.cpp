// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Terrain layers (shaders/TerrainLayers.h): the rule and blend math as C++,
// the layer maps' texture-array sizing, the material checks, and GL against
// the CPU reference with layers of different feature sets, also 8.4e6 m
// from the origin.

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>

#include "GoldenScenes.h"
#include "LayerSetup.h"
#include "MaterialMaps.h"
#include "Parity.h"
#include "ShadingBridge.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace strata::render;
namespace shading = strata::shading;
using strata::test::TestMesh;

// ---------------------------------------------------------------------------
// Rules.

TEST(TerrainLayers, BandWeightIsOneInsideAndRampsOutside)
{
    const glm::vec4 band(10.0f, 20.0f, 4.0f, 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(15.0f, band), 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(10.0f, band), 1.0f); // the bounds are inside
    EXPECT_FLOAT_EQ(shading::bandWeight(20.0f, band), 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(8.0f, band), 0.5f); // half way down the ramp
    EXPECT_FLOAT_EQ(shading::bandWeight(22.0f, band), 0.5f);
    EXPECT_FLOAT_EQ(shading::bandWeight(6.0f, band), 0.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(24.5f, band), 0.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(-1e30f, band), 0.0f);
    // Softness 0: a step, still finite.
    const glm::vec4 hard(10.0f, 20.0f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(9.999f, hard), 0.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(10.0f, hard), 1.0f);
    // Off, and unbounded sides far from the origin.
    EXPECT_FLOAT_EQ(shading::bandWeight(1e7f, glm::vec4(0.0f, 0.0f, 0.0f, 0.0f)), 1.0f);
    const glm::vec4 open(-1e30f, 1e30f, 1e6f, 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(1e9f, open), 1.0f);
    EXPECT_FLOAT_EQ(shading::bandWeight(-1e9f, open), 1.0f);
}

TEST(TerrainLayers, NoiseStaysInTheUnitRangeAndRepeatsEvery256Cells)
{
    float lo = 1.0f, hi = 0.0f;
    for (int i = 0; i < 4000; ++i) {
        const glm::vec3 p(float(i) * 0.37f - 700.0f, float(i % 61) * 1.3f, float(i % 17) * -2.1f);
        const float v = shading::layerNoise(p, 9u);
        ASSERT_TRUE(v >= 0.0f && v <= 1.0f) << v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        // Exact binary fractions: the shifted point has the same cell fraction.
        const glm::vec3 q(float(i % 97) * 0.25f, float(i % 13) * 0.5f, float(i % 7) * 0.125f);
        EXPECT_EQ(shading::valueNoise(q, 3u), shading::valueNoise(q + glm::vec3(256.0f, -512.0f, 1024.0f), 3u));
    }
    EXPECT_LT(lo, 0.3f); // it varies
    EXPECT_GT(hi, 0.7f);
}

/// A sampler of constant maps: layer L, slot k returns value(L, k).
struct ConstantMaps
{
    mutable int layer = 0;
    mutable std::uint32_t features = feature::ALL & ~feature::LAYERS;
    glm::vec4 albedo[STRATA_MAX_LAYERS];
    float height[STRATA_MAX_LAYERS];

    glm::vec4 sample(int map, glm::vec2, glm::vec2, glm::vec2) const
    {
        if (map == shading::MAP_ALBEDO || map == shading::MAP_TOP_ALBEDO) return albedo[layer];
        if (map == shading::MAP_MASK || map == shading::MAP_TOP_MASK) return glm::vec4(0.0f, 1.0f, height[layer], 0.5f);
        if (map == shading::MAP_NORMAL || map == shading::MAP_TOP_NORMAL || map == shading::MAP_DETAIL_NORMAL)
            return glm::vec4(0.5f, 0.5f, 1.0f, 1.0f);
        if (map == shading::MAP_EMISSION) return glm::vec4(0.0f);
        return glm::vec4(0.5f);
    }
    void select(int index, std::uint32_t f) const
    {
        layer = index;
        features = f;
    }
};

struct LayerFixture
{
    ConstantMaps maps;
    shading::LayerSetParams set{};
    shading::SurfaceInput world{};

    explicit LayerFixture(int count)
    {
        Material base;
        set = strata::render::detail::makeLayerSet(base, glm::dvec3(0.0), feature::ALL);
        set.count = count;
        for (int i = 0; i < STRATA_MAX_LAYERS; ++i) {
            set.layers[i] = set.layers[0];
            set.layers[i].features = feature::MASK_MAP | feature::HEIGHT_BLEND;
            set.materials[i] = set.materials[0];
            set.materials[i].metallic = 1.0f;
            set.materials[i].smoothness = 1.0f;
            maps.albedo[i] = glm::vec4(float(i + 1) / 8.0f, 0.25f, 0.5f, 1.0f);
            maps.height[i] = 0.5f;
        }
        world.p = glm::vec3(1.3f, 2.0f, -0.7f);
        world.n = glm::vec3(0.0f, 1.0f, 0.0f);
        world.dpdx = glm::vec3(0.01f, 0.0f, 0.0f);
        world.dpdy = glm::vec3(0.0f, 0.0f, 0.01f);
        world.viewDir = glm::vec3(0.0f, 1.0f, 0.0f);
        world.detailOffset = glm::vec3(0.0f);
    }
    shading::SurfaceOutput evaluate(glm::vec2 surface = glm::vec2(0.0f), glm::vec4 landform = glm::vec4(0.0f),
                                    glm::vec2 rock = glm::vec2(0.0f)) const
    {
        return shading::evaluateLayers<feature::ALL, ConstantMaps>(maps, set, world, surface, landform, rock);
    }
    void cover(int i, float opacity) { set.layers[i].opacity = opacity; }
};

bool finite(const shading::SurfaceOutput& o)
{
    for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(o.albedo[c]) || !std::isfinite(o.normal[c])) return false;
    }
    return std::isfinite(o.metallic) && std::isfinite(o.smoothness) && std::isfinite(o.occlusion);
}

TEST(TerrainLayers, NoCoverageAnywhereGivesTheBaseNeverBlackOrNan)
{
    LayerFixture f(8);
    for (int i = 1; i < 8; ++i) f.cover(i, 0.0f);
    const shading::SurfaceOutput o = f.evaluate();
    ASSERT_TRUE(finite(o));
    EXPECT_FLOAT_EQ(o.albedo.x, f.maps.albedo[0].x);
    EXPECT_GT(o.albedo.x + o.albedo.y + o.albedo.z, 0.1f);
    EXPECT_NEAR(glm::length(o.normal), 1.0f, 1e-5f);
}

TEST(TerrainLayers, FullCoverageOfEveryLayerShowsTheTopOne)
{
    LayerFixture f(8);
    const shading::SurfaceOutput o = f.evaluate();
    ASSERT_TRUE(finite(o));
    EXPECT_FLOAT_EQ(o.albedo.x, f.maps.albedo[7].x);
}

TEST(TerrainLayers, OneLayerIsTheMaterialItself)
{
    LayerFixture f(1);
    const shading::SurfaceOutput layered = f.evaluate();
    shading::SurfaceInput s = f.world;
    s.p = f.world.p * f.set.layers[0].mapScale + glm::vec3(f.set.layers[0].textureOffset);
    s.dpdx *= f.set.layers[0].mapScale;
    s.dpdy *= f.set.layers[0].mapScale;
    f.maps.select(0, f.set.layers[0].features);
    const shading::SurfaceOutput single =
        shading::evaluateSurface<feature::ALL, ConstantMaps>(f.maps, s, f.set.materials[0]);
    EXPECT_FLOAT_EQ(layered.albedo.x, single.albedo.x);
    EXPECT_FLOAT_EQ(layered.smoothness, single.smoothness);
    EXPECT_FLOAT_EQ(layered.normal.y, single.normal.y);
}

TEST(TerrainLayers, HeightDecidesBetweenHalfCoveredLayers)
{
    LayerFixture f(2);
    f.cover(1, 0.5f); // base and layer 1 share equally
    f.set.blendDepth = 0.05f;
    f.maps.height[0] = 0.9f; // the base's rocks stand out...
    f.maps.height[1] = 0.4f;
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[0].x);
    f.maps.height[0] = 0.2f; // ...or the layer fills the gaps between them
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[1].x);
    // A large depth cross-fades by coverage alone.
    f.set.blendDepth = 100.0f;
    EXPECT_NEAR(f.evaluate().albedo.x, 0.5f * (f.maps.albedo[0].x + f.maps.albedo[1].x), 0.01f);
}

TEST(TerrainLayers, ALayerFadesInContinuouslyFromZeroCoverage)
{
    LayerFixture f(2);
    f.cover(1, 0.0f);
    f.maps.height[1] = 1.0f; // the highest possible height: still no pop
    f.set.blendDepth = 0.2f;
    float previous = f.evaluate().albedo.x;
    EXPECT_FLOAT_EQ(previous, f.maps.albedo[0].x);
    for (int step = 1; step <= 100; ++step) {
        f.cover(1, float(step) * 1e-4f);
        const float now = f.evaluate().albedo.x;
        EXPECT_LT(std::abs(now - previous), 0.01f) << step;
        previous = now;
    }
}

TEST(TerrainLayers, RulesReadSlopeAltitudeCavityAndCover)
{
    LayerFixture f(2);
    f.set.layers[1].slope = glm::vec4(0.0f, 30.0f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[1].x); // flat ground
    f.world.n = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));   // 45°
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[0].x);
    f.world.n = glm::vec3(0.0f, -1.0f, 0.0f); // a ceiling: 180°
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[0].x);
    f.world.n = glm::vec3(0.0f, 1.0f, 0.0f);
    f.set.layers[1].altitude = glm::vec4(100.0f, 1e30f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[0].x);
    f.world.p.y = 150.0f;
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, f.maps.albedo[1].x);
    f.set.layers[1].cover = glm::vec4(0.5f, 1.0f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(f.evaluate(glm::vec2(0.0f, 0.0f)).albedo.x, f.maps.albedo[0].x);
    EXPECT_FLOAT_EQ(f.evaluate(glm::vec2(0.0f, 1.0f)).albedo.x, f.maps.albedo[1].x);
    f.set.layers[1].cavity = glm::vec4(0.3f, 1.0f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(f.evaluate(glm::vec2(0.1f, 1.0f)).albedo.x, f.maps.albedo[0].x);
    EXPECT_FLOAT_EQ(f.evaluate(glm::vec2(0.6f, 1.0f)).albedo.x, f.maps.albedo[1].x);
}

TEST(TerrainLayers, RulesReadTheLandformMasks)
{
    LayerFixture f(2);
    const float layer = f.maps.albedo[1].x;
    const float base = f.maps.albedo[0].x;
    auto shown = [&f](glm::vec4 landform) { return f.evaluate(glm::vec2(0.0f), landform).albedo.x; };
    // Each band on its own component, the layer where it is at least
    // `from`: flow 10^5 m² (a river), wear 2 m, deposition 0.5 m, water ½.
    using shading::LayerParams;
    glm::vec4 LayerParams::*bands[4] = {&LayerParams::flow, &LayerParams::wear, &LayerParams::deposition,
                                        &LayerParams::water};
    const float from[4] = {5.0f, 2.0f, 0.5f, 0.5f};
    for (int k = 0; k < 4; ++k) {
        f.set.layers[1].*bands[k] = glm::vec4(from[k], 1e30f, 0.0f, 1.0f);
        EXPECT_FLOAT_EQ(f.evaluate().albedo.x, base) << k; // no landform reads 0
        glm::vec4 below(0.0f), at(0.0f), others(9.0f);
        below[k] = from[k] * 0.9f;
        at[k] = from[k];
        others[k] = 0.0f;
        EXPECT_FLOAT_EQ(shown(below), base) << k;
        EXPECT_FLOAT_EQ(shown(at), layer) << k;
        EXPECT_FLOAT_EQ(shown(others), base) << k; // only its own component counts
        (f.set.layers[1].*bands[k]).w = 0.0f;
    }
    // Every enabled band multiplies: wet (water) and worn (wear) together.
    f.set.layers[1].water = glm::vec4(0.5f, 1.0f, 0.0f, 1.0f);
    f.set.layers[1].wear = glm::vec4(2.0f, 1e30f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(shown(glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)), base);
    EXPECT_FLOAT_EQ(shown(glm::vec4(0.0f, 3.0f, 0.0f, 1.0f)), layer);
}

TEST(TerrainLayers, LandformBandsReachTheShaderAndItsChecks)
{
    Material m;
    MaterialLayer river;
    river.name = "river";
    river.rule.flow = {true, 5.0f, 8.0f, 0.5f};
    river.rule.water = {true, 0.2f, 1.0f, 0.1f};
    m.layers.push_back(river);
    EXPECT_TRUE(usesLandform(m.layers[0].rule));
    EXPECT_FALSE(usesLandform(LayerRule{}));
    const shading::LayerSetParams set = strata::render::detail::makeLayerSet(m, glm::dvec3(1e6), feature::ALL);
    EXPECT_EQ(set.layers[1].flow, glm::vec4(5.0f, 8.0f, 0.5f, 1.0f)); // not shifted by the origin
    EXPECT_EQ(set.layers[1].water, glm::vec4(0.2f, 1.0f, 0.1f, 1.0f));
    EXPECT_EQ(set.layers[1].wear.w, 0.0f);
    EXPECT_EQ(set.layers[0].flow.w, 0.0f);
    EXPECT_NO_THROW(checkMaterial(m));
    for (LayerBand LayerRule::*band : {&LayerRule::flow, &LayerRule::wear, &LayerRule::deposition, &LayerRule::water}) {
        Material bad = m;
        bad.layers[0].rule.*band = {true, 3.0f, 1.0f, 0.0f};
        EXPECT_THROW(checkMaterial(bad), strata::Error);
        bad.layers[0].rule.*band = {true, 0.0f, 1.0f, -1.0f};
        EXPECT_THROW(checkMaterial(bad), strata::Error);
    }
    m.layers[0].rule.deposition = {true, 3.0f, 1.0f, 0.0f};
    try {
        checkMaterial(m);
        FAIL() << "a deposition band with min > max was accepted";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("material layer 'river': deposition band"), std::string::npos) << e.what();
    }
}

TEST(TerrainLayers, LandformDebugRampsSpanTheirRanges)
{
    shading::SurfaceOutput o{};
    const glm::vec4 zero(0.0f);
    const glm::vec4 high(7.0f, 20.0f, 20.0f, 1.0f);
    for (int view : {shading::DEBUG_VIEW_FLOW, shading::DEBUG_VIEW_WEAR, shading::DEBUG_VIEW_DEPOSITION,
                     shading::DEBUG_VIEW_WATER}) {
        const glm::vec3 lo = shading::fragmentDebugColor(o, zero, glm::vec2(0.0f), view);
        const glm::vec3 hi = shading::fragmentDebugColor(o, high, glm::vec2(0.0f), view);
        EXPECT_GT(glm::length(hi - lo), 0.5f) << view;
        // Clamped beyond the range; brighter with more.
        EXPECT_EQ(shading::fragmentDebugColor(o, high * 3.0f, glm::vec2(0.0f), view), hi) << view;
        EXPECT_EQ(shading::fragmentDebugColor(o, -high, glm::vec2(0.0f), view), lo) << view;
        EXPECT_GT(hi.x + hi.y + hi.z, lo.x + lo.y + lo.z) << view;
        // Only its own component counts, and the rock masks not at all.
        glm::vec4 others = high;
        others[view - shading::DEBUG_VIEW_FLOW] = 0.0f;
        EXPECT_EQ(shading::fragmentDebugColor(o, others, glm::vec2(1.0f, 3.0f), view), lo) << view;
    }
    // The material's views are debugViewColor()'s.
    o.metallic = 0.5f;
    EXPECT_EQ(shading::fragmentDebugColor(o, high, glm::vec2(1.0f, 3.0f), shading::DEBUG_VIEW_METALLIC),
              shading::debugViewColor(o, shading::DEBUG_VIEW_METALLIC));
}

TEST(TerrainLayers, RockDebugViewsShowHardnessAndEachBed)
{
    shading::SurfaceOutput o{};
    const glm::vec4 landform(7.0f, 20.0f, 20.0f, 1.0f); // read by the landform views only
    auto colour = [&](glm::vec2 rock, int view) { return shading::fragmentDebugColor(o, landform, rock, view); };
    // Hardness: a ramp over 0..1, clamped, brighter when harder; the bed does not count.
    const glm::vec3 soft = colour({0.0f, 0.0f}, shading::DEBUG_VIEW_HARDNESS);
    const glm::vec3 hard = colour({1.0f, 0.0f}, shading::DEBUG_VIEW_HARDNESS);
    EXPECT_GT(glm::length(hard - soft), 0.5f);
    EXPECT_GT(hard.x + hard.y + hard.z, soft.x + soft.y + soft.z);
    EXPECT_EQ(colour({2.0f, 0.0f}, shading::DEBUG_VIEW_HARDNESS), hard);
    EXPECT_EQ(colour({-1.0f, 0.0f}, shading::DEBUG_VIEW_HARDNESS), soft);
    EXPECT_EQ(colour({1.0f, 5.0f}, shading::DEBUG_VIEW_HARDNESS), hard);
    // Bed: one colour per index (a vertex between two beds rounds to the
    // nearer), neighbouring beds clearly apart, the hardness not read.
    std::vector<glm::vec3> beds;
    for (int bed = 0; bed < 6; ++bed) {
        const glm::vec3 c = colour({0.3f, float(bed)}, shading::DEBUG_VIEW_BED);
        EXPECT_EQ(colour({0.9f, float(bed) + 0.45f}, shading::DEBUG_VIEW_BED), c) << bed;
        EXPECT_EQ(colour({0.9f, float(bed) - 0.45f}, shading::DEBUG_VIEW_BED), c) << bed;
        beds.push_back(c);
    }
    for (std::size_t i = 1; i < beds.size(); ++i) EXPECT_GT(glm::length(beds[i] - beds[i - 1]), 0.15f) << i;
    // At 0 the two rock views differ from each other and from every landform view.
    for (int view : {shading::DEBUG_VIEW_FLOW, shading::DEBUG_VIEW_WEAR, shading::DEBUG_VIEW_DEPOSITION,
                     shading::DEBUG_VIEW_WATER, shading::DEBUG_VIEW_BED}) {
        EXPECT_GT(glm::length(shading::fragmentDebugColor(o, glm::vec4(0.0f), glm::vec2(0.0f), view) - soft), 0.05f)
            << view;
    }
}

TEST(TerrainLayers, RulesReadTheRockMasks)
{
    LayerFixture f(2);
    const float layer = f.maps.albedo[1].x;
    const float base = f.maps.albedo[0].x;
    auto shown = [&f](glm::vec2 rock) { return f.evaluate(glm::vec2(0.0f), glm::vec4(9.0f), rock).albedo.x; };
    // Hardness: the layer on hard rock (>= 0.7).
    f.set.layers[1].hardness = glm::vec4(0.7f, 1e30f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(f.evaluate().albedo.x, base); // no rock reads 0
    EXPECT_FLOAT_EQ(shown({0.6f, 0.0f}), base);
    EXPECT_FLOAT_EQ(shown({0.7f, 0.0f}), layer);
    EXPECT_FLOAT_EQ(shown({0.0f, 9.0f}), base); // only its own component counts
    f.set.layers[1].hardness.w = 0.0f;
    // Bed: the layer on bed 2 alone, ramps half a bed wide.
    f.set.layers[1].bed = glm::vec4(2.0f, 2.0f, 0.5f, 1.0f);
    EXPECT_FLOAT_EQ(shown({0.0f, 1.0f}), base);
    EXPECT_FLOAT_EQ(shown({0.0f, 2.0f}), layer);
    EXPECT_FLOAT_EQ(shown({0.0f, 3.0f}), base);
    EXPECT_FLOAT_EQ(shown({1.0f, 1.0f}), base);
    // Both bands multiply: bed 2 where it is hard.
    f.set.layers[1].hardness = glm::vec4(0.7f, 1e30f, 0.0f, 1.0f);
    EXPECT_FLOAT_EQ(shown({0.9f, 2.0f}), layer);
    EXPECT_FLOAT_EQ(shown({0.1f, 2.0f}), base);
    EXPECT_FLOAT_EQ(shown({0.9f, 3.0f}), base);
}

TEST(TerrainLayers, ExtremeInputsStayFinite)
{
    LayerFixture f(4);
    f.set.blendDepth = 1e-3f;
    f.cover(1, 0.5f);
    f.set.layers[2].noise = glm::vec4(1000.0f, 0.5f, 0.0f, 1.0f);
    f.set.layers[3].slope = glm::vec4(-1e30f, 1e30f, 1e6f, 1.0f);
    f.set.layers[2].flow = glm::vec4(0.0f, 7.0f, 0.5f, 1.0f);
    const glm::vec3 normals[] = {glm::vec3(0.0f), glm::vec3(1e-30f, 0.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f),
                                 glm::normalize(glm::vec3(1.0f))};
    for (const glm::vec3& n : normals) {
        f.world.n = n;
        for (float y : {-1e9f, 0.0f, 1e9f}) {
            f.world.p = glm::vec3(1e7f, y, -1e7f);
            EXPECT_TRUE(finite(f.evaluate(glm::vec2(1.0f, 1.0f), glm::vec4(1e30f, -1e30f, 1e9f, 1.0f)))) << y;
        }
    }
}

// ---------------------------------------------------------------------------
// Texture arrays and checks.

TexturePtr solid(int size, std::uint8_t value, MapKind kind)
{
    Image image;
    image.width = size;
    image.height = size;
    image.pixels.assign(std::size_t(size * size * 4), value);
    return makeTexture(image, kind);
}

TEST(TerrainLayers, LayerMapsShareOneSizePerSlot)
{
    Material m;
    m.albedo = solid(64, 90, MapKind::Albedo);
    MaterialLayer grass;
    grass.name = "grass";
    grass.material.albedo = solid(128, 160, MapKind::Albedo); // a mip level of it is 64²
    grass.material.normal = solid(32, 128, MapKind::Normal);
    m.layers.push_back(grass);
    const strata::render::detail::LayerMaps maps = strata::render::detail::resolveLayerMaps(m);
    ASSERT_EQ(maps.layerCount, 2);
    for (const auto& slot : maps.slots) {
        ASSERT_EQ(slot.size(), 2u);
        EXPECT_EQ(slot[0]->width(), slot[1]->width());
        EXPECT_EQ(slot[0]->levels.size(), slot[1]->levels.size());
    }
    EXPECT_EQ(maps.slots[0][1]->width(), 64);
    EXPECT_EQ(maps.slots[0][1]->levels[0].texels[0], 160);
    EXPECT_EQ(maps.slots[2][0]->width(), 32); // the base's flat stand-in at the slot's size
    EXPECT_EQ(maps.slots[2][0]->levels[0].texels[2], 255);
    // While in use, the same material resolves to the same texture objects
    // (the GL renderer then keeps its texture arrays between setMaterial calls).
    const strata::render::detail::LayerMaps again = strata::render::detail::resolveLayerMaps(m);
    for (std::size_t k = 0; k < 9; ++k) EXPECT_EQ(again.slots[k], maps.slots[k]) << k;

    m.layers[0].material.albedo = solid(100, 160, MapKind::Albedo);
    try {
        strata::render::detail::resolveLayerMaps(m);
        FAIL() << "sizes without a common mip level were accepted";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("layer 'grass' map albedo is 100x100"), std::string::npos) << e.what();
    }
    EXPECT_THROW(checkMaterial(m), strata::Error); // found before any texture is built
}

TEST(TerrainLayers, CheckMaterialNamesTheLayerAndTheKey)
{
    Material m;
    auto expectError = [&](const std::string& part) {
        try {
            checkMaterial(m);
            FAIL() << "accepted; expected " << part;
        } catch (const strata::Error& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    MaterialLayer snow;
    snow.name = "snow";
    snow.rule.altitude.enabled = true;
    snow.rule.altitude.min = 200.0f;
    snow.rule.altitude.max = 100.0f;
    m.layers.push_back(snow);
    expectError("material layer 'snow': altitude band");
    m.layers[0].rule.altitude.max = 300.0f;
    EXPECT_NO_THROW(checkMaterial(m));
    m.layers[0].rule.opacity = 2.0f;
    expectError("material layer 'snow': opacity");
    m.layers[0].rule.opacity = 1.0f;
    m.layers[0].material.layers.push_back(snow);
    expectError("layers cannot have layers");
    m.layers[0].material.layers.clear();
    m.layers.assign(8, m.layers[0]);
    expectError("8 layers over the base; at most 7");
    m.layers.resize(7);
    EXPECT_NO_THROW(checkMaterial(m));
    m.layerBlendDepth = 0.0f;
    expectError("layerBlendDepth");
}

TEST(TerrainLayers, FeatureSetsAreTheUnionAndEachLayersOwn)
{
    Material m = strata::test::circuitryMaterial("mohs-height");
    EXPECT_EQ(materialFeatures(m) & feature::LAYERS, 0u);
    MaterialLayer layer;
    layer.material = strata::test::circuitryMaterial("normal-rnm");
    layer.material.maskLayout = MaskLayout::Mods;
    m.layers.push_back(layer);
    const std::uint32_t all = materialFeatures(m);
    EXPECT_TRUE(all & feature::LAYERS);
    EXPECT_TRUE(all & feature::HEIGHT_BLEND); // the base's, kept beside the layer's MODS
    EXPECT_TRUE(all & feature::MODS);
    EXPECT_TRUE(all & feature::NORMAL_RNM);
    EXPECT_EQ(layerFeatures(m, 0), feature::MASK_MAP | feature::HEIGHT_BLEND);
    EXPECT_EQ(layerFeatures(m, 1), feature::MASK_MAP | feature::MODS | feature::NORMAL_MAP | feature::NORMAL_RNM);
    // Switching LAYERS off renders the base alone.
    EXPECT_EQ(effectiveFeatures(m, ~feature::LAYERS), layerFeatures(m, 0));
}

// ---------------------------------------------------------------------------
// GL against the CPU.

EglContext& context()
{
    static std::unique_ptr<EglContext> shared = EglContext::create();
    return *shared;
}

/// A ground slab with a block standing on it: flat tops, walls, one mesh.
TestMesh groundWithBlock()
{
    TestMesh mesh = strata::test::makeBox(glm::vec3(-4.0f, -1.0f, -4.0f), glm::vec3(4.0f, 0.0f, 4.0f));
    const TestMesh block = strata::test::makeBox(glm::vec3(-1.5f, 0.0f, -1.5f), glm::vec3(1.5f, 2.5f, 1.5f));
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), block.positions.begin(), block.positions.end());
    mesh.normals.insert(mesh.normals.end(), block.normals.begin(), block.normals.end());
    for (std::uint32_t i : block.indices) mesh.indices.push_back(base + i);
    return mesh;
}

/// Four layers of different feature sets: circuitry (full) everywhere,
/// grass (albedo + MOHS) on flat ground by a noise mask, MODS + RNM rock on
/// the walls, snow (albedo only) above 2 m. `lift` is added to the rules'
/// altitudes (for meshes moved up with their origin).
Material fourLayers(double lift = 0.0)
{
    Material m = strata::test::circuitryMaterial("full");
    MaterialLayer grass;
    grass.name = "grass";
    grass.material.albedo = makeTexture(strata::test::grass().albedo, MapKind::Albedo);
    grass.material.mask = makeTexture(strata::test::grass().mohs, MapKind::Mask);
    grass.material.mapScale = 0.25f;
    grass.material.albedoTint = glm::vec3(1.4f, 1.1f, 0.3f); // dry grass, unlike the base's top maps
    grass.rule.slope = {true, 0.0f, 30.0f, 10.0f};
    grass.rule.noiseFrequency = 0.5f;
    grass.rule.noiseThreshold = 0.45f;
    grass.rule.noiseSoftness = 0.2f;
    grass.rule.noiseSeed = 4;
    MaterialLayer rock;
    rock.name = "rock";
    rock.material = strata::test::circuitryMaterial("normal-rnm");
    rock.material.maskLayout = MaskLayout::Mods;
    rock.material.albedoTint = glm::vec3(0.7f, 0.6f, 0.5f);
    rock.rule.slope = {true, 60.0f, 120.0f, 20.0f};
    rock.rule.opacity = 0.8f;
    MaterialLayer snow;
    snow.name = "snow";
    snow.material.albedoTint = glm::vec3(1.2f);
    snow.rule.altitude = {true, float(lift + 2.0), std::numeric_limits<float>::infinity(), 0.5f};
    m.layers = {grass, rock, snow};
    m.layerBlendDepth = 0.15f;
    return m;
}

SnapshotOptions layerOptions(const TestMesh& mesh, glm::dvec3 origin = glm::dvec3(0.0))
{
    SnapshotOptions options = strata::test::goldenOptions(mesh, "albedo", 480, 270);
    options.camera.position += origin;
    options.camera.target += origin;
    options.material = fourLayers(origin.y);
    return options;
}

TEST(TerrainLayers, GlMatchesTheCpuWithFourLayersOfDifferentFeatureSets)
{
    const TestMesh mesh = groundWithBlock();
    const SnapshotOptions options = layerOptions(mesh);
    CpuRenderStats stats;
    const Image cpu = renderSnapshotCpu(mesh.view(), options, &stats);
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    const double p = psnr(gl, cpu);
    const double within = fractionWithin(gl, cpu, 2);
    std::cout << "[ layers   ] GL vs CPU, four layers: " << within * 100.0 << "% within 2/255, "
              << double(stats.textureFetches) / double(stats.shadedPixels) << " fetches per shaded pixel"
              << std::endl;
    STRATA_EXPECT_PARITY(p, 55.95, "four layers"); // measured 55.95 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    EXPECT_GE(within, 0.99);
    // The naive count is of every layer's maps: a layered render fetches no
    // more than it (it counted the base's only, and reported 1.7e14 % skipped).
    EXPECT_GT(stats.textureFetches, 0u);
    EXPECT_LE(stats.textureFetches, stats.naiveFetches);
    // Each layer shows somewhere: switching one off changes the image.
    for (std::size_t off = 0; off < options.material.layers.size(); ++off) {
        SnapshotOptions less = options;
        less.material.layers[off].rule.opacity = 0.0f;
        EXPECT_LT(psnr(renderSnapshotCpu(mesh.view(), less), cpu), 40.0) << options.material.layers[off].name;
    }
    if (!(p >= strata::test::parityFloor(55.95) && within >= 0.99)) {
        const auto dir = strata::test::freshTestDir();
        writeImage(gl, dir / "layers-gl.png");
        writeImage(cpu, dir / "layers-cpu.png");
        std::cout << "  wrote " << dir.string() << std::endl;
    }
}

TEST(TerrainLayers, FarFromTheOriginTheImageIsTheSame)
{
    // Origins that are whole periods of the textures (2 m, 4 m) and of the
    // noise (256 cells of 2 m): the world looks the same from there.
    const TestMesh mesh = groundWithBlock();
    const Image near = renderSnapshotCpu(mesh.view(), layerOptions(mesh));
    for (double offset : {1024.0, 131072.0, 8388608.0}) {
        const glm::dvec3 origin(offset, offset, -offset);
        TestMesh moved = mesh;
        strata::render::MeshView view = moved.view();
        view.origin = origin;
        const Image cpu = renderSnapshotCpu(view, layerOptions(mesh, origin));
        EXPECT_GE(psnr(cpu, near), 60.0) << offset;
        if (offset == 8388608.0) {
            const Image gl = renderSnapshot(context(), view, layerOptions(mesh, origin));
            // Measured 55.95 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
            STRATA_EXPECT_PARITY(psnr(gl, cpu), 55.95, "four layers 8388608 m away");
        }
    }
}

TEST(TerrainLayers, SurfaceAttributesReachTheRulesOnBothRenderers)
{
    // Cover 1 on the block's vertices: the "cave" layer paints the block only.
    const TestMesh mesh = groundWithBlock();
    std::vector<glm::vec2> surface(mesh.positions.size(), glm::vec2(0.0f));
    for (std::size_t i = 24; i < surface.size(); ++i) surface[i] = glm::vec2(0.0f, 1.0f);
    strata::render::MeshView view = mesh.view();
    SnapshotOptions options = strata::test::goldenOptions(mesh, "albedo", 320, 180);
    MaterialLayer cave;
    cave.name = "cave";
    cave.material.albedoTint = glm::vec3(0.05f, 0.05f, 0.9f);
    cave.rule.cover = {true, 0.5f, 1.0f, 0.0f};
    options.material.layers.push_back(cave);
    const Image without = renderSnapshotCpu(view, options);
    view.surface = surface.data();
    const Image cpu = renderSnapshotCpu(view, options);
    const Image gl = renderSnapshot(context(), view, options);
    EXPECT_LT(psnr(cpu, without), 30.0);
    // Measured 58.03 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(psnr(gl, cpu), 58.03, "surface attributes");
    if (psnr(gl, cpu) < strata::test::parityFloor(58.03)) {
        const auto dir = strata::test::freshTestDir();
        writeImage(gl, dir / "surface-gl.png");
        writeImage(cpu, dir / "surface-cpu.png");
        writeImage(without, dir / "surface-without.png");
        std::cout << "  wrote " << dir.string() << std::endl;
    }
    // The centre of the image is the block: blue there.
    const std::uint8_t* centre = cpu.at(160, 90);
    EXPECT_GT(centre[2], centre[0] + 40);
}

} // namespace

namespace {

TEST(TerrainLayers, TheLayersDebugViewShowsWhereEachLayerIs)
{
    const TestMesh mesh = groundWithBlock();
    SnapshotOptions options = layerOptions(mesh);
    options.debugView = DebugView::Layers;
    const Image cpu = renderSnapshotCpu(mesh.view(), options);
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    // Measured 70.46 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(psnr(gl, cpu), 70.46, "layers debug view");
    // The block's top (above 2 m) is snow, layer 3: blue.
    const glm::dvec3 top(0.0, 2.5, 0.0);
    const glm::dvec4 clip = glm::dmat4(projectionMatrix(options.camera, 480.0 / 270.0)) *
                            glm::dmat4(viewMatrix(options.camera, glm::dvec3(0.0))) * glm::dvec4(top, 1.0);
    const int x = int((clip.x / clip.w * 0.5 + 0.5) * 480.0);
    const int y = int((0.5 - clip.y / clip.w * 0.5) * 270.0) + 2; // just below the top face's centre line
    const std::uint8_t* p = cpu.at(x, y);
    EXPECT_GT(p[2], p[0] + 60) << x << "," << y;
    EXPECT_GT(p[2], p[1] + 30) << x << "," << y;
    // Switching LAYERS off shows the base's colour everywhere on the terrain.
    options.featureMask = ~feature::LAYERS;
    const Image base = renderSnapshotCpu(mesh.view(), options);
    const std::uint8_t* q = base.at(x, y);
    EXPECT_NEAR(q[0], q[2], 2);
}

/// groundWithBlock()'s landform: `block` on the block's vertices (from 24
/// on), `ground` on the slab's.
std::vector<glm::vec4> blockLandform(const TestMesh& mesh, glm::vec4 ground, glm::vec4 block)
{
    std::vector<glm::vec4> landform(mesh.positions.size(), ground);
    for (std::size_t i = 24; i < landform.size(); ++i) landform[i] = block;
    return landform;
}

/// The pixel where world point `p` projects (mesh origin 0).
glm::ivec2 projectPixel(const SnapshotOptions& options, const glm::dvec3& p)
{
    const glm::dvec4 clip = glm::dmat4(projectionMatrix(options.camera, double(options.width) / options.height)) *
                            glm::dmat4(viewMatrix(options.camera, glm::dvec3(0.0))) * glm::dvec4(p, 1.0);
    return {int((clip.x / clip.w * 0.5 + 0.5) * options.width), int((0.5 - clip.y / clip.w * 0.5) * options.height)};
}

/// groundWithBlock()'s block top centre (just below, inside the face) and
/// the ground between the block and the camera.
std::pair<glm::ivec2, glm::ivec2> blockAndGroundPixels(const SnapshotOptions& options)
{
    const glm::dvec3 towards = glm::normalize(glm::dvec3(options.camera.position.x, 0.0, options.camera.position.z));
    return {projectPixel(options, glm::dvec3(0.0, 2.5, 0.0)) + glm::ivec2(0, 2), projectPixel(options, towards * 3.0)};
}

void writeOnFailure(bool failed, const std::string& name, const Image& gl, const Image& cpu)
{
    if (!failed) return;
    const auto dir = strata::test::freshTestDir();
    writeImage(gl, dir / (name + "-gl.png"));
    writeImage(cpu, dir / (name + "-cpu.png"));
    std::cout << "  wrote " << dir.string() << std::endl;
}

TEST(TerrainLayers, LandformReachesTheRulesOnBothRenderers)
{
    // Flow 6 (a river's drainage area) on the block, 1 on the ground: the
    // "river" layer (flow >= 5) paints the block only.
    const TestMesh mesh = groundWithBlock();
    const std::vector<glm::vec4> landform =
        blockLandform(mesh, glm::vec4(1.0f, 0.0f, 0.0f, 0.0f), glm::vec4(6.0f, 0.0f, 0.0f, 0.0f));
    strata::render::MeshView view = mesh.view();
    SnapshotOptions options = strata::test::goldenOptions(mesh, "albedo", 320, 180);
    const Image plain = renderSnapshotCpu(view, options);
    MaterialLayer river;
    river.name = "river";
    river.material.albedoTint = glm::vec3(0.05f, 0.05f, 0.9f);
    river.rule.flow = {true, 5.0f, std::numeric_limits<float>::infinity(), 0.5f};
    options.material.layers.push_back(river);
    // No landform reads 0: the layer shows nowhere.
    const Image without = renderSnapshotCpu(view, options);
    const Image withoutGl = renderSnapshot(context(), view, options);
    EXPECT_GE(psnr(without, plain), 60.0);
    // Measured 56.13 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(psnr(withoutGl, without), 56.13, "no landform");
    // With the surface attributes too: the landform follows them in GL's vertex buffer.
    const std::vector<glm::vec2> surface(mesh.positions.size(), glm::vec2(0.7f, 1.0f));
    view.surface = surface.data();
    view.landform = landform.data();
    const Image cpu = renderSnapshotCpu(view, options);
    const Image gl = renderSnapshot(context(), view, options);
    const double p = psnr(gl, cpu);
    EXPECT_LT(psnr(cpu, without), 30.0);
    STRATA_EXPECT_PARITY(p, 58.03, "landform flow band"); // measured 58.03 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    EXPECT_GE(fractionWithin(gl, cpu, 2), 0.99);
    writeOnFailure(p < strata::test::parityFloor(58.03), "landform", gl, cpu);
    // The block is blue, the ground in front of it is not.
    const auto [block, front] = blockAndGroundPixels(options);
    const std::uint8_t* top = cpu.at(block.x, block.y);
    EXPECT_GT(top[2], top[0] + 40);
    const std::uint8_t* ground = cpu.at(front.x, front.y);
    EXPECT_LT(ground[2], ground[0] + 40);
    EXPECT_NEAR(int(ground[2]), int(without.at(front.x, front.y)[2]), 2);
}

TEST(TerrainLayers, RockReachesTheRulesOnBothRenderers)
{
    // Hard rock (0.9) of bed 3 on the block, soft (0.2) of bed 1 on the
    // ground: the "caprock" layer (hardness >= 0.6, bed 3) paints the block
    // only. The rock masks alone (no surface or landform attributes): GL
    // finds them at their own place in the vertex buffer.
    const TestMesh mesh = groundWithBlock();
    std::vector<glm::vec2> rock(mesh.positions.size(), glm::vec2(0.2f, 1.0f));
    for (std::size_t i = 24; i < rock.size(); ++i) rock[i] = glm::vec2(0.9f, 3.0f);
    strata::render::MeshView view = mesh.view();
    SnapshotOptions options = strata::test::goldenOptions(mesh, "albedo", 320, 180);
    const Image plain = renderSnapshotCpu(view, options);
    MaterialLayer caprock;
    caprock.name = "caprock";
    caprock.material.albedoTint = glm::vec3(0.9f, 0.3f, 0.05f);
    caprock.rule.hardness = {true, 0.6f, std::numeric_limits<float>::infinity(), 0.1f};
    caprock.rule.bed = {true, 3.0f, 3.0f, 0.5f};
    options.material.layers.push_back(caprock);
    EXPECT_TRUE(usesRock(caprock.rule));
    EXPECT_FALSE(usesLandform(caprock.rule));
    // No rock reads 0: the layer shows nowhere.
    const Image without = renderSnapshotCpu(view, options);
    EXPECT_GE(psnr(without, plain), 60.0);
    view.rock = rock.data();
    const Image cpu = renderSnapshotCpu(view, options);
    const Image gl = renderSnapshot(context(), view, options);
    const double p = psnr(gl, cpu);
    EXPECT_LT(psnr(cpu, without), 30.0);
    STRATA_EXPECT_PARITY(p, 58.03, "rock hardness and bed bands"); // measured 58.03 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    EXPECT_GE(fractionWithin(gl, cpu, 2), 0.99);
    writeOnFailure(p < strata::test::parityFloor(58.03), "rock", gl, cpu);
    // The block is orange, the ground in front of it is not.
    const auto [block, front] = blockAndGroundPixels(options);
    const std::uint8_t* top = cpu.at(block.x, block.y);
    EXPECT_GT(top[0], top[2] + 40);
    EXPECT_NEAR(int(cpu.at(front.x, front.y)[0]), int(without.at(front.x, front.y)[0]), 2);
    // The rock debug views show the masks: hard and soft, bed 3 and bed 1.
    for (DebugView v : {DebugView::Hardness, DebugView::Bed}) {
        options.debugView = v;
        ASSERT_TRUE(isRockView(v));
        const Image debugCpu = renderSnapshotCpu(view, options);
        const Image debugGl = renderSnapshot(context(), view, options);
        EXPECT_GE(fractionWithin(debugGl, debugCpu, 2), 0.99) << debugViewName(v);
        const glm::vec3 expected = shading::rockDebugColor(rock.back(), int(v));
        const std::uint8_t* a = debugCpu.at(block.x, block.y);
        EXPECT_NEAR(a[0], std::lround(shading::linearToSrgb(expected.r) * 255.0f), 3) << debugViewName(v);
        EXPECT_NEAR(a[1], std::lround(shading::linearToSrgb(expected.g) * 255.0f), 3) << debugViewName(v);
        const std::uint8_t* b = debugCpu.at(front.x, front.y);
        EXPECT_GT(std::abs(int(a[0]) - int(b[0])) + std::abs(int(a[1]) - int(b[1])) + std::abs(int(a[2]) - int(b[2])), 40)
            << debugViewName(v);
    }
    EXPECT_STREQ(debugViewName(DebugView::Hardness), "hardness");
    EXPECT_STREQ(debugViewName(DebugView::Bed), "bed");
}

TEST(TerrainLayers, AnAbsentLandformReadsZeroOnGlToo)
{
    // GL's constant for a disabled attribute is (0, 0, 0, 1): the renderer
    // must set water 0 itself, or a "dry" layer (water <= 0.5) would vanish.
    const TestMesh mesh = groundWithBlock();
    SnapshotOptions options = strata::test::goldenOptions(mesh, "albedo", 160, 90);
    const Image plain = renderSnapshotCpu(mesh.view(), options);
    MaterialLayer dry;
    dry.name = "dry";
    dry.material.albedoTint = glm::vec3(0.9f, 0.1f, 0.05f);
    dry.rule.water = {true, -std::numeric_limits<float>::infinity(), 0.5f, 0.0f};
    options.material.layers.push_back(dry);
    const Image cpu = renderSnapshotCpu(mesh.view(), options);
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    EXPECT_LT(psnr(cpu, plain), 30.0); // the dry layer shows
    // Measured 64.75 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(psnr(gl, cpu), 64.75, "absent landform, dry layer");
    const std::uint8_t* centre = gl.at(80, 45);
    EXPECT_GT(centre[0], centre[2] + 40);
}

TEST(TerrainLayers, LandformDebugViewsShowTheMasksOnBothRenderers)
{
    const TestMesh mesh = groundWithBlock();
    const std::vector<glm::vec4> landform =
        blockLandform(mesh, glm::vec4(1.0f, 2.0f, 0.5f, 0.0f), glm::vec4(6.5f, 15.0f, 12.0f, 1.0f));
    strata::render::MeshView view = mesh.view();
    view.landform = landform.data();
    SnapshotOptions options = layerOptions(mesh);
    options.width = 240;
    options.height = 135;
    const auto [top, ground] = blockAndGroundPixels(options);
    std::vector<Image> images;
    // Each view's PSNR measured on llvmpipe/EGL, AMD EPYC (Parity.h).
    const std::map<DebugView, double> measuredDb = {
        {DebugView::Flow, 63.14}, {DebugView::Wear, 63.14}, {DebugView::Deposition, 59.33}, {DebugView::Water, 63.76}};
    for (DebugView v : {DebugView::Flow, DebugView::Wear, DebugView::Deposition, DebugView::Water}) {
        options.debugView = v;
        ASSERT_TRUE(isLandformView(v));
        const Image cpu = renderSnapshotCpu(view, options);
        const Image gl = renderSnapshot(context(), view, options);
        const double p = psnr(gl, cpu);
        STRATA_EXPECT_PARITY(p, measuredDb.at(v), std::string("debug view ") + debugViewName(v)); // values above
        writeOnFailure(p < strata::test::parityFloor(measuredDb.at(v)), debugViewName(v), gl, cpu);
        // More of the mask on the block: brighter there than on the ground.
        const std::uint8_t* a = cpu.at(top.x, top.y);
        const std::uint8_t* b = cpu.at(ground.x, ground.y);
        EXPECT_GT(a[0] + a[1] + a[2], b[0] + b[1] + b[2] + 60) << debugViewName(v);
        // The colour is the ramp's, whatever the material.
        const glm::vec3 expected = shading::landformDebugColor(landform.back(), int(v));
        EXPECT_NEAR(a[0], std::lround(shading::linearToSrgb(expected.r) * 255.0f), 3) << debugViewName(v);
        EXPECT_NEAR(a[2], std::lround(shading::linearToSrgb(expected.b) * 255.0f), 3) << debugViewName(v);
        images.push_back(cpu);
    }
    for (std::size_t i = 0; i < images.size(); ++i) {
        for (std::size_t j = i + 1; j < images.size(); ++j) EXPECT_LT(psnr(images[i], images[j]), 30.0) << i << j;
    }
    EXPECT_STREQ(debugViewName(DebugView::Deposition), "deposition");
}

} // namespace
