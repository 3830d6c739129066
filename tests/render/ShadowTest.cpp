// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Sun shadows (shaders/Shadow.h, render/src/ShadowSetup.h): the lookup and
// PCF math on a synthetic map, the fitted projection, and both renderers on
// scenes whose shadows are known.

#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>

#include "ShadingPrelude.h"
#include "ShadowSetup.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <functional>
#include <memory>
#include <vector>

namespace {

using namespace strata::render;
using strata::shading::ShadowParams;
using strata::test::TestMesh;

/// A synthetic shadow map: every texel the same depth, except x >= edgeX
/// which holds `nearDepth` (an occluder covering the right part).
struct SyntheticMap
{
    int resolution = 64;
    float depthAll = 1.0f;
    int edgeX = 1 << 30;
    float nearDepth = 0.0f;
    mutable int fetches = 0;

    float depth(int x, int y) const
    {
        ++fetches;
        EXPECT_GE(x, 0);
        EXPECT_GE(y, 0);
        EXPECT_LT(x, resolution);
        EXPECT_LT(y, resolution);
        return x >= edgeX ? nearDepth : depthAll;
    }
};

/// Identity projection: a position (x, y, z) in [−1, 1]³ is its own NDC.
ShadowParams identityParams(int resolution)
{
    ShadowParams sp{};
    sp.lightViewProjection = glm::mat4(1.0f);
    sp.lightDirection = glm::vec3(0.0f, 0.0f, -1.0f); // towards the sun: −Z, so NDC depth decreases towards it
    sp.texelSize = 2.0f / float(resolution);
    sp.normalBias = 0.0f;
    sp.depthBias = 0.0f;
    sp.resolution = resolution;
    sp.enabled = 1;
    return sp;
}

TEST(Shadow, DisabledIsLitWithoutReadingTheMap)
{
    SyntheticMap map;
    map.depthAll = 0.0f; // everything occluded, were it read
    ShadowParams sp = identityParams(map.resolution);
    sp.enabled = 0;
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.0f), glm::vec3(0, 0, -1)), 1.0f);
    EXPECT_EQ(map.fetches, 0);
}

TEST(Shadow, LitInFrontOfTheStoredDepthShadowedBehindIt)
{
    SyntheticMap map;
    map.depthAll = 0.5f; // NDC z = 0
    const ShadowParams sp = identityParams(map.resolution);
    // Window depth 0.5·z + 0.5: z = −0.2 is nearer the sun than the occluder.
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.1f, 0.2f, -0.2f), glm::vec3(0, 0, -1)), 1.0f);
    EXPECT_EQ(map.fetches, 16); // the 4×4 PCF kernel
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.1f, 0.2f, 0.2f), glm::vec3(0, 0, -1)), 0.0f);
    // Outside the map (x, y or beyond the far plane): lit.
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(1.5f, 0.0f, 0.5f), glm::vec3(0, 0, -1)), 1.0f);
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.0f, -1.5f, 0.5f), glm::vec3(0, 0, -1)), 1.0f);
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.0f, 0.0f, 1.5f), glm::vec3(0, 0, -1)), 1.0f);
    // The map's corners clamp their kernels to the map.
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(-0.999f, -0.999f, 0.5f), glm::vec3(0, 0, -1)), 0.0f);
    EXPECT_EQ(strata::shading::sunVisibility(map, sp, glm::vec3(0.999f, 0.999f, 0.5f), glm::vec3(0, 0, -1)), 0.0f);
}

TEST(Shadow, PcfFadesContinuouslyAcrossAnEdge)
{
    SyntheticMap map;
    map.edgeX = 32; // texels 32.. occlude
    map.nearDepth = 0.1f;
    const ShadowParams sp = identityParams(map.resolution);
    float previous = 1.0f;
    int partial = 0;
    // Walk across the edge in steps of 1/8 texel: visibility falls from 1 to
    // 0, monotonically, in steps no larger than the kernel allows.
    for (int step = 0; step <= 8 * 8; ++step) {
        const float texel = 28.0f + float(step) / 8.0f;
        const float x = (texel + 0.5f) / 32.0f - 1.0f;
        const float v = strata::shading::sunVisibility(map, sp, glm::vec3(x, 0.0f, 0.0f), glm::vec3(0, 0, -1));
        EXPECT_LE(v, previous + 1e-6f) << texel;
        EXPECT_LE(previous - v, 1.0f / 3.0f / 8.0f + 1e-5f) << texel;
        partial += v > 0.0f && v < 1.0f;
        previous = v;
    }
    EXPECT_EQ(previous, 0.0f);
    EXPECT_GT(partial, 16);
}

