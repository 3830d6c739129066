#include "Generate.h"

#include "CaveView.h"
#include "Progress.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/PlyIO.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include <nlohmann/json.hpp>

#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace strata::app {

namespace {

std::string withThousands(std::uint64_t n)
{
    std::string digits = std::to_string(n), out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

void writeReport(const GenerateResult& result, const Scene& scene, const GenerateOptions& options,
                 const std::filesystem::path& path)
{
    nlohmann::ordered_json report;
    report["scene"] = scene.source;
    report["seed"] = result.seed;
    report["voxel_size"] = result.voxelSize;
    report["region"] = {{"min", {scene.region.min.x, scene.region.min.y, scene.region.min.z}},
                        {"max", {scene.region.max.x, scene.region.max.y, scene.region.max.z}}};
    report["active_voxels"] = result.activeVoxels;
    report["evaluated_points"] = result.evaluatedPoints;
    report["bound_evaluations"] = result.boundEvaluations;
    report["grid_memory_bytes"] = result.gridMemoryBytes;
    report["vertices"] = result.vertices;
    report["triangles"] = result.triangles;
    report["threads"] = options.threads;
    report["renderer"] = result.renderer;
    report["timings"] = result.timings;
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary);
        out << report.dump(2) << '\n';
        if (!out.flush()) throw Error("cannot write '" + path.string() + "'");
    });
}

} // namespace

render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height)
{
    return makeSnapshotOptions(scene, mesh, width, height, SnapshotRequest{});
}

render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height,
                                            const SnapshotRequest& request, const std::optional<render::Camera>& cave)
{
    render::SnapshotOptions snapshot;
    snapshot.width = width.value_or(scene.snapshot.width);
    snapshot.height = height.value_or(scene.snapshot.height);
    snapshot.samples = scene.snapshot.samples;
    snapshot.anisotropy = scene.snapshot.anisotropy;
    snapshot.shadows = scene.snapshot.shadows;
    snapshot.camera = snapshotCamera(scene, request, meshing::worldBounds(mesh),
                                     double(snapshot.width) / snapshot.height, cave);
    snapshot.lighting = scene.lighting;
    snapshot.material = buildMaterial(scene.material);
    return snapshot;
}

render::MeshView meshView(const meshing::TriangleMesh& mesh)
{
    render::MeshView view;
    view.positions = mesh.positions.data();
    view.normals = mesh.normals.data();
    view.vertexCount = mesh.positions.size();
    view.indices = mesh.indices.data();
    view.indexCount = mesh.indices.size();
    view.origin = mesh.origin;
    return view;
}

