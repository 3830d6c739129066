// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Headless rendering through EGL. These tests must run (CI has Mesa's
// llvmpipe): a machine where no context can be created fails them.

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/GlfwContext.h>
#include <strata/render/ProceduralTextures.h>

#include "ShadingPrelude.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include "TestContext.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <set>
#include <string>

namespace {

using namespace strata::render;
using strata::test::TestMesh;

using strata::test::createContext;

int srgbByte(float linear)
{
    const float c = linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    return int(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

bool isSky(const Image& image, int x, int y, const glm::vec3& sky)
{
    const std::uint8_t* p = image.at(x, y);
    return std::abs(p[0] - srgbByte(sky.r)) <= 1 && std::abs(p[1] - srgbByte(sky.g)) <= 1 &&
           std::abs(p[2] - srgbByte(sky.b)) <= 1;
}

Image solid(int r, int g, int b, int a = 255)
{
    Image image;
    image.width = 4;
    image.height = 4;
    for (int i = 0; i < 16; ++i) {
        image.pixels.insert(image.pixels.end(), {std::uint8_t(r), std::uint8_t(g), std::uint8_t(b), std::uint8_t(a)});
    }
    return image;
}

TEST(EglContext, CreatesAnOpenGlCoreContextHeadless)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    EXPECT_NE(context->description().find("via EGL"), std::string::npos) << context->description();
    std::cout << "EGL context: " << context->description() << std::endl;
    ::testing::Test::RecordProperty("egl_context", context->description());
    context->makeCurrent();
    context->makeCurrent();
}

TEST(EglContext, TwoContextsLiveTogetherAndOutliveEachOther)
{
    auto first = createContext();
    auto second = createContext();
    ASSERT_TRUE(first && second);
    first.reset(); // must not terminate the display the second one uses
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 32;
    options.height = 32;
    options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 30.0, 20.0);
    const Image image = renderSnapshot(*second, box.view(), options);
    EXPECT_FALSE(isSky(image, 16, 16, options.lighting.skyColor));
}

TEST(GlRenderer, RendersATexturedSphereOverTheSky)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(0.0f), 4.0f, 64, 32);
    SnapshotOptions options;
    options.width = 256;
    options.height = 256;
    options.camera = orbitCamera(glm::dvec3(-4.0), glm::dvec3(4.0), 30.0, 25.0);
    options.material.mapScale = 0.25f;
    options.material.albedo = makeTexture(makeRockAlbedo(256, 1), MapKind::Albedo);
    options.material.topAlbedo = makeTexture(makeGrassAlbedo(256, 1), MapKind::Albedo);

    const Image image = renderSnapshot(*context, sphere.view(), options);
    ASSERT_EQ(image.width, 256);
    ASSERT_EQ(image.height, 256);
    ASSERT_EQ(image.pixels.size(), 256u * 256u * 4u);
    writeImage(image, strata::test::freshTestDir() / "sphere.png");

    const glm::vec3 sky = options.lighting.skyColor;
    EXPECT_TRUE(isSky(image, 0, 0, sky)) << "corner is not the sRGB-encoded sky colour";
    EXPECT_TRUE(isSky(image, 255, 255, sky));
    EXPECT_FALSE(isSky(image, 128, 128, sky)) << "centre pixel is sky";

    int object = 0;
    int minLuma = 255;
    int maxLuma = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            EXPECT_EQ(image.at(x, y)[3], 255);
            if (isSky(image, x, y, sky)) {
                continue;
            }
            ++object;
            const std::uint8_t* p = image.at(x, y);
            const int luma = (p[0] * 3 + p[1] * 6 + p[2]) / 10;
            minLuma = std::min(minLuma, luma);
            maxLuma = std::max(maxLuma, luma);
        }
    }
    // The sphere's silhouette covers π·r² of the frame's 2r/sin(25°)-high view.
    EXPECT_GT(object, 256 * 256 / 8);
    EXPECT_LT(object, 256 * 256 * 3 / 4);
    EXPECT_GT(maxLuma - minLuma, 40) << "the sphere is flat-coloured";
}

TEST(GlRenderer, TopMapOnlyOnUpwardFaces)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 128;
    options.height = 128;
    options.material.albedo = makeTexture(solid(200, 30, 30), MapKind::Albedo);
    options.material.topAlbedo = makeTexture(solid(30, 200, 30), MapKind::Albedo);
    options.material.blendOffset = 0.0f;
    options.material.blendExponent = 1.0f;

    auto count = [&](double elevation, int& red, int& green) {
        options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 30.0, elevation);
        const Image image = renderSnapshot(*context, box.view(), options);
        red = green = 0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                const std::uint8_t* p = image.at(x, y);
                red += p[0] > 2 * p[1] && p[0] > 2 * p[2];
                green += p[1] > 2 * p[0] && p[1] > 2 * p[2];
            }
        }
        return image;
    };
    int red = 0;
    int green = 0;
    const Image above = count(35.0, red, green);
    writeImage(above, strata::test::freshTestDir() / "box-above.png");
    EXPECT_GT(red, 128 * 128 / 10) << "side faces should use the side map";
    EXPECT_GT(green, 128 * 128 / 20) << "the top face should use the top map";
    count(-35.0, red, green);
    EXPECT_GT(red, 128 * 128 / 10);
    EXPECT_EQ(green, 0) << "the bottom face must not use the top map";
}

