// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Pipeline.h>

#include <strata/scene/CaveView.h>
#include <strata/world/LandformAttributes.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/OutputLock.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/Simplify.h>
#include <strata/meshing/SurfaceAttributes.h>
#include <strata/meshing/SurfaceNets.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/PlyIO.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/ProceduralTextures.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <memory>
#include <sstream>

namespace strata::scene {

void writeReport(const GenerateResult& result, const Scene& scene, int threads, const std::filesystem::path& path)
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
    report["threads"] = threads;
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
                         {"projections", q.projections},
                         {"anti_tiling", q.antiTiling ? "on" : "off"},
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
        if (!out.flush()) throw Error(ErrorKind::Io, "cannot write '" + path.string() + "'", {path.string()});
    });
}

render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height)
{
    return makeSnapshotOptions(scene, mesh, width, height, SnapshotRequest{});
}

render::SnapshotOptions makeSnapshotOptions(const Scene& scene, const meshing::TriangleMesh& mesh,
                                            std::optional<int> width, std::optional<int> height,
                                            const SnapshotRequest& request, const std::optional<render::Camera>& cave,
                                            const render::Material* material)
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
    snapshot.material = material ? *material : buildMaterial(scene.material);
    if (!request.debugView.empty()) snapshot.debugView = debugViewFromName(request.debugView).value_or(render::DebugView::Shaded);
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
    if (!mesh.surface.empty() && mesh.surface.size() == mesh.positions.size()) view.surface = mesh.surface.data();
    if (!mesh.landform.empty() && mesh.landform.size() == mesh.positions.size()) view.landform = mesh.landform.data();
    if (!mesh.rock.empty() && mesh.rock.size() == mesh.positions.size()) view.rock = mesh.rock.data();
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
        throw Error(ErrorKind::BadInput, "quality normals = 'field' needs a density field gradient");
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

SampledTerrain sampleTerrain(const Scene& scene, std::optional<std::uint64_t> seed, std::uint64_t maxMemoryBytes,
                             const std::function<bool(double)>& progress)
{
    SampledTerrain out;
    out.seed = seed.value_or(scene.terrain.seed);
    out.field = fieldForSeed(scene, seed);
    out.landformMasks = landformMasksForSeed(scene, seed);
    out.rockMasks = rockMasksForSeed(scene, seed);
    terrain::SampleOptions sampling;
    sampling.voxelSize = scene.voxelSize;
    sampling.halfWidth = scene.halfWidth;
    sampling.region = scene.region;
    sampling.maxMemoryBytes = maxMemoryBytes;
    sampling.renormalize = scene.renormalize;
    sampling.progress = progress;
    out.grid = terrain::sampleLevelSet(*out.field, sampling, &out.stats);
    out.grid->setName("terrain");
    return out;
}

meshing::GradientFunction fieldGradient(std::shared_ptr<const terrain::DensityField> field, double step)
{
    return [field = std::move(field), step](const glm::dvec3& p) {
        glm::dvec3 g;
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 d(0.0);
            d[axis] = step;
            g[axis] = (field->density(p + d) - field->density(p - d)) / (2.0 * step);
        }
        return g;
    };
}

namespace {

/// Whether a layer rule (`uses`) or the debug view (`isView`) reads a mask
/// source; throws naming the view or `band` and what the source `needs`
/// when the scene has none (`hasSource` false).
bool needsMasks(const Scene& scene, const std::string& debugView, bool (*uses)(const render::LayerRule&),
                bool (*isView)(render::DebugView), bool hasSource, const std::string& band, const std::string& needs)
{
    const bool rules = std::any_of(scene.material.layers.begin(), scene.material.layers.end(),
                                   [uses](const LayerSettings& l) { return uses(l.rule); });
    const std::optional<render::DebugView> view = debugViewFromName(debugView);
    const bool shown = view && isView(*view);
    if ((rules || shown) && !hasSource) {
        throw Error(ErrorKind::BadInput,
                    scene.source + ": " + (shown ? "the debug view '" + debugView + "'" : band) + " needs " + needs,
                    {scene.source});
    }
    return rules || shown;
}

} // namespace

