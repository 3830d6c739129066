// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Render benchmark (not a test: no timing assertions anywhere), on the
// ~200k-triangle heightfield with cliffs and the built-in texture sets (512²):
//  1. start-up of the GL path, split: EGL context creation, mesh and texture
//     upload, shader compilation (glCompileShader/glLinkProgram), first frame
//     (llvmpipe JIT-compiles the program at its first draw), read-back, PNG
//     write; Mesa's on-disk shader cache is disabled so the compile figures
//     are those of a cold start;
//  2. frame time per feature set (albedo only -> everything) at WIDTHxHEIGHT
//     (default 1920x1080): GL with the persistent GlRenderer (draw + glFinish,
//     1 sample and 4x MSAA, the program compiled beforehand) versus the CPU
//     reference renderer (renderSnapshotCpu, 1 and 4 samples per pixel);
//  3. texture fetches per pixel per feature set, counted analytically: each
//     projection with a non-zero blend weight samples every enabled map once
//     (textureGrad, trilinear: 8 texels each), so fetches per shaded pixel =
//     k · (1 + mask + normal + detail + detail-normal + emission), where k, the
//     mean number of projections with a non-zero weight, is measured on the
//     same view through the triplanar-weights debug view (GL); layered
//     materials break this count, so the last column gives the fetches the
//     CPU renderer really made per shaded pixel.
//
//   cmake --build <dir> --target render_benchmark && <dir>/tests/render/render_benchmark [runs] [WIDTHxHEIGHT]

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include <filesystem>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

double smoothstep(double a, double b, double x)
{
    const double t = std::fmin(std::fmax((x - a) / (b - a), 0.0), 1.0);
    return t * t * (3.0 - 2.0 * t);
}

double terrainHeight(double x, double z)
{
    double h = 1.5 * std::sin(x * 0.11) * std::cos(z * 0.09) + 0.6 * std::sin(x * 0.31 + z * 0.17);
    const double mesa = 11.0 - std::hypot(x - 6.0, z + 4.0) + 1.8 * std::sin(x * 0.35) * std::cos(z * 0.3);
    h += 10.0 * smoothstep(-0.5, 0.5, mesa);
    const double terrace = 20.0 - std::hypot(x + 10.0, z - 12.0) + 1.2 * std::sin(z * 0.5);
    h += 4.0 * smoothstep(-0.4, 0.4, terrace);
    return h;
}

} // namespace

