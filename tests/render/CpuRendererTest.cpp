// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The CPU reference renderer: rasterization rules, determinism, agreement
// with the GL renderer, and golden images.
//
// Golden images live in tests/render/golden/. Regenerate them (after a
// deliberate change of the shading or of the test materials) with
//   STRATA_UPDATE_GOLDEN=1 <build>/tests/render/render_tests --gtest_filter='*CpuRendererGolden*'
// and look at the PNGs before committing them.

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include "GoldenScenes.h"
#include "TestContext.h"
#include "TestDir.h"
#include "TestMeshes.h"

#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace strata::render;
using strata::test::TestMesh;
using strata::test::circuitryMaterial;
using strata::test::goldenOptions;

struct Difference
{
    int maxChannel = 0;
    double mean = 0.0;
    double fractionOver8 = 0.0;
};

Difference compare(const Image& a, const Image& b)
{
    Difference d;
    std::size_t over = 0;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        const int diff = std::abs(int(a.pixels[i]) - int(b.pixels[i]));
        d.maxChannel = std::max(d.maxChannel, diff);
        sum += diff;
        over += diff > 8;
    }
    d.mean = sum / double(a.pixels.size());
    d.fractionOver8 = double(over) / double(a.pixels.size());
    return d;
}

std::filesystem::path goldenDir()
{
    return std::filesystem::path(STRATA_GOLDEN_DIR);
}

class CpuRendererGolden : public ::testing::TestWithParam<std::tuple<std::string, std::string>>
{
};

TEST_P(CpuRendererGolden, MatchesTheStoredImage)
{
    const auto& [shape, variant] = GetParam();
    const TestMesh mesh = shape == "sphere" ? strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32)
                                            : strata::test::makeBox(glm::vec3(-1.5f), glm::vec3(1.5f));
    const Image image = renderSnapshotCpu(mesh.view(), goldenOptions(mesh, variant));
    const std::filesystem::path golden = goldenDir() / (shape + "-" + variant + ".png");
    const char* update = std::getenv("STRATA_UPDATE_GOLDEN");
    if (update && std::string(update) == "1") {
        std::filesystem::create_directories(goldenDir());
        writeImage(image, golden);
        GTEST_SKIP() << "wrote " << golden;
    }
    ASSERT_TRUE(std::filesystem::exists(golden)) << golden << " is missing; see the top of CpuRendererTest.cpp";
    const Image expected = readImage(golden);
    ASSERT_EQ(expected.width, image.width);
    ASSERT_EQ(expected.height, image.height);
    const Difference d = compare(image, expected);
    if (d.mean > 0.5 || d.fractionOver8 > 0.002) {
        writeImage(image, strata::test::freshTestDir() / golden.filename());
    }
    // Tolerance: other compilers and libm may move a few values by a byte or
    // two, and an edge pixel can flip; a real change moves far more.
    EXPECT_LE(d.mean, 0.5) << golden;
    EXPECT_LE(d.fractionOver8, 0.002) << golden;
}

INSTANTIATE_TEST_SUITE_P(CircuitryFeatureSets, CpuRendererGolden,
                         ::testing::Combine(::testing::ValuesIn(strata::test::GOLDEN_SHAPES),
                                            ::testing::ValuesIn(strata::test::GOLDEN_VARIANTS)),
                         [](const auto& info) { return strata::test::goldenTestName(info.param); });

TEST(CpuRenderer, FeatureSetsOfTheGoldenMaterials)
{
    EXPECT_EQ(materialFeatures(circuitryMaterial("albedo")), 0u);
    EXPECT_EQ(materialFeatures(circuitryMaterial("mohs-height")), feature::MASK_MAP | feature::HEIGHT_BLEND);
    EXPECT_EQ(materialFeatures(circuitryMaterial("normal-rnm")),
              feature::MASK_MAP | feature::HEIGHT_BLEND | feature::NORMAL_MAP | feature::NORMAL_RNM);
    EXPECT_EQ(featureNames(materialFeatures(circuitryMaterial("full"))),
              "mask+height+normal+top+detail+detail-normal+emission");
}