bool needsLandform(const Scene& scene, const std::string& debugView)
{
    return needsMasks(scene, debugView, render::usesLandform, render::isLandformView, scene.landformMasks != nullptr,
                      "a layer's landform band", "the landform masks of erosion: add an `erode` node to the terrain tree");
}

bool needsRock(const Scene& scene, const std::string& debugView)
{
    return needsMasks(scene, debugView, render::usesRock, render::isRockView, scene.rockMasks != nullptr,
                      "a layer's hardness or bed band",
                      "the rock masks of rock beds: add a `beds` node to the terrain tree");
}

MeshMasks neededMasks(const Scene& scene, const std::string& debugView)
{
    return {needsLandform(scene, debugView), needsRock(scene, debugView)};
}

meshing::TriangleMesh meshTerrain(const Scene& scene, const QualitySettings& quality, const SampledTerrain& terrain,
                                  std::string* what, MeshMasks extra)
{
    // Positions relative to the region's centre (the .glb node translation),
    // so float precision holds for regions far from the world origin.
    const glm::dvec3 origin = 0.5 * (scene.region.min + scene.region.max);
    // "field" normals: the density field's own gradient (central differences
    // a quarter voxel apart), not the grid's.
    meshing::TriangleMesh mesh =
        meshWithQuality(*terrain.grid, quality, fieldGradient(terrain.field, 0.25 * scene.voxelSize), origin, what);
    if (mesh.triangleCount() == 0) {
        throw Error(ErrorKind::BadInput,
                    scene.source + ": the terrain has no surface inside the region (check region and terrain.height)",
                    {scene.source});
    }
    // Cavity and cover only when a layer rule reads them.
    const bool needsSurface = std::any_of(scene.material.layers.begin(), scene.material.layers.end(),
                                          [](const LayerSettings& l) { return l.rule.cavity.enabled || l.rule.cover.enabled; });
    if (needsSurface && mesh.normals.size() == mesh.positions.size()) {
        mesh.surface = meshing::computeSurfaceAttributes(*terrain.grid, mesh);
    }
    // The landform and rock masks when a rule (or the caller's debug view) reads them.
    if (needsLandform(scene) || extra.landform) {
        if (!terrain.landformMasks) {
            throw Error(ErrorKind::BadInput,
                        scene.source + ": the landform masks are needed but the terrain has no `erode` node",
                        {scene.source});
        }
        mesh.landform = world::computeLandformAttributes(*terrain.landformMasks, mesh);
    }
    if (needsRock(scene) || extra.rock) {
        if (!terrain.rockMasks) {
            throw Error(ErrorKind::BadInput,
                        scene.source + ": the rock masks are needed but the terrain has no `beds` node",
                        {scene.source});
        }
        mesh.rock = world::computeRockAttributes(*terrain.rockMasks, mesh);
    }
    return mesh;
}

void writeTerrain(const SampledTerrain& terrain, const meshing::TriangleMesh& mesh,
                  const std::filesystem::path& outputDir, bool writePly)
{
    meshing::writeGrid(*terrain.grid, outputDir / "terrain.vdb");
    meshing::writeGlb(mesh, outputDir / "terrain.glb");
    if (writePly) meshing::writePly(mesh, outputDir / "terrain.ply");
}

RenderStats renderSnapshots(const Scene& scene, const meshing::TriangleMesh& mesh, const SnapshotRequest& request,
                            render::GlContext* context, int frames, std::optional<int> width,
                            std::optional<int> height, const std::optional<render::Camera>& cave,
                            const std::function<void(int frame, const render::Image& image)>& sink,
                            const render::Material* material)
{
    RenderStats stats;
    const render::SnapshotOptions snapshot = makeSnapshotOptions(scene, mesh, width, height, request, cave, material);
    stats.features = render::featureNames(render::materialFeatures(snapshot.material));
    const render::MeshView view = meshView(mesh);
    std::unique_ptr<render::GlRenderer> renderer;
    if (context) {
        renderer = std::make_unique<render::GlRenderer>(*context);
        renderer->setMesh(view);
    }
    for (int frame = 0; frame < frames; ++frame) {
        render::SnapshotOptions frameOptions = snapshot;
        frameOptions.camera = turntableFrame(snapshot.camera, frame, frames);
        render::CpuRenderStats cpuStats;
        const render::Image image =
            renderer ? renderer->renderImage(frameOptions) : render::renderSnapshotCpu(view, frameOptions, &cpuStats);
        stats.shadedPixels += cpuStats.shadedPixels;
        stats.textureFetches += cpuStats.textureFetches;
        stats.naiveFetches += cpuStats.naiveFetches;
        sink(frame, image);
    }
    if (renderer) {
        const render::ProgramStats programs = renderer->stats();
        stats.programsCompiled = programs.compiled;
        stats.programsPossible = programs.possible;
    }
    return stats;
}

