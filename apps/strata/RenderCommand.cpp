// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata render`: one image (or a turntable) of a scene's terrain, or of a
// mesh file, with the scene's material, camera and lighting, through OpenGL
// (auto, gl) or the CPU reference renderer (cpu; auto without EGL).

#include "Commands.h"
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Bake.h>
#include <strata/scene/CaveView.h>
#include <strata/scene/Scene.h>
#include <strata/scene/SceneOffset.h>
#include "SnapshotFlags.h"

#include <strata/Error.h>
#include <strata/Stopwatch.h>
#include <strata/meshing/GridNormals.h>
#include <strata/meshing/MeshFile.h>
#include <strata/render/EglContext.h>

#include <tbb/global_control.h>

#include <cctype>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <tuple>
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
    double maxScreenError = 2.0;
};

/// `strata render DIR`: the baked world from its tiles.
int renderWorld(const RenderArguments& args, SnapshotRequest request, const std::filesystem::path& output)
{
    for (const auto& [given, flag] : {std::pair{!args.meshPath.empty(), "--mesh"}, std::pair{!args.offset.empty(), "--offset"},
                                      std::pair{args.seed.has_value(), "--seed"}, std::pair{request.turntable > 0, "--turntable"},
                                      std::pair{request.view == "cave", "--view cave"},
                                      std::pair{!request.debugView.empty(), "--debug-view"}})
        if (given) throw Error(ErrorKind::BadInput, std::string(flag) + " cannot be used when rendering a bake folder ('" + args.scenePath + "')");
    const Scene scene = loadBakedScene(args.scenePath);
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const Scene shading = applyQuality(scene, quality);
    if (request.backend == "auto") request.backend = quality.backend;
    WorldSnapshotOptions options;
    options.request = request;
    options.maxScreenError = args.maxScreenError;
    if (!args.size.empty()) std::tie(options.width, options.height) = parseSizeFlag(args.size);
    std::unique_ptr<tbb::global_control> threadLimit;
    if (args.threads > 0)
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            std::size_t(args.threads));
    std::string renderer;
    std::unique_ptr<render::EglContext> context = openBackend(request, std::cerr, renderer);
    Stopwatch clock;
    render::Image image;
    const WorldSnapshotStats stats = renderBakedWorld(shading, args.scenePath, options, context.get(),
                                                      [&](const render::Image& frame) { image = frame; });
    render::writeImage(image, output);
    if (!args.quiet) {
        std::cout << "strata render: " << args.scenePath << " (baked world) → " << output.string() << "\n  tiles    ";
        for (std::size_t l = 0; l < stats.tilesPerLevel.size(); ++l)
            std::cout << " L" << l << ": " << stats.tilesPerLevel[l];
        std::cout << std::fixed << std::setprecision(3) << "\n  render    " << std::setw(8) << clock.seconds() << " s   "
                  << stats.triangles << " triangles, " << image.width << "x" << image.height << ", "
                  << (context ? "gl" : "cpu") << std::defaultfloat << std::endl;
    }
    return 0;
}