TEST(CpuRenderer, BitwiseIdenticalOnAnyThreadCount)
{
    const TestMesh mesh = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 48, 24);
    SnapshotOptions options = goldenOptions(mesh, "full");
    options.width = 200;
    options.height = 150;
    Image one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = renderSnapshotCpu(mesh.view(), options);
    }
    for (int run = 0; run < 3; ++run) {
        const Image many = renderSnapshotCpu(mesh.view(), options);
        ASSERT_EQ(one.pixels, many.pixels);
    }
}

/// Two triangles sharing a diagonal through pixel centres leave no gap: the
/// covered area is exactly the square's 32² pixels.
TEST(CpuRenderer, SharedEdgesCoverEveryPixelExactlyOnce)
{
    // A square of side 2 in the z = 0 plane facing +Z, split along a diagonal;
    // the camera looks straight at it so its corners land on pixel corners.
    TestMesh mesh;
    mesh.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    mesh.normals.assign(4, glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2, 0, 2, 3};
    SnapshotOptions options;
    options.width = 64;
    options.height = 64;
    options.camera.position = glm::dvec3(0.0, 0.0, 4.0);
    options.camera.target = glm::dvec3(0.0);
    options.camera.fovYDegrees = 2.0 * glm::degrees(std::atan(0.5)); // the square fills half the view
    options.camera.nearPlane = 1.0;
    options.camera.farPlane = 10.0;
    const Image image = renderSnapshotCpu(mesh.view(), options);
    const glm::vec3 sky = options.lighting.skyColor;
    const Image skyOnly = renderSnapshotCpu(MeshView{}, options);
    int covered = 0;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            covered += image.at(x, y)[2] != skyOnly.at(x, y)[2] || image.at(x, y)[0] != skyOnly.at(x, y)[0];
        }
    }
    (void)sky;
    // The square spans exactly pixels 16..47 on both axes: 32² pixels.
    EXPECT_EQ(covered, 32 * 32);
    EXPECT_NE(image.at(16, 16)[0], skyOnly.at(16, 16)[0]);
    EXPECT_EQ(image.at(15, 16)[0], skyOnly.at(15, 16)[0]);
    EXPECT_EQ(image.at(48, 47)[0], skyOnly.at(48, 47)[0]);
}

TEST(CpuRenderer, TopLeftRuleOnPixelCentres)
{
    // A square whose edges pass exactly through pixel centres: the left and
    // top edges' pixels are in, the right and bottom edges' are out.
    TestMesh mesh;
    // The square −1..1 spans pixels 16..47 (16 px per unit); shift it by half a pixel.
    const float s = 1.0f;
    const float shift = 1.0f / 32.0f;
    mesh.positions = {
        {-s + shift, -s - shift, 0}, {s + shift, -s - shift, 0}, {s + shift, s - shift, 0}, {-s + shift, s - shift, 0}};
    mesh.normals.assign(4, glm::vec3(0, 0, 1));
    mesh.indices = {0, 1, 2, 0, 2, 3};
    SnapshotOptions options;
    options.width = 64;
    options.height = 64;
    options.samples = 1; // the rule at pixel centres (multisampling: CpuMsaaTest.cpp)
    options.camera.position = glm::dvec3(0.0, 0.0, 4.0);
    options.camera.target = glm::dvec3(0.0);
    options.camera.fovYDegrees = 2.0 * glm::degrees(std::atan(0.5));
    options.camera.nearPlane = 1.0;
    options.camera.farPlane = 10.0;
    const Image image = renderSnapshotCpu(mesh.view(), options);
    const Image skyOnly = renderSnapshotCpu(MeshView{}, options);
    auto in = [&](int x, int y) {
        return image.at(x, y)[0] != skyOnly.at(x, y)[0] || image.at(x, y)[2] != skyOnly.at(x, y)[2];
    };
    int covered = 0;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) covered += in(x, y);
    }
    EXPECT_EQ(covered, 32 * 32);
    // Shifted right and down by half a pixel: the left edge passes through the
    // centres of column 16 (in), the right edge through column 48 (out), the
    // top edge through row 16's centres (in), the bottom edge through row 48's (out).
    EXPECT_TRUE(in(16, 30));
    EXPECT_FALSE(in(15, 30));
    EXPECT_TRUE(in(47, 30));
    EXPECT_FALSE(in(48, 30));
    EXPECT_TRUE(in(30, 16));
    EXPECT_FALSE(in(30, 15));
    EXPECT_TRUE(in(30, 47));
    EXPECT_FALSE(in(30, 48));
}