namespace {

/// Times the stages of generate() and tells the observer.
class Stages
{
public:
    explicit Stages(PipelineObserver* observer)
        : mObserver(observer)
    {
    }
    /// Starts a stage; throws strata::Error (Interrupted) when the observer
    /// asked to stop, so every stage boundary honours an interruption.
    void begin(const std::string& stage)
    {
        if (!progress(0.0)) throw Error(ErrorKind::Interrupted, stage + " interrupted");
        mStage = stage;
        mStart = Clock::now();
        if (mObserver) mObserver->beginStage(stage);
    }
    bool progress(double fraction) { return mObserver ? mObserver->progress(fraction) : true; }
    void end(const std::string& detail = "")
    {
        const double seconds = std::chrono::duration<double>(Clock::now() - mStart).count();
        mSeconds[mStage] = seconds;
        if (mObserver) mObserver->endStage(mStage, seconds, detail);
    }
    void notice(const std::string& line)
    {
        if (mObserver) mObserver->notice(line);
    }
    std::map<std::string, double>& seconds() { return mSeconds; }
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - mCreated).count(); }

private:
    using Clock = std::chrono::steady_clock;
    PipelineObserver* mObserver;
    std::string mStage;
    Clock::time_point mCreated = Clock::now();
    Clock::time_point mStart;
    std::map<std::string, double> mSeconds;
};

} // namespace