TEST(Shadow, NormalOffsetMovesAlongTheGivenNormalOnly)
{
    ShadowParams sp = identityParams(64);
    sp.normalBias = 2.0f;
    sp.depthBias = 1.0f;
    const glm::vec3 p(0.1f, 0.2f, 0.3f);
    const glm::vec3 n(0.0f, 1.0f, 0.0f);
    const glm::vec3 q = strata::shading::shadowLookupPosition(sp, p, n);
    EXPECT_NEAR(q.x, p.x, 1e-7f);
    EXPECT_NEAR(q.y, p.y + 2.0f * sp.texelSize, 1e-6f);
    EXPECT_NEAR(q.z, p.z - 1.0f * sp.texelSize, 1e-6f);
    // Facing the sun, the normal offset vanishes (only the depth bias moves it).
    const glm::vec3 facing = strata::shading::shadowLookupPosition(sp, p, -sp.lightDirection);
    EXPECT_NEAR(glm::length(facing - p), 1.0f * sp.texelSize, 1e-6f);
    // Zero biases leave the point where it is.
    sp.normalBias = sp.depthBias = 0.0f;
    const glm::vec3 same = strata::shading::shadowLookupPosition(sp, p, n);
    EXPECT_EQ(same, p);
}

TEST(Shadow, ShadowedLightingScalesTheSunOnly)
{
    strata::shading::LightingParams l{};
    l.lightCount = 2;
    l.lights[0].color = glm::vec3(2.0f);
    l.lights[1].color = glm::vec3(0.5f);
    l.skyAmbient = glm::vec3(0.3f);
    const strata::shading::LightingParams s = strata::shading::shadowedLighting(l, 0.25f);
    EXPECT_EQ(s.lights[0].color, glm::vec3(0.5f));
    EXPECT_EQ(s.lights[1].color, glm::vec3(0.5f));
    EXPECT_EQ(s.skyAmbient, glm::vec3(0.3f));
}

TEST(Shadow, ProjectionHoldsTheBoundsWithMargin)
{
    const TestMesh box = strata::test::makeBox(glm::vec3(-3.0f, 0.0f, -2.0f), glm::vec3(5.0f, 4.0f, 1.0f));
    Lighting lighting;
    ShadowOptions options;
    options.resolution = 512;
    for (const glm::vec3& sun :
         {glm::vec3(0.3f, 0.8f, 0.2f), glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(-1.0f, 0.05f, 0.0f)}) {
        lighting.sunDirection = sun;
        const ShadowParams sp = detail::makeShadowParams(detail::meshBounds(box.view()), lighting, options);
        ASSERT_EQ(sp.enabled, 1);
        EXPECT_NEAR(glm::length(sp.lightDirection), 1.0f, 1e-6f);
        EXPECT_GT(sp.texelSize, 0.0f);
        for (const glm::vec3& p : box.positions) {
            const glm::vec4 c = sp.lightViewProjection * glm::vec4(p, 1.0f);
            EXPECT_NEAR(c.w, 1.0f, 1e-6f);
            // Inside by at least the margin (normal + depth bias + 2 texels in x and y).
            const float marginNdc = (options.normalBias + options.depthBias) * sp.texelSize * 2.0f /
                                    (sp.texelSize * float(options.resolution));
            EXPECT_LT(std::abs(c.x), 1.0f - marginNdc);
            EXPECT_LT(std::abs(c.y), 1.0f - marginNdc);
            EXPECT_LT(std::abs(c.z), 1.0f);
        }
        // Towards the sun is nearer (smaller depth).
        const glm::vec4 a = sp.lightViewProjection * glm::vec4(glm::vec3(1.0f, 2.0f, -0.5f), 1.0f);
        const glm::vec4 b = sp.lightViewProjection * glm::vec4(glm::vec3(1.0f, 2.0f, -0.5f) + sp.lightDirection, 1.0f);
        EXPECT_LT(b.z, a.z);
    }
    options.enabled = false;
    EXPECT_EQ(detail::makeShadowParams(detail::meshBounds(box.view()), lighting, options).enabled, 0);
    options.enabled = true;
    EXPECT_EQ(detail::makeShadowParams(detail::meshBounds(MeshView{}), lighting, options).enabled, 0);
}

/// A slab with a box floating over it; the sun straight above.
TestMesh floatingBox()
{
    TestMesh mesh = strata::test::makeBox(glm::vec3(-6.0f, -1.0f, -6.0f), glm::vec3(6.0f, 0.0f, 6.0f));
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.5f, 2.0f, -1.5f), glm::vec3(1.5f, 3.0f, 1.5f));
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), box.positions.begin(), box.positions.end());
    mesh.normals.insert(mesh.normals.end(), box.normals.begin(), box.normals.end());
    for (std::uint32_t i : box.indices) mesh.indices.push_back(base + i);
    return mesh;
}

/// Straight down onto the slab from high above, narrow lens: the box covers
/// the centre, the slab's top fills the view.
SnapshotOptions topDown(int size)
{
    SnapshotOptions options;
    options.width = size;
    options.height = size;
    options.samples = 1;
    options.camera.position = glm::dvec3(0.0, 40.0, 0.0);
    options.camera.target = glm::dvec3(0.0);
    options.camera.up = glm::dvec3(0.0, 0.0, -1.0);
    options.camera.fovYDegrees = 2.0 * glm::degrees(std::atan(5.0 / 40.0)); // ±5 m at the slab
    options.camera.nearPlane = 1.0;
    options.camera.farPlane = 100.0;
    options.lighting.sunDirection = glm::vec3(0.0f, 1.0f, 0.0f);
    options.lighting.extraLights.clear();
    options.shadows.resolution = 512;
    return options;
}