/// A mesh file to render: any format meshing reads, with face-averaged
/// normals where the file has none.
meshing::TriangleMesh readRenderMesh(const std::filesystem::path& path)
{
    meshing::TriangleMesh mesh = meshing::readMesh(path);
    if (mesh.triangleCount() == 0) {
        throw Error(ErrorKind::BadInput, "mesh file '" + path.string() + "' has no triangles", {path.string()});
    }
    if (mesh.normals.size() != mesh.positions.size()) meshing::computeFaceNormals(mesh);
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
    render
        ->add_option("scene", args->scenePath,
                     "Scene file (TOML), or a `strata bake` folder (the whole world from its tiles); without one, "
                     "the embedded default scene")
        ->check(CLI::ExistingPath);
    render->add_option("--max-screen-error", args->maxScreenError,
                       "Bake folders: per tile, the coarsest level whose geometric error stays within this many "
                       "pixels (the 3D Tiles rule)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
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
        ->check(seedValidator());
    render
        ->add_option("--threads", args->threads, "Worker threads (0 = all cores); the image is identical for any count")
        ->check(CLI::Range(0, 1024));
    render->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");

    return {render, [args]() {
                // Every flag checked before any work: bad values exit 2 with nothing written.
                SnapshotRequest request = args->snapshot.request();
                const glm::dvec3 offset =
                    args->offset.empty() ? glm::dvec3(0.0) : parseVec3Flag("--offset", args->offset);
                offsetRequest(request, offset);
                std::filesystem::path output = args->output;
                std::string ext = output.extension().string();
                for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
                if (!request.format.empty() && ext != "." + request.format) {
                    throw Error(ErrorKind::BadInput, "--snapshot-format '" + request.format + "' does not match the output name '" +
                                args->output + "' (use a ." + request.format + " name)");
                }
                if (std::filesystem::is_directory(args->scenePath)) return renderWorld(*args, request, output);
                if (request.view == "cave" && !args->meshPath.empty()) {
                    throw Error(ErrorKind::BadInput, "--view cave needs the scene's terrain grid: it cannot be used with --mesh '" +
                                args->meshPath + "'");
                }
                const Scene scene = offsetScene(args->scenePath.empty()
                                                    ? defaultScene()
                                                    : loadScene(args->scenePath),
                                                offset);
                // The scene's [quality] table applies as in `strata generate`:
                // geometry knobs to the terrain, render knobs to the image.
                const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
                const Scene shading = applyQuality(scene, quality);
                if (request.backend == "auto") request.backend = quality.backend;
                std::optional<int> width, height;
                if (!args->size.empty()) std::tie(width, height) = parseSizeFlag(args->size);
                std::unique_ptr<tbb::global_control> threadLimit;
                if (args->threads > 0) {
                    threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                        std::size_t(args->threads));
                }
                // GL first: without a context, fail (gl) or fall back (auto) before the long stages.
                std::string renderer;
                std::unique_ptr<render::EglContext> context = openBackend(request, std::cerr, renderer);

                Stopwatch clock;
                std::optional<render::Camera> cave;
                meshing::TriangleMesh mesh;
                if (args->meshPath.empty()) {
                    // The terrain in memory, through the same stages as `strata generate`.
                    const MeshMasks masks = neededMasks(shading, request.debugView); // before the long stages
                    const SampledTerrain terrain = sampleTerrain(shading, args->seed);
                    if (request.view == "cave") {
                        cave = findCaveView(*terrain.grid, shading.region.min, shading.region.max).camera;
                    }
                    mesh = meshTerrain(shading, quality, terrain, nullptr, masks);
                } else {
                    mesh = readRenderMesh(args->meshPath);
                    mesh.origin += offset; // the mesh file moves with the scene
                }
                const double meshSeconds = clock.seconds();
                clock.restart();
                const std::vector<std::filesystem::path> paths = snapshotPaths(output, request.turntable);
                std::vector<render::Image> images(paths.size());
                const RenderStats stats =
                    renderSnapshots(shading, mesh, request, context.get(), int(paths.size()), width, height, cave,
                                    [&](int frame, const render::Image& image) { images[std::size_t(frame)] = image; });
                const render::Image& image = images.back();
                const double renderSeconds = clock.seconds();
                // Written only when every frame rendered: a failure leaves no partial turntable.
                for (std::size_t frame = 0; frame < paths.size(); ++frame) render::writeImage(images[frame], paths[frame]);
                if (!args->quiet) {
                    std::cout << std::fixed << std::setprecision(3)
                              << "strata render: " << (args->meshPath.empty() ? scene.source : args->meshPath) << " → "
                              << args->output << "\n  mesh      " << std::setw(8) << meshSeconds << " s   "
                              << mesh.triangleCount() << " triangles\n  render    " << std::setw(8) << renderSeconds
                              << " s   " << stats.features << ", " << image.width << "x"
                              << image.height << ", " << (context ? "gl" : "cpu")
                              << (paths.size() > 1 ? ", " + std::to_string(paths.size()) + " frames" : std::string())
                              << std::endl;
                }
                return 0;
            }};
}

} // namespace strata::app