GenerateResult generate(const Scene& scene, const GenerateOptions& options, std::ostream& out)
{
    StageLog log(out, stdoutIsTerminal(), options.quiet);
    GenerateResult result;
    if (options.snapshot) {
        checkSnapshotRequest(options.request); // bad flags: nothing written
    }

    std::error_code ec;
    std::filesystem::create_directories(options.outputDir, ec);
    if (ec || !std::filesystem::is_directory(options.outputDir)) {
        throw Error("cannot create output directory '" + options.outputDir.string() + "': " + ec.message());
    }

    // The GL context first: on a machine without one, fail before the long stages.
    std::unique_ptr<render::EglContext> context;
    double contextSeconds = 0.0;
    if (options.snapshot && options.request.backend != "cpu") {
        log.begin("context");
        context = openBackend(options.request, std::cerr, result.renderer);
        log.end(result.renderer);
        contextSeconds = log.seconds().at("context");
    } else if (options.snapshot) {
        result.renderer = "strata CPU reference renderer";
    }

    result.seed = options.seed.value_or(scene.terrain.seed);
    result.voxelSize = scene.voxelSize;

    log.begin("generate");
    // The scene's root density field; another seed rebuilds the tree.
    const std::shared_ptr<const terrain::DensityField> field =
        options.seed && *options.seed != scene.terrain.seed && scene.buildField ? scene.buildField(*options.seed)
                                                                                : scene.field;
    if (!field) throw Error(scene.source + ": the scene has no terrain");
    terrain::SampleOptions sampling;
    sampling.voxelSize = scene.voxelSize;
    sampling.halfWidth = scene.halfWidth;
    sampling.region = scene.region;
    sampling.maxMemoryBytes = options.maxMemoryBytes;
    sampling.renormalize = scene.renormalize;
    sampling.progress = [&log](double fraction) {
        log.progress(fraction);
        return true;
    };
    terrain::SampleStats stats;
    openvdb::FloatGrid::Ptr grid = terrain::sampleLevelSet(*field, sampling, &stats);
    grid->setName("terrain");
    result.activeVoxels = grid->activeVoxelCount();
    result.evaluatedPoints = stats.evaluatedPoints;
    result.boundEvaluations = stats.boundEvaluations;
    result.gridMemoryBytes = grid->memUsage();
    log.end(withThousands(result.activeVoxels) + " active voxels, " +
            withThousands(result.gridMemoryBytes / 1024) + " KiB");

    // The cave view needs the grid; found before any file is written.
    std::optional<render::Camera> caveCamera;
    if (options.snapshot && options.request.view == "cave") {
        log.begin("cave");
        const CaveView cave = findCaveView(*grid, scene.region.min, scene.region.max);
        caveCamera = cave.camera;
        std::ostringstream info;
        info << std::fixed << std::setprecision(1) << "camera at (" << cave.camera.position.x << ", "
             << cave.camera.position.y << ", " << cave.camera.position.z << "), " << withThousands(cave.caveCells)
             << " cells of " << cave.cellSize << " m, " << (cave.looksOut ? "looking out" : "looking along the cave");
        log.end(info.str());
    }

    log.begin("mesh");
    meshing::GridToMeshOptions meshOptions;
    meshOptions.adaptivity = scene.adaptivity;
    const meshing::TriangleMesh mesh = meshing::gridToMesh(*grid, meshOptions);
    result.vertices = mesh.vertexCount();
    result.triangles = mesh.triangleCount();
    log.end(withThousands(result.vertices) + " vertices, " + withThousands(result.triangles) + " triangles");
    if (mesh.triangleCount() == 0) {
        throw Error(scene.source + ": the terrain has no surface inside the region (check region and terrain.height)");
    }

    log.begin("write");
    meshing::writeGrid(*grid, options.outputDir / "terrain.vdb");
    meshing::writeGlb(mesh, options.outputDir / "terrain.glb");
    if (options.writePly) meshing::writePly(mesh, options.outputDir / "terrain.ply");
    log.end();

    if (options.snapshot) {
        log.begin("render");
        const render::SnapshotOptions snapshot =
            makeSnapshotOptions(scene, mesh, options.width, options.height, options.request, caveCamera);
        const std::string format = options.request.format.empty() ? "png" : options.request.format;
        const std::vector<std::filesystem::path> paths =
            snapshotPaths(options.outputDir / ("snapshot." + format), options.request.turntable);
        const render::MeshView view = meshView(mesh);
        std::unique_ptr<render::GlRenderer> renderer;
        if (context) {
            renderer = std::make_unique<render::GlRenderer>(*context);
            renderer->setMesh(view);
        }
        render::Image image;
        for (std::size_t frame = 0; frame < paths.size(); ++frame) {
            render::SnapshotOptions frameOptions = snapshot;
            frameOptions.camera = turntableFrame(snapshot.camera, int(frame), int(paths.size()));
            image = renderer ? renderer->renderImage(frameOptions) : render::renderSnapshotCpu(view, frameOptions);
            render::writeImage(image, paths[frame]);
        }
        log.end(std::to_string(image.width) + "x" + std::to_string(image.height) + ", " + (context ? "gl" : "cpu") +
                ", " + render::featureNames(render::materialFeatures(snapshot.material)) +
                (paths.size() > 1 ? ", " + std::to_string(paths.size()) + " frames" : std::string()));
    }

    result.timings = log.seconds();
    if (options.snapshot && context) {
        // Context creation is part of the render stage's cost.
        result.timings["render"] += contextSeconds;
        result.timings.erase("context");
    }
    result.timings["total"] = log.elapsed();
    writeReport(result, scene, options, options.outputDir / "report.json");
    if (!options.quiet) {
        out << "  total     " << std::fixed << std::setprecision(3) << std::setw(8) << result.timings["total"]
            << " s   wrote " << options.outputDir.string() << "/" << std::defaultfloat << std::endl;
    }
    return result;
}

} // namespace strata::app
