// `strata render`: one image (or a turntable) of a scene's terrain, or of a
// mesh file, with the scene's material, camera and lighting, through OpenGL
// (auto, gl) or the CPU reference renderer (cpu; auto without EGL).

#include "Commands.h"
#include "Generate.h"
#include "Quality.h"
#include "CaveView.h"
#include "Scene.h"
#include "SceneOffset.h"
#include "SnapshotFlags.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/PlyIO.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>

#include <tbb/global_control.h>

#include <glm/geometric.hpp>

#include <cctype>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>
#include <sstream>
#include <vector>

namespace strata::app {

namespace {

struct RenderArguments
{
    std::string scenePath;
    std::string meshPath;
    std::string output;
    SnapshotFlags snapshot;
    std::string offset; ///< --offset X,Y,Z
    std::string size;
    std::optional<std::uint64_t> seed;
    int threads = 0;
    bool quiet = false;
};

/// Area-weighted vertex normals, for mesh files without normals.
void computeVertexNormals(meshing::TriangleMesh& mesh)
{
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if (a >= mesh.positions.size() || b >= mesh.positions.size() || c >= mesh.positions.size()) continue;
        const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        mesh.normals[a] += n;
        mesh.normals[b] += n;
        mesh.normals[c] += n;
    }
    for (glm::vec3& n : mesh.normals) {
        const float len = glm::length(n);
        n = len > 0.0f ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
}

/// The scene's terrain mesh, through the generate pipeline (no snapshot)
/// into a scratch folder beside the output, read back and removed.
meshing::TriangleMesh terrainMesh(const Scene& scene, std::optional<std::uint64_t> seed,
                                  const std::filesystem::path& output, std::optional<render::Camera>* cave)
{
    const std::filesystem::path scratch =
        std::filesystem::absolute(output).parent_path() / (".strata-render-" + output.filename().string());
    GenerateOptions options;
    options.outputDir = scratch;
    options.seed = seed;
    options.snapshot = false;
    options.quiet = true;
    std::ostringstream log;
    struct Cleanup
    {
        std::filesystem::path dir;
        ~Cleanup()
        {
            std::error_code ec;
            std::filesystem::remove_all(dir, ec);
        }
    } cleanup{scratch};
    generate(scene, options, log);
    if (cave) {
        const openvdb::FloatGrid::Ptr grid = meshing::readLevelSet(scratch / "terrain.vdb");
        *cave = findCaveView(*grid, scene.region.min, scene.region.max).camera;
    }
    return meshing::readGltf(scratch / "terrain.glb");
}

meshing::TriangleMesh readMesh(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    meshing::TriangleMesh mesh =
        (ext == ".glb" || ext == ".gltf") ? meshing::readGltf(path) : meshing::readMeshFile(path);
    if (mesh.triangleCount() == 0) throw Error("mesh file '" + path.string() + "' has no triangles");
    if (mesh.normals.size() != mesh.positions.size()) computeVertexNormals(mesh);
    return mesh;
}

} // namespace

Command registerRenderCommand(CLI::App& app)
{
    auto args = std::make_shared<RenderArguments>();
    CLI::App* render = app.add_subcommand(
        "render",
        "Render one image (or --turntable N frames) of a scene's terrain (or of --mesh FILE) with the scene's "
        "material, camera and light");
    render->add_option("scene", args->scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    render
        ->add_option("--mesh", args->meshPath,
                     "Render this mesh (.glb, .gltf, .ply, .obj, .stl) instead of the scene's terrain")
        ->check(CLI::ExistingFile);
    render->add_option("-o,--output", args->output, "Output image (.png, .exr, .tif, .jpg, by extension)")->required();
    render->add_option("--offset", args->offset,
                       "Move the whole scene (terrain or --mesh, region, camera; camera flags included) by X,Y,Z "
                       "world metres, |value| <= 1e9");
    args->snapshot.add(render);
    render->add_option("--size", args->size, "Image size WIDTHxHEIGHT (default from the scene, 1280x720)");
    render->add_option("--seed", args->seed, "Override the scene's seed")
        ->check(CLI::NonNegativeNumber); // CLI11 would wrap -1 to 2^64 - 1
    render
        ->add_option("--threads", args->threads, "Worker threads (0 = all cores); the image is identical for any count")
        ->check(CLI::Range(0, 1024));
    render->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");

    return {render, [args]() {
                using Clock = std::chrono::steady_clock;
                // Every flag checked before any work: bad values exit 2 with nothing written.
                SnapshotRequest request = args->snapshot.request();
                const glm::dvec3 offset =
                    args->offset.empty() ? glm::dvec3(0.0) : parseVec3Flag("--offset", args->offset);
                offsetRequest(request, offset);
                std::filesystem::path output = args->output;
                std::string ext = output.extension().string();
                for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
                if (!request.format.empty() && ext != "." + request.format) {
                    throw Error("--snapshot-format '" + request.format + "' does not match the output name '" +
                                args->output + "' (use a ." + request.format + " name)");
                }
                if (request.view == "cave" && !args->meshPath.empty()) {
                    throw Error("--view cave needs the scene's terrain grid: it cannot be used with --mesh '" +
                                args->meshPath + "'");
                }
                const Scene scene = offsetScene(args->scenePath.empty()
                                                    ? parseScene(defaultSceneText(), "<default scene>")
                                                    : loadScene(args->scenePath),
                                                offset);
                // The scene's [quality] render knobs (filtering, normal blend,
                // shadow resolution, backend) apply here too; the geometry
                // knobs apply inside generate(), which gets the scene as written.
                const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
                const Scene shading = applyQuality(scene, quality);
                if (request.backend == "auto") request.backend = quality.backend;
                std::optional<int> width, height;
                if (!args->size.empty()) {
                    static const std::regex pattern(R"((\d{1,5})[xX](\d{1,5}))");
                    std::smatch match;
                    if (!std::regex_match(args->size, match, pattern)) {
                        throw Error("--size '" + args->size + "' must look like WIDTHxHEIGHT, e.g. 1280x720");
                    }
                    width = std::stoi(match[1]);
                    height = std::stoi(match[2]);
                    if (*width < 1 || *height < 1 || *width > 16384 || *height > 16384) {
                        throw Error("--size '" + args->size + "': width and height must be in [1, 16384]");
                    }
                }
                std::unique_ptr<tbb::global_control> threadLimit;
                if (args->threads > 0) {
                    threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                        std::size_t(args->threads));
                }
                // GL first: without a context, fail (gl) or fall back (auto) before the long stages.
                std::string renderer;
                std::unique_ptr<render::EglContext> context = openBackend(request, std::cerr, renderer);

                auto t0 = Clock::now();
                std::optional<render::Camera> cave;
                meshing::TriangleMesh mesh =
                    args->meshPath.empty()
                        ? terrainMesh(scene, args->seed, args->output, request.view == "cave" ? &cave : nullptr)
                        : readMesh(args->meshPath);
                if (!args->meshPath.empty()) mesh.origin += offset; // the mesh file moves with the scene
                auto t1 = Clock::now();
                const render::SnapshotOptions snapshot = makeSnapshotOptions(shading, mesh, width, height, request, cave);
                auto t2 = Clock::now();
                const render::MeshView view = meshView(mesh);
                const std::vector<std::filesystem::path> paths = snapshotPaths(output, request.turntable);
                std::unique_ptr<render::GlRenderer> glRenderer;
                if (context) {
                    glRenderer = std::make_unique<render::GlRenderer>(*context);
                    glRenderer->setMesh(view);
                }
                std::vector<render::Image> images;
                for (std::size_t frame = 0; frame < paths.size(); ++frame) {
                    render::SnapshotOptions frameOptions = snapshot;
                    frameOptions.camera = turntableFrame(snapshot.camera, int(frame), int(paths.size()));
                    images.push_back(glRenderer ? glRenderer->renderImage(frameOptions)
                                                : render::renderSnapshotCpu(view, frameOptions));
                }
                const render::Image& image = images.back();
                auto t3 = Clock::now();
                for (std::size_t frame = 0; frame < paths.size(); ++frame) render::writeImage(images[frame], paths[frame]);
                if (!args->quiet) {
                    auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
                    std::cout << std::fixed << std::setprecision(3)
                              << "strata render: " << (args->meshPath.empty() ? scene.source : args->meshPath) << " → "
                              << args->output << "\n  mesh      " << std::setw(8) << seconds(t0, t1) << " s   "
                              << mesh.triangleCount() << " triangles\n  material  " << std::setw(8) << seconds(t1, t2)
                              << " s   " << render::featureNames(render::materialFeatures(snapshot.material))
                              << "\n  render    " << std::setw(8) << seconds(t2, t3) << " s   " << image.width << "x"
                              << image.height << ", " << (context ? "gl" : "cpu")
                              << (paths.size() > 1 ? ", " + std::to_string(paths.size()) + " frames" : std::string())
                              << std::endl;
                }
                return 0;
            }};
}

} // namespace strata::app
