// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// GL versus the CPU reference renderer, whole images: the golden scenes at
// 640×360 (MSAA off on GL, since the CPU takes one sample per pixel) must
// reach each scene's PSNR and fraction of pixels within 2/255 on every
// channel as measured on llvmpipe, less a margin (Parity.h; the values are
// in MEASURED below). Both numbers are printed for every scene. Runs on
// llvmpipe through EGL in CI: never skipped (no EGL is a failure here).

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>

#include "GoldenScenes.h"
#include "Parity.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace strata::render;
using strata::test::TestMesh;

constexpr double MIN_WITHIN_2 = 0.99;

struct Measured
{
    double db;       ///< PSNR, dB
    double within2;  ///< the fraction of pixels within 2/255 on every channel
};

/// Each scene's PSNR and fraction of pixels within 2/255 measured on
/// strata::test::PARITY_MACHINE: GL on Mesa llvmpipe through EGL against the
/// CPU renderer on the specification's log2 path (LodLog2::Exact). Since
/// terrain.frag picks each map's level of detail itself with the CPU's
/// formula (issue 41; textureLod instead of textureGrad) llvmpipe's
/// approximate log2 no longer moves it: 54-63 dB and 99.6-100% of the
/// pixels within 2/255, against 50-53 dB and 95-98% with the driver's level
/// of detail (the table before, at d484e97). Each run asserts the
/// PSNR less PARITY_MARGIN_DB (3 dB) and the fraction less 1 point (at
/// most MIN_WITHIN_2). Measured twice, identical.
const std::map<std::string, Measured> MEASURED = {
    // clang-format off
    {"sphere-albedo", {63.44, 1.0000}},
    {"sphere-mohs-height", {62.09, 0.9999}},
    {"sphere-normal-whiteout", {60.57, 0.9992}},
    {"sphere-normal-udn", {60.66, 0.9994}},
    {"sphere-normal-rnm", {60.33, 0.9991}},
    {"sphere-detail-emission", {57.28, 0.9960}},
    {"sphere-full", {57.19, 0.9964}},
    {"cube-albedo", {59.85, 1.0000}},
    {"cube-mohs-height", {59.27, 1.0000}},
    {"cube-normal-whiteout", {58.01, 0.9997}},
    {"cube-normal-udn", {58.11, 0.9997}},
    {"cube-normal-rnm", {58.01, 0.9997}},
    {"cube-detail-emission", {54.61, 0.9959}},
    {"cube-full", {54.25, 0.9956}},
    {"shadowed-box", {55.02, 0.9962}},
    {"atmosphere", {58.84, 1.0000}},
    {"sphere-full-biplanar", {57.15, 0.9963}},
    // clang-format on
};

EglContext& context()
{
    static std::unique_ptr<EglContext> shared = EglContext::create(); // throws (test fails) without EGL
    return *shared;
}

/// Prints and checks the parity of `gl` and `cpu`; on failure writes both
/// images to a fresh test folder.
void expectParity(const Image& gl, const Image& cpu, const std::string& name)
{
    const double p = psnr(gl, cpu);
    const double within = fractionWithin(gl, cpu, 2);
    std::cout << "[ parity   ] " << std::left << std::setw(28) << name << std::right << " " << std::fixed
              << std::setprecision(3) << within * 100.0 << "% of pixels within 2/255" << std::defaultfloat
              << std::endl;
    const auto measured = MEASURED.find(name);
    ASSERT_NE(measured, MEASURED.end()) << name << " has no measured values in MEASURED";
    STRATA_EXPECT_PARITY(p, measured->second.db, name); // the value measured on PARITY_MACHINE, in MEASURED
    const double minWithin = std::min(MIN_WITHIN_2, measured->second.within2 - 0.01);
    EXPECT_GE(within, minWithin) << name << ": measured " << measured->second.within2 << " on "
                                 << strata::test::PARITY_MACHINE;
    if (!(p >= strata::test::parityFloor(measured->second.db) && within >= minWithin)) {
        const auto dir = strata::test::freshTestDir();
        writeImage(gl, dir / (name + "-gl.png"));
        writeImage(cpu, dir / (name + "-cpu.png"));
        std::cout << "  wrote " << dir.string() << std::endl;
    }
}

/// A ground slab with a box on or over it, one mesh.
TestMesh slabWithBox(glm::vec3 slabLo, glm::vec3 slabHi, glm::vec3 boxLo, glm::vec3 boxHi)
{
    TestMesh mesh = strata::test::makeBox(slabLo, slabHi);
    const TestMesh box = strata::test::makeBox(boxLo, boxHi);
    const auto base = std::uint32_t(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), box.positions.begin(), box.positions.end());
    mesh.normals.insert(mesh.normals.end(), box.normals.begin(), box.normals.end());
    for (std::uint32_t i : box.indices) mesh.indices.push_back(base + i);
    return mesh;
}

class GoldenParity : public ::testing::TestWithParam<std::tuple<std::string, std::string>>
{
};

TEST_P(GoldenParity, GlMatchesTheCpuAt640x360)
{
    const auto& [shape, variant] = GetParam();
    const TestMesh mesh = shape == "sphere" ? strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32)
                                            : strata::test::makeBox(glm::vec3(-1.5f), glm::vec3(1.5f));
    const SnapshotOptions options = strata::test::goldenOptions(mesh, variant, 640, 360);
    ASSERT_EQ(options.samples, 1);
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    const Image cpu = renderSnapshotCpu(mesh.view(), options);
    expectParity(gl, cpu, shape + "-" + variant);
}