TEST(GlRenderer, SideTexturesAreNotMirroredSeenFromOutside)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    // A horizontal ramp: brightness grows with U. Each side face of a box
    // inside one texture repeat, seen head-on, must get brighter to the right.
    Image ramp;
    ramp.width = 64;
    ramp.height = 64;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const auto v = std::uint8_t(x * 4);
            ramp.pixels.insert(ramp.pixels.end(), {v, v, v, 255});
        }
    }
    const glm::vec3 lo{0.05f}, hi{0.45f};
    const TestMesh box = strata::test::makeBox(lo, hi);
    SnapshotOptions options;
    options.width = 96;
    options.height = 96;
    options.samples = 1;
    options.material.mapScale = 1.0f;
    options.material.albedo = makeTexture(ramp, MapKind::Albedo);
    // Head-on sun, no ambient, a rough surface: the face shows the albedo,
    // barely tone-mapped.
    options.material.smoothness = 0.0f;
    options.material.fresnelStrength = 0.0f;
    options.lighting.sunColor = glm::vec3(1.0f);
    options.lighting.skyAmbient = glm::vec3(0.0f);
    options.lighting.groundAmbient = glm::vec3(0.0f);
    for (double azimuth : {0.0, 90.0, 180.0, 270.0}) {
        options.camera = orbitCamera(glm::dvec3(lo), glm::dvec3(hi), azimuth, 0.0, 30.0);
        options.lighting.sunDirection = glm::vec3(options.camera.position - options.camera.target);
        const Image image = renderSnapshot(*context, box.view(), options);
        const int left = image.at(36, 48)[0];
        const int right = image.at(60, 48)[0];
        EXPECT_GT(right, left + 10) << "azimuth " << azimuth << ": the texture is mirrored";
    }
}

TEST(GlRenderer, ShadingMatchesTheSharedHeaderOnTheCpu)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    // One flat face towards the camera, a solid texture: every pixel of the
    // face must be what the same header computes in C++.
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 64;
    options.height = 64;
    options.material.albedo = makeTexture(solid(150, 120, 90), MapKind::Albedo);
    options.lighting.sunDirection = glm::vec3(0.3f, 0.5f, 0.8f);
    options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 0.0, 0.0);
    const Image image = renderSnapshot(*context, box.view(), options);

    auto toLinear = [](int byte) {
        const float c = float(byte) / 255.0f;
        return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    };
    const Lighting& l = options.lighting;
    strata::shading::SurfaceOutput o{};
    o.albedo = glm::vec3{toLinear(150), toLinear(120), toLinear(90)};
    o.normal = glm::vec3(0.0f, 0.0f, 1.0f);
    o.metallic = options.material.metallic;
    o.smoothness = options.material.smoothness;
    o.occlusion = 1.0f;
    o.emission = glm::vec3(0.0f);
    strata::shading::LightingParams lp{};
    lp.lights[0].direction = glm::normalize(l.sunDirection);
    lp.lights[0].color = l.sunColor;
    lp.lightCount = 1;
    lp.skyAmbient = l.skyAmbient;
    lp.groundAmbient = l.groundAmbient;
    lp.exposure = l.exposure;
    const glm::vec3 expected = strata::shading::toneMap(
        strata::shading::lightSurface(o, glm::vec3(0.0f, 0.0f, 1.0f), lp, options.material.fresnelStrength),
        l.exposure);
    const std::uint8_t* centre = image.at(32, 32);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(int(centre[c]), srgbByte(expected[c]), 1) << "channel " << c;
    }
}

TEST(GlRenderer, SameInputsGiveTheSameBytes)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(1.0f, 2.0f, 3.0f), 2.0f, 32, 16);
    SnapshotOptions options;
    options.width = 64;
    options.height = 48;
    options.camera = orbitCamera(glm::dvec3(-1.0, 0.0, 1.0), glm::dvec3(3.0, 4.0, 5.0), 200.0, 10.0);
    options.material.albedo = makeTexture(makeRockAlbedo(64, 3), MapKind::Albedo);
    const Image a = renderSnapshot(*context, sphere.view(), options);
    const Image b = renderSnapshot(*context, sphere.view(), options);
    EXPECT_EQ(a.pixels, b.pixels);
}

