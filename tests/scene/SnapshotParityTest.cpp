// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The default scene as `strata generate` renders it (640×360, the scene's 4×
// MSAA, its atmosphere, llvmpipe with its default settings: no driver
// variables), on GL through EGL against the CPU reference renderer with the
// same 4× MSAA. Parity is measured on terrain pixels only: the sky is the
// same formula on both sides (Atmosphere.h) and would inflate a whole-frame
// figure. A terrain pixel is one where the image differs from the same view
// rendered without the mesh. Both figures are printed.

#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>

#include "Parity.h"
#include "TestDir.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <limits>
#include <vector>

namespace {

using namespace strata;

/// PSNR over the pixels where `mask` is set (RGB, 8 bits); +inf when equal.
double maskedPsnr(const render::Image& a, const render::Image& b, const std::vector<bool>& mask)
{
    double sum = 0.0;
    std::size_t count = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            if (!mask[std::size_t(y) * std::size_t(a.width) + std::size_t(x)]) continue;
            for (int c = 0; c < 3; ++c) {
                const double d = double(a.at(x, y)[c]) - double(b.at(x, y)[c]);
                sum += d * d;
            }
            count += 3;
        }
    }
    if (count == 0) return std::numeric_limits<double>::quiet_NaN();
    if (sum == 0.0) return std::numeric_limits<double>::infinity();
    return 10.0 * std::log10(255.0 * 255.0 / (sum / double(count)));
}

TEST(SnapshotParity, DefaultSceneOnGlMatchesTheCpuWithMsaaOnTerrainPixels)
{
    ASSERT_EQ(std::getenv("GALLIVM_PERF"), nullptr) << "measured with llvmpipe's default settings";

    const scene::Scene input = scene::parseScene(scene::defaultSceneText(), "<default scene>");
    const scene::QualitySettings quality = scene::resolveQuality(input, std::nullopt, {});
    const scene::Scene s = scene::applyQuality(input, quality);
    const scene::SampledTerrain terrain = scene::sampleTerrain(s);
    const meshing::TriangleMesh mesh = scene::meshTerrain(s, quality, terrain);
    render::SnapshotOptions options = scene::makeSnapshotOptions(s, mesh, 640, 360);
    ASSERT_EQ(options.samples, 4);
    ASSERT_TRUE(options.lighting.atmosphere.enabled);
    const render::MeshView view = scene::meshView(mesh);
    render::MeshView empty = view;
    empty.indexCount = 0;

    const auto context = render::EglContext::create();
    const render::Image gl = render::renderSnapshot(*context, view, options);
    const render::Image cpu = render::renderSnapshotCpu(view, options);
    const render::Image sky = render::renderSnapshotCpu(empty, options);
    const render::Image glSky = render::renderSnapshot(*context, empty, options);
    std::vector<bool> terrainPixels(std::size_t(gl.width) * std::size_t(gl.height));
    std::size_t terrainCount = 0;
    for (int y = 0; y < gl.height; ++y) {
        for (int x = 0; x < gl.width; ++x) {
            bool differs = false;
            for (int c = 0; c < 3; ++c) differs = differs || cpu.at(x, y)[c] != sky.at(x, y)[c];
            terrainPixels[std::size_t(y) * std::size_t(gl.width) + std::size_t(x)] = differs;
            terrainCount += differs;
        }
    }
    const double terrainDb = maskedPsnr(gl, cpu, terrainPixels);
    const double wholeDb = render::psnr(gl, cpu);
    const double skyDb = render::psnr(glSky, sky);
    std::cout << "[ parity   ] default scene 640x360, 4x MSAA: terrain pixels (" << terrainCount << ") PSNR "
              << std::fixed << std::setprecision(2) << terrainDb << " dB; whole frame " << wholeDb
              << " dB; the sky alone " << skyDb << " dB; within 2/255: " << std::setprecision(3)
              << render::fractionWithin(gl, cpu, 2) * 100.0 << "%" << std::endl;
    EXPECT_GT(terrainCount, std::size_t(640 * 360 / 3));
    // Measured 53.60 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(terrainDb, 53.60, "default scene, terrain pixels");
    // Measured 56.51 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(wholeDb, 56.51, "default scene, whole frame");
    // Measured 60.02 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(skyDb, 60.02, "default scene, the sky alone");
    if (!(terrainDb >= strata::test::parityFloor(53.60))) {
        const auto dir = test::freshTestDir();
        render::writeImage(gl, dir / "gl.png");
        render::writeImage(cpu, dir / "cpu.png");
        std::cout << "  wrote " << dir.string() << std::endl;
    }
}

} // namespace
