// Render times per feature set at 1280x720, CPU and GL, on the ~200k-triangle
// heightfield with cliffs, with the built-in texture sets (512²).
// Not a test (no timing assertions anywhere): a tool for the numbers in the
// README.
//
//   cmake --build <dir> --target render_benchmark && <dir>/tests/render/render_benchmark [runs]

#include <strata/Error.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

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

double height(double x, double z)
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
    const int n = 317;
    const double size = 64.0;
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;
    for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
            const double x = (double(i) / (n - 1) - 0.5) * size;
            const double z = (double(j) / (n - 1) - 0.5) * size;
            const double e = 0.01;
            const double dx = (height(x + e, z) - height(x - e, z)) / (2 * e);
            const double dz = (height(x, z + e) - height(x, z - e)) / (2 * e);
            positions.emplace_back(float(x), float(height(x, z)), float(z));
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
    m.detail = makeTexture(rock.detail, MapKind::Detail);
    cases.push_back({"  + detail", m});
    m.detailNormal = makeTexture(rock.normal, MapKind::DetailNormal);
    m.emission = makeTexture(circuit.emission, MapKind::Emission);
    cases.push_back({"  + detail normal + emission (all)", m});

    std::unique_ptr<EglContext> context;
    try {
        context = EglContext::create();
        std::printf("GL: %s\n", context->description().c_str());
    } catch (const strata::Error& e) {
        std::printf("GL: unavailable (%s)\n", e.what());
    }
    SnapshotOptions options;
    options.camera =
        orbitCamera(glm::dvec3(-24.0, 0.0, -24.0), glm::dvec3(24.0, 12.0, 24.0), 35.0, 28.0, 50.0, 1280.0 / 720.0);
    auto median = [&](auto&& render) {
        std::vector<double> ms;
        for (int r = 0; r < runs; ++r) {
            const auto t0 = Clock::now();
            render();
            ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        return ms[ms.size() / 2];
    };
    std::printf("1280x720, %zu triangles, median of %d runs (ms)\n", mesh.indexCount / 3, runs);
    std::printf("%-42s %-40s %8s %10s %10s\n", "feature set", "bits", "CPU", "GL 1x", "GL 4xMSAA");
    for (const Case& c : cases) {
        options.material = c.material;
        const double cpu = median([&] { renderSnapshotCpu(mesh, options); });
        double gl1 = -1.0, gl4 = -1.0;
        if (context) {
            options.samples = 1;
            renderSnapshot(*context, mesh, options); // warm-up: shader compile
            gl1 = median([&] { renderSnapshot(*context, mesh, options); });
            options.samples = 4;
            gl4 = median([&] { renderSnapshot(*context, mesh, options); });
        }
        std::printf("%-42s %-40s %8.0f %10.0f %10.0f\n", c.name, featureNames(materialFeatures(c.material)).c_str(),
                    cpu, gl1, gl4);
    }
    return 0;
}