TEST(GlRenderer, MeshOriginIsHonoured)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    // The same box, once at the origin and once with its vertices relative
    // to a far-away origin: the two images agree.
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 64;
    options.height = 64;
    options.samples = 1;
    options.material.albedo = makeTexture(makeRockAlbedo(64, 3), MapKind::Albedo);
    options.material.mapScale = 0.5f;
    options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 40.0, 30.0);
    const Image atZero = renderSnapshot(*context, box.view(), options);

    const glm::dvec3 origin{4.0e6, 1000.0, -2.0e6}; // multiples of the texture period
    strata::render::MeshView far = box.view();
    far.origin = origin;
    options.camera.position += origin;
    options.camera.target += origin;
    const Image moved = renderSnapshot(*context, far, options);
    int different = 0;
    for (std::size_t i = 0; i < atZero.pixels.size(); ++i) {
        different += std::abs(int(atZero.pixels[i]) - int(moved.pixels[i])) > 2;
    }
    EXPECT_LT(different, int(atZero.pixels.size() / 100));
}

TEST(GlRenderer, EmptyMeshGivesSkyAndBadInputsThrow)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    SnapshotOptions options;
    options.width = 16;
    options.height = 8;
    options.samples = 1;
    const Image sky = renderSnapshot(*context, strata::render::MeshView{}, options);
    EXPECT_TRUE(isSky(sky, 0, 0, options.lighting.skyColor));
    EXPECT_TRUE(isSky(sky, 15, 7, options.lighting.skyColor));

    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions bad = options;
    bad.width = 0;
    EXPECT_THROW(renderSnapshot(*context, box.view(), bad), strata::Error);
    bad = options;
    bad.material.mapScale = 0.0f;
    EXPECT_THROW(renderSnapshot(*context, box.view(), bad), strata::Error);
    bad = options;
    bad.material.albedo = std::make_shared<Texture>(); // no levels
    EXPECT_THROW(renderSnapshot(*context, box.view(), bad), strata::Error);

    TestMesh broken = box;
    broken.indices[4] = 1000;
    EXPECT_THROW(renderSnapshot(*context, broken.view(), options), strata::Error);
}

// ---------------------------------------------------------------------------
// The persistent renderer.

/// A material with every map (the circuitry set, grass on top) and the
/// parameters that keep every feature visible.
Material fullMaterial()
{
    static const TextureSetImages circuit = makeBuiltinSet(BuiltinSet::Circuitry, 64, 5);
    static const TextureSetImages grass = makeBuiltinSet(BuiltinSet::Grass, 64, 5);
    Material m;
    m.mapScale = 0.5f;
    m.albedo = makeTexture(circuit.albedo, MapKind::Albedo);
    m.mask = makeTexture(circuit.mohs, MapKind::Mask);
    m.normal = makeTexture(circuit.normal, MapKind::Normal);
    m.topAlbedo = makeTexture(grass.albedo, MapKind::Albedo);
    m.topMask = makeTexture(grass.mohs, MapKind::Mask);
    m.topNormal = makeTexture(grass.normal, MapKind::Normal);
    m.detail = makeTexture(circuit.detail, MapKind::Detail);
    m.detailNormal = makeTexture(circuit.normal, MapKind::DetailNormal);
    m.emission = makeTexture(circuit.emission, MapKind::Emission);
    m.metallic = 1.0f;
    m.smoothness = 1.0f;
    m.heightStrength = 0.6f;
    return m;
}

bool differ(const Image& a, const Image& b) { return a.pixels != b.pixels; }

TEST(GlRendererCache, FeatureSetsAreNormalisedAndCounted)
{
    const std::vector<std::uint32_t> sets = allFeatureSets();
    // Single material: 4 mask states × 10 normal states × 2³ (top, detail,
    // emission); layered (no exclusions): 5 mask states × 13 normal states ×
    // 2³; each with and without anti-tiling.
    EXPECT_EQ(sets.size(), 2u * (320u + 520u));
    EXPECT_EQ(sets.front(), 0u);
    EXPECT_EQ(sets.back(), feature::ALL);
    for (std::uint32_t f : sets) {
        EXPECT_EQ(normalizeFeatures(f), f);
    }
    EXPECT_EQ(normalizeFeatures(feature::HEIGHT_BLEND | feature::MODS), 0u);
    EXPECT_EQ(normalizeFeatures(feature::NORMAL_UDN | feature::NORMAL_RNM | feature::NORMAL_MAP),
              feature::NORMAL_MAP | feature::NORMAL_RNM);
    EXPECT_EQ(normalizeFeatures(0xffffffffu), normalizeFeatures(feature::ALL));
    const Material full = fullMaterial();
    EXPECT_EQ(effectiveFeatures(full, feature::ALL), materialFeatures(full));
    EXPECT_EQ(effectiveFeatures(full, ~feature::MASK_MAP), materialFeatures(full) & ~feature::MASK_MAP &
                                                               ~feature::HEIGHT_BLEND);
    EXPECT_EQ(effectiveFeatures(full, 0u), 0u);
}

