#include "Generate.h"

#include "CaveView.h"
#include "Progress.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/Simplify.h>
#include <strata/meshing/SurfaceNets.h>
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
    const QualitySettings& q = result.quality;
    report["quality"] = {{"preset", q.preset},
                         {"voxel_size", q.voxelSize},
                         {"half_width", q.halfWidth},
                         {"mesher", q.mesher},
                         {"adaptivity", q.adaptivity},
                         {"normals", q.normals},
                         {"projection", q.projectionSteps},
                         {"simplify", q.simplifyRatio},
                         {"filtering", filteringName(q.filtering)},
                         {"normal_blend", normalBlendName(q.normalBlend)},
                         {"shadow_resolution", q.shadowResolution},
                         {"backend", q.backend}};
    // Model only what the scene requires: work done against work possible.
    nlohmann::ordered_json model;
    model["evaluated_points"] = result.evaluatedPoints;
    model["active_voxels"] = result.activeVoxels;
    model["evaluated_per_active_voxel"] =
        result.activeVoxels ? double(result.evaluatedPoints) / double(result.activeVoxels) : 0.0;
    if (result.programsPossible > 0) {
        model["shader_variants_compiled"] = result.programsCompiled;
        model["shader_variants_possible"] = result.programsPossible;
    }
    if (result.shadedPixels > 0) {
        model["shaded_pixels"] = result.shadedPixels;
        model["texture_fetches"] = result.textureFetches;
        model["texture_fetches_naive"] = result.naiveFetches;
        model["texture_fetches_skipped"] = result.naiveFetches - result.textureFetches;
    }
    report["model"] = model;
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
    snapshot.filtering = scene.snapshot.filtering;
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

meshing::TriangleMesh meshWithQuality(const openvdb::FloatGrid& grid, const QualitySettings& quality,
                                      const meshing::GradientFunction& gradient, const glm::dvec3& origin,
                                      std::string* what)
{
    const meshing::NormalMethod normals = quality.normals == "face"    ? meshing::NormalMethod::Face
                                          : quality.normals == "field" ? meshing::NormalMethod::Gradient
                                                                       : meshing::NormalMethod::Grid;
    if (normals == meshing::NormalMethod::Gradient && !gradient) {
        throw Error("quality normals = 'field' needs a density field gradient");
    }
    meshing::TriangleMesh mesh;
    std::ostringstream description;
    if (quality.mesher == "volume") {
        meshing::GridToMeshOptions options;
        options.adaptivity = quality.adaptivity;
        options.normals = normals;
        options.gradient = gradient;
        options.projectionSteps = quality.projectionSteps;
        options.origin = origin;
        mesh = meshing::gridToMesh(grid, options);
        description << "volume (adaptivity " << quality.adaptivity << ")";
    } else {
        meshing::DualContouringOptions options;
        options.chunkSize = 32;
        options.normals = normals;
        options.gradient = gradient;
        options.projectionSteps = quality.projectionSteps;
        options.origin = origin;
        mesh = quality.mesher == "surface-nets" ? meshing::surfaceNets(grid, options)
                                                : meshing::dualContouring(grid, options);
        description << quality.mesher;
    }
    description << ", " << quality.normals << " normals";
    if (quality.projectionSteps > 0) description << ", " << quality.projectionSteps << " projection steps";
    if (quality.simplifyRatio < 1.0 && mesh.triangleCount() > 0) {
        meshing::SimplifyOptions simplifyOptions;
        simplifyOptions.ratio = quality.simplifyRatio;
        simplifyOptions.maxError = 0.5 * grid.voxelSize()[0];
        simplifyOptions.lockBorder = true;
        const std::size_t before = mesh.triangleCount();
        mesh = meshing::simplify(mesh, simplifyOptions);
        if (normals == meshing::NormalMethod::Face) meshing::computeFaceNormals(mesh);
        description << ", simplified " << before << " -> " << mesh.triangleCount();
    }
    if (what) *what = description.str();
    return mesh;
}

