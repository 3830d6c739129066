// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// gl_device_probe: the golden scenes (GoldenScenes.h) rendered by the GL
// renderer through EGL and by the CPU reference renderer, compared pixel by
// pixel, with the GL context's description and the time of each. For a
// machine with a GPU that has none of Strata's build dependencies: it is
// linked with --as-needed and touches no image file code, so it needs only
// EGL/GL (libglvnd), libepoxy, TBB and the C++ runtime beside it
// (docs/testing.md, "A real GPU"). Writes nothing unless given a folder,
// where it leaves each scene's two images as binary PPM.
//   gl_device_probe [OUT_DIR]

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>

#include "GoldenScenes.h"
#include "TestMeshes.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace {

using namespace strata::render;

/// PSNR over RGB (dB), as render::psnr() (not linked here: it lives beside
/// the image file code).
double psnrRgb(const Image& a, const Image& b)
{
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4)
        for (int c = 0; c < 3; ++c, ++n) {
            const double d = double(a.pixels[i + c]) - double(b.pixels[i + c]);
            sum += d * d;
        }
    const double mse = sum / double(n);
    return mse == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / mse);
}

/// The fraction of pixels whose RGB all lie within `tolerance`.
double within(const Image& a, const Image& b, int tolerance)
{
    std::size_t good = 0;
    for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
        bool ok = true;
        for (int c = 0; c < 3; ++c) ok = ok && std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) <= tolerance;
        good += ok;
    }
    return double(good) / double(a.pixels.size() / 4);
}

void writePpm(const Image& image, const std::string& path)
{
    std::ofstream out(path, std::ios::binary);
    out << "P6\n" << image.width << " " << image.height << "\n255\n";
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) out.write(reinterpret_cast<const char*>(&image.pixels[i]), 3);
}

double secondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int main(int argc, char** argv)
{
    const std::string out = argc > 1 ? argv[1] : "";
    try {
        auto context = EglContext::create();
        std::printf("context  %s\n", context->description().c_str());
        double worst = INFINITY;
        for (const std::string& shape : strata::test::GOLDEN_SHAPES)
            for (const std::string& variant : strata::test::GOLDEN_VARIANTS) {
                const strata::test::TestMesh mesh = shape == "sphere"
                                                        ? strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32)
                                                        : strata::test::makeBox(glm::vec3(-1.5f), glm::vec3(1.5f));
                const SnapshotOptions options = strata::test::goldenOptions(mesh, variant, 640, 360);
                auto start = std::chrono::steady_clock::now();
                const Image gl = renderSnapshot(*context, mesh.view(), options);
                const double glSeconds = secondsSince(start);
                start = std::chrono::steady_clock::now();
                const Image cpu = renderSnapshotCpu(mesh.view(), options);
                const double cpuSeconds = secondsSince(start);
                const double db = psnrRgb(gl, cpu);
                worst = std::min(worst, db);
                std::printf("%-24s %6.2f dB  %6.2f%% within 2/255  GL %7.1f ms  CPU %7.1f ms\n",
                            (shape + "-" + variant).c_str(), db, 100.0 * within(gl, cpu, 2), glSeconds * 1e3,
                            cpuSeconds * 1e3);
                if (!out.empty()) {
                    writePpm(gl, out + "/" + shape + "-" + variant + "-gl.ppm");
                    writePpm(cpu, out + "/" + shape + "-" + variant + "-cpu.ppm");
                }
            }
        std::printf("lowest   %.2f dB\n", worst);
        // Where GL and the CPU part: the same two scenes with the level of
        // detail from llvmpipe's approximate log2 on the CPU, and with the
        // nearest mip level on both (no trilinear blend).
        for (const std::string& shape : strata::test::GOLDEN_SHAPES) {
            const strata::test::TestMesh mesh = shape == "sphere"
                                                    ? strata::test::makeUvSphere(glm::vec3(0.0f), 2.0f, 64, 32)
                                                    : strata::test::makeBox(glm::vec3(-1.5f), glm::vec3(1.5f));
            SnapshotOptions options = strata::test::goldenOptions(mesh, "full", 640, 360);
            options.cpuLodLog2 = LodLog2::Llvmpipe;
            std::printf("%-24s %6.2f dB  (CPU on llvmpipe's log2)\n", (shape + "-full").c_str(),
                        psnrRgb(renderSnapshot(*context, mesh.view(), options), renderSnapshotCpu(mesh.view(), options)));
            options.cpuLodLog2 = LodLog2::Exact;
            options.filtering = TextureFilter::Bilinear;
            std::printf("%-24s %6.2f dB  (nearest mip level on both)\n", (shape + "-full").c_str(),
                        psnrRgb(renderSnapshot(*context, mesh.view(), options), renderSnapshotCpu(mesh.view(), options)));
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "gl_device_probe: %s\n", e.what());
        return 1;
    }
}