TEST(CpuRenderer, AgreesWithTheGlRenderer)
{
    // Never skipped: without an EGL context (Mesa llvmpipe, installed by
    // scripts/install-deps.sh) this fails naming what is missing.
    const std::unique_ptr<EglContext> context = strata::test::createContext();
    ASSERT_TRUE(context);
    const TestMesh mesh = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32);
    for (const char* variant : {"albedo", "normal-whiteout", "full"}) {
        SnapshotOptions options = goldenOptions(mesh, variant);
        const Image cpu = renderSnapshotCpu(mesh.view(), options);
        const Image gl = renderSnapshot(*context, mesh.view(), options);
        const Difference d = compare(cpu, gl);
        if (d.mean > 1.0) {
            const auto dir = strata::test::freshTestDir();
            writeImage(cpu, dir / (std::string(variant) + "-cpu.png"));
            writeImage(gl, dir / (std::string(variant) + "-gl.png"));
        }
        // Same math; rasterization and filtering precision differ slightly.
        EXPECT_LE(d.mean, 1.0) << variant;
        EXPECT_LE(d.fractionOver8, 0.02) << variant;
    }
}

TEST(CpuRenderer, EveryFeatureCombinationCompilesOnGlAndAgrees)
{
    // Never skipped: without an EGL context (Mesa llvmpipe, installed by
    // scripts/install-deps.sh) this fails naming what is missing.
    const std::unique_ptr<EglContext> context = strata::test::createContext();
    ASSERT_TRUE(context);
    const TestMesh mesh = strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 24, 12);
    const Material full = circuitryMaterial("full");
    // Each map present or not (9 bits would be 512 programs; every single map
    // alone, every map but one, and the layouts and blends cover all code).
    TexturePtr Material::*const slots[] = {&Material::mask,   &Material::normal,       &Material::topAlbedo,
                                           &Material::detail, &Material::detailNormal, &Material::emission};
    std::vector<Material> materials;
    for (int i = 0; i < 6; ++i) {
        Material alone = full;
        Material allBut = full;
        for (int j = 0; j < 6; ++j) {
            if (j != i) alone.*slots[j] = nullptr;
        }
        alone.topMask = alone.topNormal = nullptr;
        allBut.*slots[i] = nullptr;
        materials.push_back(alone);
        materials.push_back(allBut);
    }
    Material mods = full;
    mods.maskLayout = MaskLayout::Mods;
    materials.push_back(mods);
    for (NormalBlend blend : {NormalBlend::Udn, NormalBlend::Rnm}) {
        Material m = full;
        m.normalBlend = blend;
        materials.push_back(m);
    }
    for (const Material& material : materials) {
        SnapshotOptions options;
        options.width = 64;
        options.height = 64;
        options.samples = 1;
        options.camera = orbitCamera(glm::dvec3(-2.0), glm::dvec3(2.0), 20.0, 30.0);
        options.material = material;
        const Image gl = renderSnapshot(*context, mesh.view(), options);
        const Image cpu = renderSnapshotCpu(mesh.view(), options);
        const Difference d = compare(cpu, gl);
        EXPECT_LE(d.mean, 1.5) << featureNames(materialFeatures(material));
    }
}

TEST(CpuRenderer, RejectsBadInput)
{
    const TestMesh box = strata::test::makeBox(glm::vec3(-1.0f), glm::vec3(1.0f));
    SnapshotOptions options;
    options.width = 16;
    options.height = 16;
    SnapshotOptions bad = options;
    bad.material.blendOffset = 0.7f;
    EXPECT_THROW(renderSnapshotCpu(box.view(), bad), strata::Error);
    TestMesh broken = box;
    broken.indices[2] = 99;
    EXPECT_THROW(renderSnapshotCpu(broken.view(), options), strata::Error);
    // An empty mesh is the sky.
    const Image sky = renderSnapshotCpu(MeshView{}, options);
    EXPECT_EQ(sky.at(0, 0)[3], 255);
}

} // namespace