/// The on/off values of three feature bits a < b < c in one set, as an index
/// into the table of all such triples' values.
int tripleValues(std::uint32_t s, int a, int b, int c)
{
    constexpr int BITS = 12;
    const int v = int((s >> a) & 1u) | int((s >> b) & 1u) << 1 | int((s >> c) & 1u) << 2;
    return ((a * BITS + b) * BITS + c) * 8 + v;
}

template <class F> void forEachTriple(F&& f)
{
    for (int a = 0; a < 12; ++a) {
        for (int b = a + 1; b < 12; ++b) {
            for (int c = b + 1; c < 12; ++c) f(a, b, c);
        }
    }
}

/// The feature sets the variant test compiles. By default a 3-wise cover of
/// allFeatureSets(): for every three feature bits, each of their eight
/// on/off combinations that some valid set has is in a chosen set (chosen
/// greedily, the lowest set first on ties). A shader bug from features
/// meeting shows up between a few of them; the cover is a few dozen
/// programs where compiling every variant takes llvmpipe over 10
/// CPU-minutes. STRATA_ALL_SHADER_VARIANTS=1 compiles every variant instead
/// (the layered and anti-tiled ones every 7th: each layered program is the
/// material once per layer, and all 1360 would take an hour).
std::vector<std::uint32_t> variantsToCompile()
{
    const std::vector<std::uint32_t> sets = allFeatureSets();
    const char* all = std::getenv("STRATA_ALL_SHADER_VARIANTS");
    if (all != nullptr && std::string(all) == "1") {
        std::vector<std::uint32_t> every;
        for (std::size_t i = 0; i < sets.size(); ++i) {
            if ((sets[i] & (feature::LAYERS | feature::ANTI_TILING)) && (i / 8) % 7 != 0) continue;
            every.push_back(sets[i]);
        }
        return every;
    }
    std::vector<char> uncovered(12 * 12 * 12 * 8, 0);
    std::size_t left = 0;
    for (std::uint32_t s : sets) {
        forEachTriple([&](int a, int b, int c) {
            char& u = uncovered[std::size_t(tripleValues(s, a, b, c))];
            left += std::size_t(u == 0);
            u = 1;
        });
    }
    std::vector<std::uint32_t> cover;
    while (left > 0) {
        std::uint32_t best = sets.front();
        int bestGain = -1;
        for (std::uint32_t s : sets) {
            int gain = 0;
            forEachTriple([&](int a, int b, int c) { gain += uncovered[std::size_t(tripleValues(s, a, b, c))]; });
            if (gain > bestGain) {
                best = s;
                bestGain = gain;
            }
        }
        cover.push_back(best);
        forEachTriple([&](int a, int b, int c) {
            char& u = uncovered[std::size_t(tripleValues(best, a, b, c))];
            left -= std::size_t(u);
            u = 0;
        });
    }
    return cover;
}

TEST(GlRendererVariantCover, EveryThreeFeaturesMeetInEachOfTheirValidCombinations)
{
    const std::vector<std::uint32_t> sets = allFeatureSets();
    const std::vector<std::uint32_t> cover = variantsToCompile();
    ASSERT_LT(cover.size(), sets.size() / 10);
    for (std::uint32_t s : cover) EXPECT_EQ(normalizeFeatures(s), s) << featureNames(s);
    int checked = 0;
    forEachTriple([&](int a, int b, int c) {
        const std::uint32_t mask = (1u << a) | (1u << b) | (1u << c);
        for (std::uint32_t v = 0; v < 8; ++v) {
            const std::uint32_t want = ((v & 1u) << a) | ((v >> 1 & 1u) << b) | ((v >> 2 & 1u) << c);
            auto has = [&](std::uint32_t s) { return (s & mask) == want; };
            const bool possible = std::any_of(sets.begin(), sets.end(), has);
            EXPECT_EQ(std::any_of(cover.begin(), cover.end(), has), possible)
                << "bits " << a << ", " << b << ", " << c << " = " << v;
            checked += int(possible);
        }
    });
    EXPECT_GT(checked, 220 * 4); // most combinations are valid sets
    std::cout << cover.size() << " of " << sets.size() << " feature sets hold every valid combination of any "
              << "three features (" << checked << ")" << std::endl;
}

/// The feature-set variants of the terrain program (variantsToCompile())
/// compile, link and draw without a GL error, each once (split in shards so
/// ctest can run them in parallel).
class GlRendererVariants : public ::testing::TestWithParam<int>
{
};

