#include "Generate.h"

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

render::Camera makeCamera(const Scene& scene, const meshing::Bounds& bounds, double aspect)
{
    const CameraSettings& settings = scene.camera;
    if (settings.position) {
        render::Camera camera;
        camera.position = *settings.position;
        camera.target = *settings.target;
        camera.fovYDegrees = settings.fov;
        const double extent = glm::length(bounds.max - bounds.min);
        camera.nearPlane = std::max(1e-3, extent * 1e-4);
        camera.farPlane = glm::length(camera.position - camera.target) + 2.0 * extent + 1.0;
        return camera;
    }
    render::Camera camera = render::orbitCamera(bounds.min, bounds.max, settings.azimuth, settings.elevation,
                                                settings.fov, aspect);
    if (settings.zoom != 1.0) {
        const double distance = glm::length(camera.position - camera.target) / settings.zoom;
        const double radius = 0.5 * glm::length(bounds.max - bounds.min);
        camera.position = camera.target + (camera.position - camera.target) / settings.zoom;
        camera.nearPlane = std::max(distance - radius, distance * 1e-3);
        camera.farPlane = distance + radius;
    }
    return camera;
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
    render::SnapshotOptions snapshot;
    snapshot.width = width.value_or(scene.snapshot.width);
    snapshot.height = height.value_or(scene.snapshot.height);
    snapshot.samples = scene.snapshot.samples;
    snapshot.anisotropy = scene.snapshot.anisotropy;
    snapshot.camera = makeCamera(scene, meshing::worldBounds(mesh), double(snapshot.width) / snapshot.height);
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

    std::error_code ec;
    std::filesystem::create_directories(options.outputDir, ec);
    if (ec || !std::filesystem::is_directory(options.outputDir)) {
        throw Error("cannot create output directory '" + options.outputDir.string() + "': " + ec.message());
    }

    // The GL context first: on a machine without one, fail before the long stages.
    std::unique_ptr<render::EglContext> context;
    double contextSeconds = 0.0;
    if (options.backend != "gl" && options.backend != "cpu") {
        throw Error("unknown render backend '" + options.backend + "' (use gl or cpu)");
    }
    if (options.snapshot && options.backend == "gl") {
        log.begin("context");
        context = render::EglContext::create();
        result.renderer = context->description();
        log.end(result.renderer);
        contextSeconds = log.seconds().at("context");
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
    result.gridMemoryBytes = grid->memUsage();
    log.end(withThousands(result.activeVoxels) + " active voxels, " +
            withThousands(result.gridMemoryBytes / 1024) + " KiB");

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
        const render::SnapshotOptions snapshot = makeSnapshotOptions(scene, mesh, options.width, options.height);

        const render::MeshView view = meshView(mesh);
        if (options.backend == "cpu") result.renderer = "strata CPU reference renderer";
        const render::Image image = options.backend == "cpu" ? render::renderSnapshotCpu(view, snapshot)
                                                             : render::renderSnapshot(*context, view, snapshot);
        render::writeImage(image, options.outputDir / "snapshot.png");
        log.end(std::to_string(image.width) + "x" + std::to_string(image.height) + ", " + options.backend + ", " +
                render::featureNames(render::materialFeatures(snapshot.material)));
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
