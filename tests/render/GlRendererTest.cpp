// Headless rendering through EGL. These tests must run (CI has Mesa's
// llvmpipe): a machine where no context can be created fails them.

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include "ShadingPrelude.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>

namespace {

using namespace strata::render;
using strata::test::TestMesh;

std::unique_ptr<EglContext> createContext()
{
    try {
        return EglContext::create();
    } catch (const strata::Error& e) {
        ADD_FAILURE() << "no EGL context: " << e.what();
        return nullptr;
    }
}

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

Image solid(int r, int g, int b)
{
    Image image;
    image.width = 4;
    image.height = 4;
    for (int i = 0; i < 16; ++i) {
        image.pixels.insert(image.pixels.end(), {std::uint8_t(r), std::uint8_t(g), std::uint8_t(b), 255});
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

} // namespace