TEST_P(GlRendererVariants, EveryFeatureSetCompilesAndRendersWithoutGlErrors)
{
    constexpr int SHARDS = 8;
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    GlRenderer renderer(*context);
    renderer.setMesh(box.view());
    const Camera camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 30.0, 30.0);
    const Lighting lighting;
    const std::vector<std::uint32_t> sets = variantsToCompile();
    int drawn = 0;
    std::set<std::uint32_t> seen;
    std::size_t expected = 0;
    for (std::size_t i = std::size_t(GetParam()); i < sets.size(); i += SHARDS) {
        const bool layered = (sets[i] & feature::LAYERS) != 0u;
        ++expected;
        // The full material with the variant's layout and normal blend; the
        // feature mask switches the other maps off (textures stay uploaded).
        // Layered: a MOHS/UDN base under a MODS/RNM layer, so that the union
        // holds every bit.
        Material m = fullMaterial();
        m.antiTiling = true; // off through the mask where the set lacks it
        m.maskLayout = (sets[i] & feature::MODS) && !layered ? MaskLayout::Mods : MaskLayout::Mohs;
        m.normalBlend = layered                           ? NormalBlend::Udn
                        : (sets[i] & feature::NORMAL_RNM) ? NormalBlend::Rnm
                        : (sets[i] & feature::NORMAL_UDN) ? NormalBlend::Udn
                                                          : NormalBlend::Whiteout;
        if (layered) {
            MaterialLayer layer;
            layer.name = "mods-rnm";
            layer.material = fullMaterial();
            layer.material.maskLayout = MaskLayout::Mods;
            layer.material.normalBlend = NormalBlend::Rnm;
            layer.rule.slope = {true, 0.0f, 40.0f, 10.0f};
            m.layers.push_back(layer);
        }
        renderer.setMaterial(m);
        DrawOptions options;
        options.featureMask = sets[i];
        ASSERT_EQ(renderer.activeFeatures(sets[i]), sets[i]) << featureNames(sets[i]);
        try {
            renderer.drawFrame(camera, lighting, 24, 24, 1, options);
        } catch (const strata::Error& e) {
            ADD_FAILURE() << featureNames(sets[i]) << ": " << e.what();
            continue;
        }
        const Image image = renderer.readFrame();
        EXPECT_FALSE(isSky(image, 12, 12, lighting.skyColor)) << featureNames(sets[i]);
        EXPECT_TRUE(isSky(image, 0, 0, lighting.skyColor)) << featureNames(sets[i]);
        seen.insert(sets[i]);
        ++drawn;
    }
    const ProgramStats stats = renderer.stats();
    EXPECT_EQ(stats.possible, 1680);
    EXPECT_EQ(stats.compiled, drawn);
    EXPECT_EQ(std::set<std::uint32_t>(stats.featureSets.begin(), stats.featureSets.end()), seen);
    EXPECT_EQ(drawn, int(expected));
    std::cout << "shard " << GetParam() << ": " << drawn << " variants compiled in " << stats.compileSeconds << " s"
              << std::endl;
}

INSTANTIATE_TEST_SUITE_P(Shards, GlRendererVariants, ::testing::Range(0, 8));

TEST(GlRendererCache, EachVariantIsCompiledOnceAndOnlyWhenUsed)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    GlRenderer renderer(*context);
    EXPECT_EQ(renderer.stats().compiled, 0) << "nothing is compiled before it is used";
    renderer.setMesh(box.view());
    const Material full = fullMaterial();
    renderer.setMaterial(full);
    const Camera camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 30.0, 30.0);
    const Lighting lighting;
    DrawOptions options;
    for (int frame = 0; frame < 3; ++frame) {
        renderer.drawFrame(camera, lighting, 16, 16, 1, options);
    }
    EXPECT_EQ(renderer.stats().compiled, 1);
    ASSERT_EQ(renderer.stats().featureSets.size(), 1u);
    EXPECT_EQ(renderer.stats().featureSets[0], materialFeatures(full));

    // Debug views and the wireframe are uniforms, not variants.
    options.debugView = DebugView::WorldNormals;
    options.wireframe = true;
    renderer.drawFrame(camera, lighting, 16, 16, 1, options);
    EXPECT_EQ(renderer.stats().compiled, 1);

    // A feature toggle selects another variant, compiled once.
    options.featureMask = ~feature::NORMAL_MAP;
    renderer.drawFrame(camera, lighting, 16, 16, 1, options);
    renderer.drawFrame(camera, lighting, 16, 16, 1, options);
    EXPECT_EQ(renderer.stats().compiled, 2);
    options.featureMask = feature::ALL;
    renderer.drawFrame(camera, lighting, 16, 16, 1, options);
    EXPECT_EQ(renderer.stats().compiled, 2);

    // Another material with the same feature set reuses the program.
    Material other = full;
    other.albedoTint = glm::vec3(0.5f);
    other.albedo = makeTexture(solid(10, 200, 10), MapKind::Albedo);
    renderer.setMaterial(other);
    renderer.drawFrame(camera, lighting, 16, 16, 1, {});
    EXPECT_EQ(renderer.stats().compiled, 2);
    renderer.prepareProgram(0u);
    EXPECT_EQ(renderer.stats().compiled, 3);
    EXPECT_GT(renderer.stats().compileSeconds, 0.0);
}