INSTANTIATE_TEST_SUITE_P(CircuitryFeatureSets, GoldenParity,
                         ::testing::Combine(::testing::ValuesIn(strata::test::GOLDEN_SHAPES),
                                            ::testing::ValuesIn(strata::test::GOLDEN_VARIANTS)),
                         [](const auto& info) { return strata::test::goldenTestName(info.param); });

/// A box floating over a ground slab, lit from the side: a cast shadow on
/// the ground and self-shadowing; both renderers draw their own shadow maps.
TEST(RenderParity, CastShadowsMatch)
{
    const TestMesh mesh = slabWithBox(glm::vec3(-6.0f, -1.0f, -6.0f), glm::vec3(6.0f, 0.0f, 6.0f),
                                      glm::vec3(-1.5f, 1.5f, -1.5f), glm::vec3(1.5f, 4.5f, 1.5f));
    SnapshotOptions options = strata::test::goldenOptions(mesh, "full", 640, 360);
    options.lighting.sunDirection = glm::vec3(0.5f, 0.6f, 0.3f);
    options.shadows.resolution = 1024;
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    const Image cpu = renderSnapshotCpu(mesh.view(), options);
    expectParity(gl, cpu, "shadowed-box");
    // The shadows are really there: without them, the shadowed pixels (the
    // box's shadow on the slab) are brighter.
    SnapshotOptions unshadowed = options;
    unshadowed.shadows.enabled = false;
    const Image plain = renderSnapshotCpu(mesh.view(), unshadowed);
    int darker = 0;
    for (int y = 0; y < cpu.height; ++y) {
        for (int x = 0; x < cpu.width; ++x) {
            darker += int(plain.at(x, y)[1]) - int(cpu.at(x, y)[1]) > 20;
        }
    }
    std::cout << "  " << darker << " pixels in cast shadow" << std::endl;
    EXPECT_GT(darker, 1500); // measured: 2369 of 230400 (the shadow falls mostly behind the box)
}

/// A 600 m ground slab with a box on it, seen from 6 m up towards a low sun:
/// the sky pass (gradient, glow, the sun's disc) and thick height fog over
/// the distance, both renderers through the same Atmosphere.h.
TEST(RenderParity, AtmosphereMatches)
{
    const TestMesh mesh = slabWithBox(glm::vec3(-300.0f, -1.0f, -300.0f), glm::vec3(300.0f, 0.0f, 300.0f),
                                      glm::vec3(-4.0f, 0.0f, -30.0f), glm::vec3(4.0f, 8.0f, -22.0f));
    SnapshotOptions options = strata::test::goldenOptions(mesh, "full", 640, 360);
    options.camera.position = glm::dvec3(0.0, 6.0, 40.0);
    options.camera.target = glm::dvec3(0.0, 8.0, -100.0);
    options.camera.nearPlane = 0.5;
    options.camera.farPlane = 2000.0;
    options.lighting.sunDirection = glm::vec3(0.15f, 0.12f, -1.0f);
    options.lighting.extraLights.clear();
    options.shadows.resolution = 1024;
    Atmosphere& atmosphere = options.lighting.atmosphere;
    atmosphere.enabled = true;
    atmosphere.fogDensity = 0.008f;
    atmosphere.fogFalloff = 0.05f;
    atmosphere.sunDiscRadius = 2.0f;
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    const Image cpu = renderSnapshotCpu(mesh.view(), options);
    expectParity(gl, cpu, "atmosphere");
    // The sky is not flat (it brightens towards the sun and the horizon) and
    // the fog is there (the far ground is lighter than the near ground).
    EXPECT_NE(std::vector<std::uint8_t>(cpu.at(0, 0), cpu.at(0, 0) + 3),
              std::vector<std::uint8_t>(cpu.at(320, 0), cpu.at(320, 0) + 3));
    const int farGround = int(cpu.at(20, 200)[0]) + cpu.at(20, 200)[1] + cpu.at(20, 200)[2];
    const int nearGround = int(cpu.at(20, 355)[0]) + cpu.at(20, 355)[1] + cpu.at(20, 355)[2];
    std::cout << "  ground brightness (sum of sRGB bytes): far " << farGround << ", near " << nearGround << std::endl;
    EXPECT_GT(farGround, nearGround + 30);
}

/// Biplanar mapping (Material::projections = 2) on both renderers: the
/// same image, fewer fetches than triplanar, close to the triplanar image.
TEST(RenderParity, BiplanarMatchesAndFetchesLess)
{
    const TestMesh mesh = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32);
    SnapshotOptions options = strata::test::goldenOptions(mesh, "full", 640, 360);
    CpuRenderStats triplanarStats, biplanarStats;
    const Image triplanar = renderSnapshotCpu(mesh.view(), options, &triplanarStats);
    options.material.projections = 2;
    const Image gl = renderSnapshot(context(), mesh.view(), options);
    const Image cpu = renderSnapshotCpu(mesh.view(), options, &biplanarStats);
    expectParity(gl, cpu, "sphere-full-biplanar");
    const double perPixelTri = double(triplanarStats.textureFetches) / double(triplanarStats.shadedPixels);
    const double perPixelBi = double(biplanarStats.textureFetches) / double(biplanarStats.shadedPixels);
    const double againstTriplanar = psnr(cpu, triplanar);
    std::cout << "  fetches per shaded pixel: triplanar " << perPixelTri << ", biplanar " << perPixelBi
              << "; biplanar vs triplanar PSNR " << againstTriplanar << " dB" << std::endl;
    EXPECT_LT(perPixelBi, perPixelTri);
    EXPECT_GT(againstTriplanar, 25.0); // a harder blend near the diagonals, the same picture
    EXPECT_LT(againstTriplanar, 100.0); // and not the triplanar image itself
}

} // namespace
