// Renders a ~200k-triangle heightfield with cliffs at 1280x720 through EGL,
// with the procedural rock (sides) and grass (top) textures, and prints the
// timing. Not a test: a tool to look at the renderer's output.
//
//   render_snapshot_demo [output-dir]     (default /tmp/strata-render-demo)

#include <strata/Error.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include <glm/geometric.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

namespace {

double smoothstep(double a, double b, double x)
{
    const double t = std::fmin(std::fmax((x - a) / (b - a), 0.0), 1.0);
    return t * t * (3.0 - 2.0 * t);
}

/// Rolling hills with a mesa (steep cliffs, ~10 m) and a lower terrace, metres.
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
    const std::filesystem::path out = argc > 1 ? argv[1] : "/tmp/strata-render-demo";
    try {
        std::filesystem::create_directories(out);
        const int n = 317; // (n−1)²·2 = 199,712 triangles
        const double size = 64.0;
        std::vector<glm::vec3> positions;
        std::vector<glm::vec3> normals;
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
                const auto b = a + 1;
                const auto c = a + std::uint32_t(n);
                const auto d = c + 1;
                // Counter-clockwise seen from above (+Y).
                indices.insert(indices.end(), {a, c, b, b, c, d});
            }
        }
        MeshView mesh;
        mesh.positions = positions.data();
        mesh.normals = normals.data();
        mesh.vertexCount = positions.size();
        mesh.indices = indices.data();
        mesh.indexCount = indices.size();

        auto t0 = Clock::now();
        auto context = EglContext::create();
        auto t1 = Clock::now();
        std::printf("context: %s (%.0f ms)\n", context->description().c_str(),
                    std::chrono::duration<double, std::milli>(t1 - t0).count());

        t0 = Clock::now();
        SnapshotOptions options;
        const Image rock = makeRockAlbedo(1024, 1);
        const Image grass = makeGrassAlbedo(1024, 1);
        options.material.albedo = makeTexture(rock, MapKind::Albedo);
        options.material.topAlbedo = makeTexture(grass, MapKind::Albedo);
        t1 = Clock::now();
        std::printf("textures: 2 x 1024^2 in %.0f ms\n", std::chrono::duration<double, std::milli>(t1 - t0).count());
        writeImage(rock, out / "rock.png");
        writeImage(grass, out / "grass.png");

        options.camera = orbitCamera(glm::dvec3(-24.0, 0.0, -24.0), glm::dvec3(24.0, 12.0, 24.0), 35.0, 28.0);
        for (int run = 0; run < 3; ++run) {
            t0 = Clock::now();
            const Image image = renderSnapshot(*context, mesh, options);
            t1 = Clock::now();
            std::printf("snapshot %dx%d, %d samples, %zu triangles: %.0f ms\n", image.width, image.height,
                        options.samples, indices.size() / 3,
                        std::chrono::duration<double, std::milli>(t1 - t0).count());
            if (run == 0) {
                writeImage(image, out / "terrain.png");
            }
        }
        // Where the time goes: no MSAA, then also an empty mesh (fixed costs).
        for (int samples : {1, 2, 4, 8}) {
            SnapshotOptions variant = options;
            variant.samples = samples;
            t0 = Clock::now();
            renderSnapshot(*context, MeshView{}, variant);
            t1 = Clock::now();
            renderSnapshot(*context, mesh, variant);
            const auto t2 = Clock::now();
            std::printf("%d sample(s): empty mesh %.0f ms, terrain %.0f ms\n", samples,
                        std::chrono::duration<double, std::milli>(t1 - t0).count(),
                        std::chrono::duration<double, std::milli>(t2 - t1).count());
        }

        // A closer look at a cliff.
        options.camera.position = glm::dvec3(-14.0, 9.0, 14.0);
        options.camera.target = glm::dvec3(2.0, 4.0, -2.0);
        options.camera.nearPlane = 0.5;
        options.camera.farPlane = 300.0;
        writeImage(renderSnapshot(*context, mesh, options), out / "terrain-close.png");
        std::printf("wrote %s\n", out.string().c_str());
    } catch (const strata::Error& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