TEST(GlRendererCache, ReuseAcrossFramesGivesIdenticalImages)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(1.0f, 2.0f, 3.0f), 2.0f, 32, 16);
    SnapshotOptions options;
    options.width = 64;
    options.height = 48;
    options.samples = 4;
    options.camera = orbitCamera(glm::dvec3(-1.0, 0.0, 1.0), glm::dvec3(3.0, 4.0, 5.0), 200.0, 10.0);
    options.material = fullMaterial();
    GlRenderer renderer(*context);
    renderer.setMesh(sphere.view());
    const Image first = renderer.renderImage(options);
    const Image second = renderer.renderImage(options);
    EXPECT_EQ(first.pixels, second.pixels);

    // Something else in between (another view, size, debug view, material) changes nothing after.
    SnapshotOptions other = options;
    other.width = 40;
    other.samples = 1;
    other.debugView = DebugView::TriplanarWeights;
    other.camera = orbitCamera(glm::dvec3(-1.0, 0.0, 1.0), glm::dvec3(3.0, 4.0, 5.0), 20.0, 40.0);
    other.material.albedo = makeTexture(solid(200, 30, 30), MapKind::Albedo);
    const Image between = renderer.renderImage(other);
    EXPECT_TRUE(differ(between, first));
    const Image third = renderer.renderImage(options);
    EXPECT_EQ(first.pixels, third.pixels);

    // The one-shot wrapper gives the same bytes as the persistent renderer.
    const Image oneShot = renderSnapshot(*context, sphere.view(), options);
    EXPECT_EQ(first.pixels, oneShot.pixels);
}

TEST(GlRendererCache, KeptShadowMapFollowsTheSunAndTheMesh)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    // A block standing on a slab: its shadow moves with the sun.
    TestMesh scene = strata::test::makeBox(glm::vec3(-4.0f, -1.0f, -4.0f), glm::vec3(4.0f, 0.0f, 4.0f));
    const TestMesh block = strata::test::makeBox(glm::vec3(-0.5f, 0.0f, -0.5f), glm::vec3(0.5f, 2.0f, 0.5f));
    const auto base = std::uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), block.positions.begin(), block.positions.end());
    scene.normals.insert(scene.normals.end(), block.normals.begin(), block.normals.end());
    for (std::uint32_t i : block.indices) {
        scene.indices.push_back(base + i);
    }
    SnapshotOptions east;
    east.width = 64;
    east.height = 64;
    east.samples = 1;
    east.shadows.resolution = 256;
    east.camera = orbitCamera(glm::dvec3(-4.0, -1.0, -4.0), glm::dvec3(4.0, 2.0, 4.0), 20.0, 60.0);
    east.lighting.sunDirection = glm::vec3(1.0f, 1.0f, 0.2f);
    SnapshotOptions west = east;
    west.lighting.sunDirection = glm::vec3(-1.0f, 1.0f, 0.2f);

    GlRenderer renderer(*context);
    renderer.setMesh(scene.view());
    const Image a = renderer.renderImage(east);
    const Image b = renderer.renderImage(west);
    const Image c = renderer.renderImage(east);
    EXPECT_TRUE(differ(a, b)) << "the sun moved, the image did not";
    EXPECT_EQ(a.pixels, c.pixels);
    EXPECT_EQ(b.pixels, renderSnapshot(*context, scene.view(), west).pixels) << "a stale shadow map";

    // A new mesh under the same sun redraws the map: the block's shadow goes.
    const TestMesh slab = strata::test::makeBox(glm::vec3(-4.0f, -1.0f, -4.0f), glm::vec3(4.0f, 0.0f, 4.0f));
    renderer.setMesh(slab.view());
    EXPECT_EQ(renderer.renderImage(east).pixels, renderSnapshot(*context, slab.view(), east).pixels);
}