GenerateResult generate(const Scene& input, const GenerateOptions& options, std::ostream& out)
{
    StageLog log(out, stdoutIsTerminal(), options.quiet);
    GenerateResult result;
    // Quality first: a bad preset writes nothing. An explicit backend in the
    // request counts as a flag.
    QualityOverrides flags = options.quality;
    if (options.request.backend != "auto" && !flags.count("backend")) {
        flags["backend"] = checkKnob("backend", options.request.backend);
    }
    result.quality = resolveQuality(input, options.preset, flags);
    const Scene scene = applyQuality(input, result.quality);
    SnapshotRequest request = options.request;
    request.backend = result.quality.backend;
    if (options.snapshot) {
        checkSnapshotRequest(request); // bad flags: nothing written
    }

    std::error_code ec;
    std::filesystem::create_directories(options.outputDir, ec);
    if (ec || !std::filesystem::is_directory(options.outputDir)) {
        throw Error("cannot create output directory '" + options.outputDir.string() + "': " + ec.message());
    }

    // The GL context first: on a machine without one, fail before the long stages.
    std::unique_ptr<render::EglContext> context;
    double contextSeconds = 0.0;
    if (options.snapshot && request.backend != "cpu") {
        log.begin("context");
        context = openBackend(request, std::cerr, result.renderer);
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
    if (options.snapshot && request.view == "cave") {
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
    // Positions relative to the region's centre (the .glb node translation),
    // so float precision holds for regions far from the world origin.
    const glm::dvec3 meshOrigin = 0.5 * (scene.region.min + scene.region.max);
    // "field" normals: the density field's own gradient (central differences
    // a quarter voxel apart), not the grid's.
    const double step = 0.25 * scene.voxelSize;
    const meshing::GradientFunction fieldGradient = [&field, step](const glm::dvec3& p) {
        glm::dvec3 g;
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 d(0.0);
            d[axis] = step;
            g[axis] = (field->density(p + d) - field->density(p - d)) / (2.0 * step);
        }
        return g;
    };
    std::string mesherDescription;
    const meshing::TriangleMesh mesh =
        meshWithQuality(*grid, result.quality, fieldGradient, meshOrigin, &mesherDescription);
    result.mesher = mesherDescription;
    result.vertices = mesh.vertexCount();
    result.triangles = mesh.triangleCount();
    log.end(withThousands(result.vertices) + " vertices, " + withThousands(result.triangles) + " triangles, " +
            mesherDescription);
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
            makeSnapshotOptions(scene, mesh, options.width, options.height, request, caveCamera);
        const std::string format = request.format.empty() ? "png" : request.format;
        const std::vector<std::filesystem::path> paths =
            snapshotPaths(options.outputDir / ("snapshot." + format), request.turntable);
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
            render::CpuRenderStats cpuStats;
            image = renderer ? renderer->renderImage(frameOptions) : render::renderSnapshotCpu(view, frameOptions, &cpuStats);
            result.shadedPixels += cpuStats.shadedPixels;
            result.textureFetches += cpuStats.textureFetches;
            result.naiveFetches += cpuStats.naiveFetches;
            render::writeImage(image, paths[frame]);
        }
        if (renderer) {
            const render::ProgramStats programs = renderer->stats();
            result.programsCompiled = programs.compiled;
            result.programsPossible = programs.possible;
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
        // Model only what the scene requires: work done against work possible.
        std::ostringstream model;
        model << std::fixed << std::setprecision(2) << "  model     " << withThousands(result.evaluatedPoints)
              << " points evaluated for " << withThousands(result.activeVoxels) << " active voxels ("
              << (result.activeVoxels ? double(result.evaluatedPoints) / double(result.activeVoxels) : 0.0)
              << " per voxel)";
        if (result.programsPossible > 0) {
            model << "; " << result.programsCompiled << " of " << result.programsPossible
                  << " shader variants compiled";
        }
        if (result.naiveFetches > 0) {
            model << "; " << withThousands(result.textureFetches) << " texture fetches of "
                  << withThousands(result.naiveFetches) << " naive ("
                  << 100.0 * double(result.naiveFetches - result.textureFetches) / double(result.naiveFetches)
                  << "% skipped)";
        }
        out << model.str() << "\n  quality   " << describeQuality(result.quality) << '\n';
        out << "  total     " << std::fixed << std::setprecision(3) << std::setw(8) << result.timings["total"]
            << " s   wrote " << options.outputDir.string() << "/" << std::defaultfloat << std::endl;
    }
    return result;
}

} // namespace strata::app