GenerateResult generate(const Scene& input, const GenerateOptions& options, PipelineObserver* observer)
{
    Stages log(observer);
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
    // A layer or debug view that needs erosion's masks the terrain lacks: nothing written.
    const MeshMasks masks = neededMasks(scene, options.snapshot ? request.debugView : std::string());

    // The GL context first: on a machine without one, fail before the long stages.
    std::unique_ptr<render::EglContext> context;
    double contextSeconds = 0.0;
    if (options.snapshot && request.backend != "cpu") {
        log.begin("context");
        std::ostringstream notices;
        context = openBackend(request, notices, result.renderer);
        std::istringstream lines(notices.str());
        for (std::string line; std::getline(lines, line);) log.notice(line);
        log.end(result.renderer);
        contextSeconds = log.seconds().at("context");
    } else if (options.snapshot) {
        result.renderer = "strata CPU reference renderer";
    }

    // The material's maps, decoded and checked before any long stage or
    // write: a bad map fails the run with nothing written.
    std::optional<render::Material> material;
    const bool materialFiles = std::any_of(scene.material.files.begin(), scene.material.files.end(),
                                           [](const auto& file) { return file.has_value(); });
    std::uint64_t gridBudget = options.maxMemoryBytes;
    if (options.snapshot || materialFiles) {
        log.begin("material");
        material = buildMaterial(scene.material);
        // The maps count against the memory budget; the grid gets the rest.
        std::set<const render::Texture*> counted;
        std::uint64_t mapBytes = 0;
        for (const render::TexturePtr& map :
             {material->albedo, material->mask, material->normal, material->topAlbedo, material->topMask,
              material->topNormal, material->detail, material->detailNormal, material->emission}) {
            if (map && counted.insert(map.get()).second) mapBytes += render::textureBytes(map);
        }
        if (gridBudget > 0) {
            if (mapBytes >= gridBudget) {
                throw Error(ErrorKind::BadInput,
                            scene.source + ": the material's maps take " + withThousands(mapBytes >> 20) +
                                " MiB, the whole memory budget (" + withThousands(gridBudget >> 20) +
                                " MiB): use smaller maps or raise --max-memory",
                            {scene.source});
            }
            gridBudget -= mapBytes;
        }
        log.end(render::featureNames(render::materialFeatures(*material)) + ", " +
                withThousands((mapBytes + (1u << 19)) >> 20) + " MiB of maps");
    }

    result.voxelSize = scene.voxelSize;
    log.begin("generate");
    const SampledTerrain terrain = sampleTerrain(scene, options.seed, gridBudget,
                                                 [&log](double fraction) { return log.progress(fraction); });
    result.seed = terrain.seed;
    result.activeVoxels = terrain.grid->activeVoxelCount();
    result.evaluatedPoints = terrain.stats.evaluatedPoints;
    result.boundEvaluations = terrain.stats.boundEvaluations;
    result.gridMemoryBytes = terrain.grid->memUsage();
    log.end(withThousands(result.activeVoxels) + " active voxels, " +
            withThousands(result.gridMemoryBytes / 1024) + " KiB");

    // The cave view needs the grid; found before any file is written.
    std::optional<render::Camera> caveCamera;
    if (options.snapshot && request.view == "cave") {
        log.begin("cave");
        const CaveView cave = findCaveView(*terrain.grid, scene.region.min, scene.region.max);
        caveCamera = cave.camera;
        std::ostringstream info;
        info << std::fixed << std::setprecision(1) << "camera at (" << cave.camera.position.x << ", "
             << cave.camera.position.y << ", " << cave.camera.position.z << "), " << withThousands(cave.caveCells)
             << " cells of " << cave.cellSize << " m, " << (cave.looksOut ? "looking out" : "looking along the cave");
        log.end(info.str());
    }

    log.begin("mesh");
    const meshing::TriangleMesh mesh = meshTerrain(scene, result.quality, terrain, &result.mesher, masks);
    result.vertices = mesh.vertexCount();
    result.triangles = mesh.triangleCount();
    log.end(withThousands(result.vertices) + " vertices, " + withThousands(result.triangles) + " triangles, " +
            result.mesher);

    log.begin("write");
    // The output folder is made only now, when there is something to put in it.
    std::error_code ec;
    std::filesystem::create_directories(options.outputDir, ec);
    if (ec || !std::filesystem::is_directory(options.outputDir)) {
        throw Error(ErrorKind::Io,
                    "cannot create output directory '" + options.outputDir.string() + "': " +
                        (ec ? ec.message() : "a file of that name is in the way"),
                    {options.outputDir.string()});
    }
    // A run's outputs are a set: one run at a time writes into a folder.
    const OutputLock lock(options.outputDir);
    writeTerrain(terrain, mesh, options.outputDir, options.writePly);
    log.end();

    if (options.snapshot) {
        log.begin("render");
        const std::string format = request.format.empty() ? "png" : request.format;
        const std::vector<std::filesystem::path> paths =
            snapshotPaths(options.outputDir / ("snapshot." + format), request.turntable);
        int width = 0, height = 0;
        const RenderStats stats =
            renderSnapshots(scene, mesh, request, context.get(), int(paths.size()), options.width, options.height,
                            caveCamera, [&](int frame, const render::Image& image) {
                                render::writeImage(image, paths[std::size_t(frame)]);
                                width = image.width;
                                height = image.height;
                            },
                            material ? &*material : nullptr);
        result.programsCompiled = stats.programsCompiled;
        result.programsPossible = stats.programsPossible;
        result.shadedPixels = stats.shadedPixels;
        result.textureFetches = stats.textureFetches;
        result.naiveFetches = stats.naiveFetches;
        log.end(std::to_string(width) + "x" + std::to_string(height) + ", " + (context ? "gl" : "cpu") + ", " +
                stats.features +
                (options.request.debugView.empty() ? std::string() : ", debug view " + options.request.debugView) +
                (paths.size() > 1 ? ", " + std::to_string(paths.size()) + " frames" : std::string()));
    }

    result.timings = log.seconds();
    if (options.snapshot && context) {
        // Context creation is part of the render stage's cost.
        result.timings["render"] += contextSeconds;
        result.timings.erase("context");
    }
    result.timings["total"] = log.elapsed();
    writeReport(result, scene, options.threads, options.outputDir / "report.json");
    return result;
}

} // namespace strata::scene