TEST(GlRendererCache, MeshAndMaterialCanBeReplaced)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    const TestMesh small = strata::test::makeBox(glm::vec3(-0.2f), glm::vec3(0.2f));
    SnapshotOptions options;
    options.width = 32;
    options.height = 32;
    options.samples = 1;
    // Head-on from 6 m: the big box's face spans pixels 9..23, the small one's 15..17.
    options.camera.position = glm::dvec3(0.0, 0.0, 6.0);
    options.camera.target = glm::dvec3(0.0);
    options.material.albedo = makeTexture(solid(200, 30, 30), MapKind::Albedo);
    GlRenderer renderer(*context);
    EXPECT_THROW(renderer.readFrame(), strata::Error) << "no frame yet";
    renderer.setMesh(box.view());
    const Image big = renderer.renderImage(options);
    EXPECT_FALSE(isSky(big, 11, 16, options.lighting.skyColor));
    EXPECT_TRUE(isSky(big, 5, 16, options.lighting.skyColor));
    renderer.setMesh(small.view());
    const Image little = renderer.renderImage(options);
    EXPECT_TRUE(isSky(little, 11, 16, options.lighting.skyColor));
    EXPECT_FALSE(isSky(little, 16, 16, options.lighting.skyColor));
    renderer.setMesh(MeshView{});
    const Image empty = renderer.renderImage(options);
    EXPECT_TRUE(isSky(empty, 16, 16, options.lighting.skyColor));

    TestMesh broken = box;
    broken.indices[7] = 24;
    EXPECT_THROW(renderer.setMesh(broken.view()), strata::Error);
    Material bad;
    bad.blendExponent = 0.0f;
    EXPECT_THROW(renderer.setMaterial(bad), strata::Error);
    EXPECT_THROW(renderer.setMaterial(Material{}, 0.5f), strata::Error);
}

// ---------------------------------------------------------------------------
// Debug views, feature toggles, wireframe.

/// The centre pixel of the +Z face of a box seen head-on.
const std::uint8_t* faceCentre(GlRenderer& renderer, SnapshotOptions options, DebugView view, Image& keep)
{
    options.debugView = view;
    keep = renderer.renderImage(options);
    return keep.at(32, 32);
}

TEST(GlRendererDebugViews, ShowTheMaterialValuesAsBytes)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 64;
    options.height = 64;
    options.samples = 1;
    options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 0.0, 0.0);
    options.material.albedo = makeTexture(solid(150, 120, 90), MapKind::Albedo);
    // MOHS = (0.2, 0.4, 0.6, 0.8).
    options.material.mask = makeTexture(solid(51, 102, 153, 204), MapKind::Mask);
    options.material.metallic = 1.0f;
    options.material.smoothness = 1.0f;
    options.material.occlusionStrength = 1.0f;
    options.material.heightStrength = 0.0f;
    GlRenderer renderer(*context);
    renderer.setMesh(box.view());
    Image image;
    auto expectRgb = [&](DebugView view, int r, int g, int b) {
        const std::uint8_t* p = faceCentre(renderer, options, view, image);
        EXPECT_NEAR(p[0], r, 1) << debugViewName(view);
        EXPECT_NEAR(p[1], g, 1) << debugViewName(view);
        EXPECT_NEAR(p[2], b, 1) << debugViewName(view);
    };
    expectRgb(DebugView::TriplanarWeights, 0, 0, 255); // the Z projection alone
    expectRgb(DebugView::WorldNormals, 128, 128, 255);
    expectRgb(DebugView::Metallic, 51, 51, 51);
    expectRgb(DebugView::Occlusion, 102, 102, 102);
    expectRgb(DebugView::Height, 153, 153, 153);
    expectRgb(DebugView::Smoothness, 204, 204, 204);
    expectRgb(DebugView::Albedo, 150, 120, 90);
    EXPECT_TRUE(isSky(image, 0, 0, options.lighting.skyColor)) << "debug views keep the background";

    // Toggling the mask map off: metallic is the material's own value.
    options.featureMask = ~feature::MASK_MAP;
    options.material.metallic = 0.6f;
    expectRgb(DebugView::Metallic, 153, 153, 153);
    expectRgb(DebugView::Height, 255, 255, 255);

    // The weights of a 45° edge view: X and Z both, summing to one.
    options.featureMask = feature::ALL;
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(0.0f), 1.0f, 64, 32);
    renderer.setMesh(sphere.view());
    options.material.blendOffset = 0.0f;
    options.material.blendExponent = 1.0f;
    options.camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 45.0, 0.0);
    const std::uint8_t* p = faceCentre(renderer, options, DebugView::TriplanarWeights, image);
    // (The pixel centre is half a pixel off the view axis: the normal is ~1° off 45°.)
    EXPECT_NEAR(p[0], p[2], 8);
    EXPECT_LT(p[1], 10);
    EXPECT_NEAR(p[0] + p[1] + p[2], 255, 4);

    SnapshotOptions bad = options;
    bad.debugView = DebugView(DEBUG_VIEW_COUNT);
    EXPECT_THROW(renderer.renderImage(bad), strata::Error);
    EXPECT_STREQ(debugViewName(DebugView::Albedo), "albedo");
}

TEST(GlRendererDebugViews, EachViewDiffersOnTheFullMaterial)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 48, 24);
    SnapshotOptions options;
    options.width = 48;
    options.height = 48;
    options.samples = 1;
    options.camera = orbitCamera(glm::dvec3(-2.0), glm::dvec3(2.0), 30.0, 30.0);
    options.material = fullMaterial();
    GlRenderer renderer(*context);
    renderer.setMesh(sphere.view());
    std::vector<Image> images;
    for (int view = 0; view < DEBUG_VIEW_COUNT; ++view) {
        options.debugView = DebugView(view);
        images.push_back(renderer.renderImage(options));
    }
    for (int a = 0; a < DEBUG_VIEW_COUNT; ++a) {
        for (int b = a + 1; b < DEBUG_VIEW_COUNT; ++b) {
            EXPECT_TRUE(differ(images[std::size_t(a)], images[std::size_t(b)]))
                << debugViewName(DebugView(a)) << " = " << debugViewName(DebugView(b));
        }
    }
    EXPECT_EQ(renderer.stats().compiled, 1);
}

