// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Anti-tiling (stochastic tiling, shaders/TriplanarShading.h and
// TriplanarMaterial.h): the taps' weights, continuity, anchoring to the world
// through the rebasing, that repeats stop repeating, and GL against the CPU.

#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>

#include "GoldenScenes.h"
#include "Parity.h"
#include "ShadingBridge.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>

namespace {

using namespace strata::render;
namespace shading = strata::shading;
using strata::test::TestMesh;

/// A smooth test signal of UV, blended by the taps as a map would be.
float blended(glm::vec2 uv, glm::vec2 shift, float sharpness)
{
    const shading::StochasticTaps t = shading::stochasticTaps(uv, shift, sharpness);
    auto g = [](glm::vec2 q) { return std::sin(6.2831853f * q.x) + std::cos(6.2831853f * q.y); };
    return g(uv + t.offset0) * t.weights.x + g(uv + t.offset1) * t.weights.y + g(uv + t.offset2) * t.weights.z;
}

TEST(AntiTiling, WeightsAreFiniteAndSumToOneAtAnySharpness)
{
    for (float sharpness : {1.0f, 4.0f, 16.0f}) {
        for (int i = 0; i < 2000; ++i) {
            const glm::vec2 uv(float(i) * 0.0137f - 9.0f, float(i % 89) * 0.061f - 2.0f);
            const shading::StochasticTaps t = shading::stochasticTaps(uv, glm::vec2(0.0f), sharpness);
            const float sum = t.weights.x + t.weights.y + t.weights.z;
            ASSERT_NEAR(sum, 1.0f, 1e-5f);
            for (int c = 0; c < 3; ++c) {
                ASSERT_TRUE(t.weights[c] >= 0.0f && t.weights[c] <= 1.0f);
            }
            for (glm::vec2 o : {t.offset0, t.offset1, t.offset2}) {
                ASSERT_TRUE(o.x >= 0.0f && o.x < 1.0f && o.y >= 0.0f && o.y < 1.0f);
            }
        }
    }
    // At a lattice corner that corner alone counts.
    const shading::StochasticTaps corner = shading::stochasticTaps(glm::vec2(3.0f, -2.0f), glm::vec2(0.0f), 4.0f);
    EXPECT_FLOAT_EQ(corner.weights.x, 1.0f);
}

TEST(AntiTiling, TheBlendIsContinuousAcrossCellAndTriangleEdges)
{
    const float e = 1e-4f;
    for (float sharpness : {1.0f, 4.0f, 16.0f}) {
        for (int i = 0; i < 50; ++i) {
            const float s = float(i) * 0.0199f;
            // A vertical and a horizontal cell border, and the diagonal.
            EXPECT_NEAR(blended({5.0f - e, s}, {}, sharpness), blended({5.0f + e, s}, {}, sharpness), 0.01f);
            EXPECT_NEAR(blended({s, -3.0f - e}, {}, sharpness), blended({s, -3.0f + e}, {}, sharpness), 0.01f);
            const glm::vec2 d(2.0f + s, 7.0f + 1.0f - s);
            EXPECT_NEAR(blended(d - glm::vec2(e), {}, sharpness), blended(d + glm::vec2(e), {}, sharpness), 0.01f);
        }
    }
}

TEST(AntiTiling, DroppedRepeatsMoveTheLatticeWithTheWorld)
{
    // A host that drops k whole repeats from UV and passes k as the shift
    // gets the same taps: the pattern belongs to the world, not the mesh.
    for (int k : {1, 255, 256, 1000, -3, -7000}) {
        for (int i = 0; i < 40; ++i) {
            const glm::vec2 uv(float(i) * 0.173f + 0.01f, float(i % 7) * 0.31f + 0.02f);
            const shading::StochasticTaps a = shading::stochasticTaps(uv + glm::vec2(float(k), 0.0f), glm::vec2(0.0f), 4.0f);
            const float wrapped = float(((k % 256) + 256) % 256);
            const shading::StochasticTaps b = shading::stochasticTaps(uv, glm::vec2(wrapped, 0.0f), 4.0f);
            EXPECT_EQ(a.offset0, b.offset0) << k;
            EXPECT_EQ(a.offset2, b.offset2) << k;
            EXPECT_NEAR(a.weights.x, b.weights.x, 2e-3f) << k; // uv + k rounds at large k
        }
    }
}

/// A sampler of one repeating albedo (no other maps).
struct StripeMaps
{
    mutable std::uint32_t features = feature::ANTI_TILING;
    glm::vec4 sample(int, glm::vec2 uv, glm::vec2, glm::vec2) const
    {
        const float u = uv.x - std::floor(uv.x), v = uv.y - std::floor(uv.y);
        return glm::vec4(u, v, 0.5f, 1.0f);
    }
    void select(int, std::uint32_t f) const { features = f; }
};

TEST(AntiTiling, RepeatsNoLongerRepeat)
{
    shading::MaterialParams m = strata::render::detail::toShading(Material{});
    shading::SurfaceInput s{};
    s.n = glm::vec3(0.0f, 1.0f, 0.0f);
    s.viewDir = s.n;
    s.dpdx = glm::vec3(0.001f, 0.0f, 0.0f);
    s.dpdy = glm::vec3(0.0f, 0.0f, 0.001f);
    int differ = 0;
    for (int i = 0; i < 100; ++i) {
        s.p = glm::vec3(float(i) * 0.37f, 0.0f, float(i % 13) * 0.29f);
        shading::SurfaceInput next = s;
        next.p.x += 1.0f; // one repeat further
        StripeMaps off;
        off.features = 0;
        EXPECT_LT(glm::length(shading::evaluateSurface<feature::ALL>(off, s, m).albedo -
                              shading::evaluateSurface<feature::ALL>(off, next, m).albedo),
                  1e-5f); // the same texel one repeat on
        StripeMaps on;
        const glm::vec3 a = shading::evaluateSurface<feature::ALL>(on, s, m).albedo;
        const glm::vec3 b = shading::evaluateSurface<feature::ALL>(on, next, m).albedo;
        differ += glm::length(a - b) > 0.05f;
    }
    EXPECT_GT(differ, 80);
}

EglContext& context()
{
    static std::unique_ptr<EglContext> shared = EglContext::create();
    return *shared;
}

TEST(AntiTiling, GlMatchesTheCpuAndTheWorldAnchorsThePattern)
{
    const TestMesh box = strata::test::makeBox(glm::vec3(-2.0f), glm::vec3(2.0f));
    SnapshotOptions options = strata::test::goldenOptions(box, "normal-whiteout", 480, 270);
    options.material.antiTiling = true;
    CpuRenderStats on, off;
    const Image cpu = renderSnapshotCpu(box.view(), options, &on);
    const Image gl = renderSnapshot(context(), box.view(), options);
    SnapshotOptions plain = options;
    plain.material.antiTiling = false;
    const Image cpuPlain = renderSnapshotCpu(box.view(), plain, &off);
    const double parity = psnr(gl, cpu);
    const double fetchRatio = double(on.textureFetches) / double(off.textureFetches);
    std::cout << "[ anti-til ] against plain tiling " << psnr(cpu, cpuPlain) << " dB; fetches x" << fetchRatio
              << std::endl;
    STRATA_EXPECT_PARITY(parity, 53.07, "anti-tiling box"); // measured 53.07 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    EXPECT_LT(psnr(cpu, cpuPlain), 30.0); // it changes the look
    EXPECT_NEAR(fetchRatio, 3.0, 0.01);   // albedo, mask and normal: three taps each
    // The naive count knows the three taps: what was fetched stays within it
    // (it counted one tap a projection, and the report said 1.6e14 % skipped).
    EXPECT_LE(on.textureFetches, on.naiveFetches);
    EXPECT_LE(off.textureFetches, off.naiveFetches);
    EXPECT_EQ(on.naiveFetches, 3 * off.naiveFetches);

    // The same world box seen from a mesh origin 1234.5 m away (not a whole
    // number of 256 repeats): the same image, since the lattice follows the
    // world.
    const glm::dvec3 origin(1234.5, -617.25, 987.75);
    TestMesh moved = box;
    for (glm::vec3& p : moved.positions) p = glm::vec3(glm::dvec3(p) - origin);
    strata::render::MeshView view = moved.view();
    view.origin = origin;
    const Image far = renderSnapshotCpu(view, options);
    EXPECT_GE(psnr(far, cpu), 45.0);
}

} // namespace