int luminance(const Image& image, int x, int y)
{
    const std::uint8_t* p = image.at(x, y);
    return int(p[0]) + int(p[1]) + int(p[2]);
}

/// The slab under the box is in shadow (sun straight above): seen from a
/// camera beside the box (looking under it), the centre of the slab is
/// darker than its rim, by the sun's share; without shadows it is not.
void checkCastShadow(const std::function<Image(const SnapshotOptions&)>& render)
{
    const TestMesh mesh = floatingBox();
    SnapshotOptions options = topDown(96);
    // A camera just above the slab, beside the box, looking at the slab's centre under it.
    options.camera.position = glm::dvec3(0.0, 1.0, 5.5);
    options.camera.target = glm::dvec3(0.0, 0.0, 0.0);
    options.camera.up = glm::dvec3(0.0, 1.0, 0.0);
    options.camera.fovYDegrees = 60.0;
    options.camera.nearPlane = 0.1;
    const Image shadowed = render(options);
    options.shadows.enabled = false;
    const Image lit = render(options);
    options.lighting.sunColor = glm::vec3(0.0f);
    const Image ambientOnly = render(options);
    // The image centre shows the slab under the box: fully shadowed, it gets
    // the ambient light only. The bottom rows show the slab near the camera,
    // in the sun: unchanged.
    const int cx = 48, cy = 48;
    EXPECT_GT(luminance(lit, cx, cy), luminance(ambientOnly, cx, cy) + 60);
    EXPECT_NEAR(luminance(shadowed, cx, cy), luminance(ambientOnly, cx, cy), 3);
    EXPECT_NEAR(luminance(shadowed, cx, 92), luminance(lit, cx, 92), 3);
}

/// A plane lit at a grazing 8° shows no shadow acne: every pixel of it is as
/// bright as without shadows, thanks to the normal-offset bias; with both
/// biases zero the same plane does show acne (the test can fail).
void checkNoAcne(const std::function<Image(const SnapshotOptions&)>& render)
{
    TestMesh plane = strata::test::makeBox(glm::vec3(-6.0f, -1.0f, -6.0f), glm::vec3(6.0f, 0.0f, 6.0f));
    SnapshotOptions options = topDown(96);
    options.lighting.sunDirection = glm::normalize(glm::vec3(1.0f, std::tan(glm::radians(8.0f)), 0.3f));
    const Image shadowed = render(options);
    SnapshotOptions plain = options;
    plain.shadows.enabled = false;
    const Image lit = render(plain);
    EXPECT_GE(fractionWithin(shadowed, lit, 2), 0.999);
    SnapshotOptions noBias = options;
    noBias.shadows.normalBias = 0.0f;
    noBias.shadows.depthBias = 0.0f;
    const Image acne = render(noBias);
    EXPECT_LT(fractionWithin(acne, lit, 2), 0.95);
    (void)plane;
}

TEST(Shadow, CpuCastShadowAndNoAcne)
{
    const TestMesh mesh = floatingBox();
    checkCastShadow([&](const SnapshotOptions& o) { return renderSnapshotCpu(mesh.view(), o); });
    const TestMesh plane = strata::test::makeBox(glm::vec3(-6.0f, -1.0f, -6.0f), glm::vec3(6.0f, 0.0f, 6.0f));
    checkNoAcne([&](const SnapshotOptions& o) { return renderSnapshotCpu(plane.view(), o); });
}

TEST(Shadow, GlCastShadowAndNoAcne)
{
    std::unique_ptr<EglContext> context = EglContext::create(); // CI has EGL (llvmpipe): never skipped
    const TestMesh mesh = floatingBox();
    checkCastShadow([&](const SnapshotOptions& o) { return renderSnapshot(*context, mesh.view(), o); });
    const TestMesh plane = strata::test::makeBox(glm::vec3(-6.0f, -1.0f, -6.0f), glm::vec3(6.0f, 0.0f, 6.0f));
    checkNoAcne([&](const SnapshotOptions& o) { return renderSnapshot(*context, plane.view(), o); });
}

TEST(Shadow, CpuShadowsAreBitwiseIdenticalOnAnyThreadCount)
{
    const TestMesh mesh = floatingBox();
    SnapshotOptions options = topDown(128);
    options.lighting.sunDirection = glm::vec3(0.4f, 0.8f, 0.2f);
    Image a;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        a = renderSnapshotCpu(mesh.view(), options);
    }
    const Image b = renderSnapshotCpu(mesh.view(), options);
    EXPECT_EQ(a.pixels, b.pixels);
}

} // namespace