int main(int argc, char** argv)
{
    using namespace strata::render;
    using Clock = std::chrono::steady_clock;
    const int runs = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
    int width = 1920;
    int height = 1080;
    if (argc > 2 && std::sscanf(argv[2], "%dx%d", &width, &height) != 2) {
        std::fprintf(stderr, "usage: render_benchmark [runs] [WIDTHxHEIGHT]\n");
        return 2;
    }
    // Cold-start compile figures: no on-disk shader cache (set before EGL loads Mesa).
    ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
    const int n = 317;
    const double size = 64.0;
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double x = (double(i) / (n - 1) - 0.5) * size;
            const double z = (double(j) / (n - 1) - 0.5) * size;
            const double e = 0.01;
            const double dx = (terrainHeight(x + e, z) - terrainHeight(x - e, z)) / (2 * e);
            const double dz = (terrainHeight(x, z + e) - terrainHeight(x, z - e)) / (2 * e);
            positions.emplace_back(float(x), float(terrainHeight(x, z)), float(z));
            normals.push_back(glm::normalize(glm::vec3(float(-dx), 1.0f, float(-dz))));
        }
    }
    for (int j = 0; j + 1 < n; ++j) {
        for (int i = 0; i + 1 < n; ++i) {
            const auto a = std::uint32_t(j * n + i);
            indices.insert(indices.end(),
                           {a, a + std::uint32_t(n), a + 1, a + 1, a + std::uint32_t(n), a + std::uint32_t(n) + 1});
        }
    }
    MeshView mesh;
    mesh.positions = positions.data();
    mesh.normals = normals.data();
    mesh.vertexCount = positions.size();
    mesh.indices = indices.data();
    mesh.indexCount = indices.size();

    const TextureSetImages rock = makeBuiltinSet(BuiltinSet::Rock, 512, 7);
    const TextureSetImages grass = makeBuiltinSet(BuiltinSet::Grass, 512, 7);
    const TextureSetImages circuit = makeBuiltinSet(BuiltinSet::Circuitry, 512, 7);

    struct Case
    {
        const char* name;
        Material material;
    };
    std::vector<Case> cases;
    Material m;
    m.albedo = makeTexture(rock.albedo, MapKind::Albedo);
    cases.push_back({"albedo", m});
    m.topAlbedo = makeTexture(grass.albedo, MapKind::Albedo);
    cases.push_back({"albedo+top", m});
    m.metallic = 1.0f;
    m.smoothness = 1.0f;
    m.mask = makeTexture(rock.mohs, MapKind::Mask);
    m.topMask = makeTexture(grass.mohs, MapKind::Mask);
    m.heightStrength = 0.6f;
    cases.push_back({"mohs+height+top", m});
    m.normal = makeTexture(rock.normal, MapKind::Normal);
    m.topNormal = makeTexture(grass.normal, MapKind::Normal);
    cases.push_back({"default scene (mohs+height+normal+top)", m});
    Material rnm = m;
    rnm.normalBlend = NormalBlend::Rnm;
    cases.push_back({"  same, RNM normals", rnm});
    Material biplanar = m;
    biplanar.projections = 2;
    cases.push_back({"  same, biplanar", biplanar});
    Material antiTiled = m;
    antiTiled.antiTiling = true;
    cases.push_back({"  same, anti-tiling", antiTiled});
    {
        // The default material under three layers (TerrainLayers.h), each a
        // built-in set with albedo, MOHS and normals: sand low down, soil on
        // the slopes, snow in patches on the heights.
        const TextureSetImages sand = makeBuiltinSet(BuiltinSet::Sand, 512, 7);
        const TextureSetImages soil = makeBuiltinSet(BuiltinSet::Soil, 512, 7);
        const TextureSetImages snow = makeBuiltinSet(BuiltinSet::Snow, 512, 7);
        auto layer = [&](const char* name, const TextureSetImages& set) {
            MaterialLayer l;
            l.name = name;
            l.material.albedo = makeTexture(set.albedo, MapKind::Albedo);
            l.material.mask = makeTexture(set.mohs, MapKind::Mask);
            l.material.normal = makeTexture(set.normal, MapKind::Normal);
            l.material.metallic = 1.0f;
            l.material.smoothness = 1.0f;
            l.material.heightStrength = 0.6f;
            return l;
        };
        Material layered = m;
        MaterialLayer l1 = layer("sand", sand);
        l1.rule.altitude = {true, -1e9f, 1.5f, 1.0f};
        MaterialLayer l2 = layer("soil", soil);
        l2.rule.slope = {true, 25.0f, 50.0f, 8.0f};
        MaterialLayer l3 = layer("snow", snow);
        l3.rule.altitude = {true, 9.0f, 1e9f, 1.5f};
        l3.rule.slope = {true, 0.0f, 30.0f, 8.0f};
        l3.rule.noiseFrequency = 0.15f;
        l3.rule.noiseThreshold = 0.35f;
        layered.layers = {l1, l2, l3};
        cases.push_back({"  default + 3 layers (4 in all)", layered});
        Material two = m;
        two.layers = {l1};
        cases.push_back({"  default + 1 layer (sand)", two});
    }
    m.detail = makeTexture(rock.detail, MapKind::Detail);
    cases.push_back({"  + detail", m});
    m.detailNormal = makeTexture(rock.normal, MapKind::DetailNormal);
    m.emission = makeTexture(circuit.emission, MapKind::Emission);
    cases.push_back({"  + detail normal + emission (all)", m});

    SnapshotOptions options;
    options.width = width;
    options.height = height;
    options.camera = orbitCamera(glm::dvec3(-24.0, 0.0, -24.0), glm::dvec3(24.0, 12.0, 24.0), 35.0, 28.0, 50.0,
                                 double(width) / double(height));
    auto seconds = [](Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); };
    auto median = [&](auto&& render) {
        std::vector<double> ms;
        for (int r = 0; r < runs; ++r) {
            const auto t0 = Clock::now();
            render();
            ms.push_back(1000.0 * seconds(t0));
        }
        std::sort(ms.begin(), ms.end());
        return ms[ms.size() / 2];
    };

    // 1. Start-up, in this fresh process, with the default scene's material.
    std::unique_ptr<EglContext> context;
    std::unique_ptr<GlRenderer> renderer;
    {
        options.material = cases[3].material;
        auto t0 = Clock::now();
        try {
            context = EglContext::create();
        } catch (const strata::Error& e) {
            std::printf("GL: unavailable (%s)\n", e.what());
        }
        const double contextS = seconds(t0);
        if (context) {
            std::printf("GL: %s\n", context->description().c_str());
            t0 = Clock::now();
            renderer = std::make_unique<GlRenderer>(*context);
            renderer->setMesh(mesh);
            renderer->setMaterial(options.material);
            renderer->finish();
            const double uploadS = seconds(t0);
            t0 = Clock::now();
            renderer->prepareProgram(renderer->activeFeatures());
            renderer->finish();
            const double compileS = seconds(t0);
            t0 = Clock::now();
            DrawOptions draw;
            draw.shadows = options.shadows;
            renderer->drawFrame(options.camera, options.lighting, width, height, options.samples, draw);
            renderer->finish();
            const double firstFrameS = seconds(t0);
            t0 = Clock::now();
            renderer->drawFrame(options.camera, options.lighting, width, height, options.samples, draw);
            renderer->finish();
            const double secondFrameS = seconds(t0);
            t0 = Clock::now();
            const Image image = renderer->readFrame();
            const double readS = seconds(t0);
            const std::filesystem::path png = std::filesystem::temp_directory_path() / "strata-render-benchmark.png";
            t0 = Clock::now();
            writeImage(image, png);
            const double pngS = seconds(t0);
            std::filesystem::remove(png);
            std::printf("\nstart-up at %dx%d, %d samples, %s, shadows %s (s):\n", width, height, options.samples,
                        featureNames(renderer->activeFeatures()).c_str(), options.shadows.enabled ? "on" : "off");
            std::printf("  %-44s %8.3f\n", "EGL context creation", contextS);
            std::printf("  %-44s %8.3f\n", "mesh + texture upload", uploadS);
            std::printf("  %-44s %8.3f\n", "shader compilation (compile + link)", compileS);
            std::printf("  %-44s %8.3f\n", "first frame (incl. llvmpipe JIT of the program)", firstFrameS);
            std::printf("  %-44s %8.3f\n", "  (second frame, for comparison)", secondFrameS);
            std::printf("  %-44s %8.3f\n", "read-back", readS);
            std::printf("  %-44s %8.3f\n", "PNG write", pngS);
        }
    }

    // 2. Frame times and 3. texture fetches per feature set.
    std::printf("\n%dx%d, %zu triangles, median of %d runs (ms); GL = persistent renderer, draw + glFinish;\n"
                "fetches = texture fetches per shaded pixel (k = mean projections with weight > 0)\n",
                width, height, mesh.indexCount / 3, runs);
    std::printf("%-40s %-36s %8s %10s %9s %10s %5s %8s %8s\n", "feature set", "bits", "CPU 1x", "CPU 4xMSAA", "GL 1x",
                "GL 4xMSAA", "k", "fetches", "CPU f/px");
    for (const Case& c : cases) {
        options.material = c.material;
        const std::uint32_t f = materialFeatures(c.material);
        options.samples = 1;
        const double cpu1 = median([&] { renderSnapshotCpu(mesh, options); });
        CpuRenderStats counted;
        renderSnapshotCpu(mesh, options, &counted); // fetches the CPU renderer really made, per shaded pixel
        const double cpuFetches =
            counted.shadedPixels ? double(counted.textureFetches) / double(counted.shadedPixels) : 0.0;
        options.samples = 4;
        const double cpu4 = median([&] { renderSnapshotCpu(mesh, options); });
        double gl1 = -1.0, gl4 = -1.0, k = 0.0;
        if (renderer) {
            renderer->setMaterial(c.material);
            DrawOptions draw;
            draw.shadows = options.shadows;
            auto frame = [&](int samples) {
                renderer->drawFrame(options.camera, options.lighting, width, height, samples, draw);
                renderer->finish();
            };
            frame(1); // warm-up: program compile and JIT
            gl1 = median([&] { frame(1); });
            frame(4);
            gl4 = median([&] { frame(4); });
            // k from the weights view: a channel > 0 is a projection in use.
            DrawOptions weights = draw;
            weights.debugView = DebugView::TriplanarWeights;
            renderer->drawFrame(options.camera, options.lighting, width, height, 1, weights);
            const Image w = renderer->readFrame();
            std::size_t pixels = 0, projections = 0;
            DrawOptions shaded = draw;
            renderer->drawFrame(options.camera, options.lighting, width, height, 1, shaded);
            const Image lit = renderer->readFrame();
            for (std::size_t i = 0; i < w.pixels.size(); i += 4) {
                // Terrain pixels: the two views differ (the sky is the same in both).
                const bool terrain = w.pixels[i] != lit.pixels[i] || w.pixels[i + 1] != lit.pixels[i + 1] ||
                                     w.pixels[i + 2] != lit.pixels[i + 2];
                if (!terrain) continue;
                ++pixels;
                projections += (w.pixels[i] > 0) + (w.pixels[i + 1] > 0) + (w.pixels[i + 2] > 0);
            }
            k = pixels ? double(projections) / double(pixels) : 0.0;
        }
        const int maps = 1 + ((f & feature::MASK_MAP) != 0) + ((f & feature::NORMAL_MAP) != 0) +
                         ((f & feature::DETAIL) != 0) + ((f & feature::DETAIL_NORMAL) != 0) +
                         ((f & feature::EMISSION) != 0);
        std::printf("%-40s %-36s %8.0f %10.0f %9.0f %10.0f %5.2f %8.2f %8.2f\n", c.name, featureNames(f).c_str(), cpu1,
                    cpu4, gl1, gl4, k, k * maps, cpuFetches);
    }
    if (renderer) {
        const ProgramStats stats = renderer->stats();
        std::printf("\nGL programs compiled: %d of %d possible variants, %.3f s in compile + link\n", stats.compiled,
                    stats.possible, stats.compileSeconds);
    }
    return 0;
}