TEST(GlRendererDebugViews, MatchTheCpuRenderersDebugViews)
{
    // The views are the shared header's debugViewColor() on both renderers:
    // the same image up to rasterization and filtering, as the shaded one.
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh sphere = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 96, 48);
    SnapshotOptions options;
    options.width = 96;
    options.height = 96;
    options.samples = 1;
    // GL picks each map's level of detail as the CPU reference does
    // (terrain.frag's mapLod, the specification's log2), no longer the
    // driver's approximation: the CPU's exact path is the one to match.
    options.cpuLodLog2 = LodLog2::Exact;
    options.camera = orbitCamera(glm::dvec3(-2.0), glm::dvec3(2.0), 30.0, 30.0);
    options.material = fullMaterial();
    GlRenderer renderer(*context);
    renderer.setMesh(sphere.view());
    const Image cpuShaded = renderSnapshotCpu(sphere.view(), options);
    for (int view = 1; view < DEBUG_VIEW_COUNT; ++view) {
        options.debugView = DebugView(view);
        const Image gl = renderer.renderImage(options);
        const Image cpu = renderSnapshotCpu(sphere.view(), options);
        ASSERT_EQ(gl.pixels.size(), cpu.pixels.size());
        EXPECT_TRUE(differ(cpu, cpuShaded)) << debugViewName(DebugView(view)) << ": the CPU shows the shaded image";
        std::size_t close = 0;
        for (std::size_t i = 0; i < gl.pixels.size(); i += 4) {
            bool within = true;
            for (int c = 0; c < 3; ++c) {
                within = within && std::abs(int(gl.pixels[i + std::size_t(c)]) - int(cpu.pixels[i + std::size_t(c)])) <= 2;
            }
            close += within;
        }
        const double fraction = double(close) / double(gl.pixels.size() / 4);
        std::cout << debugViewName(DebugView(view)) << ": " << 100.0 * fraction << "% of pixels within 2/255"
                  << std::endl;
        EXPECT_GE(fraction, 0.99) << debugViewName(DebugView(view));
    }
}

TEST(GlRendererDebugViews, WireframeDrawsEdgesInTheWireColour)
{
    auto context = createContext();
    ASSERT_TRUE(context);
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    GlRenderer renderer(*context);
    renderer.setMesh(box.view());
    Material m;
    m.albedo = makeTexture(solid(40, 40, 200), MapKind::Albedo);
    renderer.setMaterial(m);
    const Camera camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 30.0, 30.0);
    auto redPixels = [](const Image& image) {
        int red = 0;
        for (int y = 0; y < image.height; ++y) {
            for (int x = 0; x < image.width; ++x) {
                const std::uint8_t* p = image.at(x, y);
                red += p[0] > 200 && p[1] < 40 && p[2] < 40;
            }
        }
        return red;
    };
    DrawOptions options;
    options.wireColor = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
    renderer.drawFrame(camera, Lighting{}, 96, 96, 1, options);
    const Image solidImage = renderer.readFrame();
    EXPECT_EQ(redPixels(solidImage), 0);
    options.wireframe = true;
    renderer.drawFrame(camera, Lighting{}, 96, 96, 1, options);
    const Image wire = renderer.readFrame();
    // 9 visible edges (+ 3 face diagonals) of ~40 pixels each.
    EXPECT_GT(redPixels(wire), 200);
    EXPECT_LT(redPixels(wire), 96 * 96 / 4);
    // Hidden edges stay hidden: the far corner's edges do not show through.
    EXPECT_TRUE(isSky(wire, 0, 0, Lighting{}.skyColor));
}

TEST(GlfwContext, WithoutADisplayTheErrorIsOneLine)
{
    const char* display = std::getenv("DISPLAY");
    const std::string saved = display ? display : "";
    ::unsetenv("DISPLAY");
    ::unsetenv("WAYLAND_DISPLAY");
    try {
        auto window = GlfwContext::create(64, 64, "test", false);
        ADD_FAILURE() << "a window opened without DISPLAY";
    } catch (const strata::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("cannot open a window"), std::string::npos) << message;
        EXPECT_NE(message.find("xvfb-run"), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_THROW(GlfwContext::create(0, 64, "test", false), strata::Error);
    if (display) {
        ::setenv("DISPLAY", saved.c_str(), 1);
    }
}

} // namespace
