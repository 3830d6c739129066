// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/QualityBench.h>

#include <strata/Error.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include <strata/scene/Snapshot.h>
#include <strata/terrain/SampleLevelSet.h>

#include <chrono>
#include <fstream>
#include <memory>
#include <optional>

namespace strata::bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

/// The renderer of the bench: one GL renderer (when EGL works) kept for all
/// configurations, or the CPU renderer.
struct BenchRenderer
{
    std::unique_ptr<render::EglContext> context;
    std::unique_ptr<render::GlRenderer> gl;
    std::string description;
};

render::Image renderTimed(BenchRenderer& r, const render::MeshView& view, const render::SnapshotOptions& options,
                          bool useGl, QualityRow& row)
{
    render::Image image;
    if (useGl) {
        r.gl->setMesh(view);
        r.gl->renderImage(options); // warm: upload, program compile, shadow map
        r.gl->finish();
        const auto start = Clock::now();
        image = r.gl->renderImage(options);
        row.renderSeconds = secondsSince(start);
        row.variants = r.gl->stats().compiled;
        row.backend = "gl";
    } else {
        render::CpuRenderStats stats;
        const auto start = Clock::now();
        image = render::renderSnapshotCpu(view, options, &stats);
        row.renderSeconds = secondsSince(start);
        row.fetches = stats.textureFetches;
        row.naiveFetches = stats.naiveFetches;
        row.backend = "cpu";
    }
    return image;
}

/// What the scene rows share across configurations.
struct SceneRun
{
    scene::Scene base;
    QualityBenchSize size;
    BenchRenderer renderer;
    std::optional<render::Camera> camera; ///< the accurate mesh frames every render
    render::Image reference, balanced;
    std::vector<std::pair<std::size_t, render::Image>> images; ///< row index, render
};

/// The default scene under one configuration: sample, mesh, measure, render.
QualityRow measureScene(SceneRun& run, const QualityConfig& config, std::size_t configIndex,
                        const scene::QualitySettings& quality, render::Image& image)
{
    const scene::Scene scene = scene::applyQuality(run.base, quality);
    QualityRow row;
    row.subject = "scene";
    row.config = configIndex;
    row.quality = quality;
    row.voxelSize = quality.voxelSize;
    const auto start = Clock::now();
    terrain::SampleOptions sampling;
    sampling.voxelSize = scene.voxelSize;
    sampling.halfWidth = scene.halfWidth;
    sampling.region = scene.region;
    const openvdb::FloatGrid::Ptr grid = terrain::sampleLevelSet(*scene.field, sampling);
    const terrain::DensityField& field = *scene.field;
    const double step = 0.25 * scene.voxelSize;
    const meshing::GradientFunction gradient = [&field, step](const glm::dvec3& p) {
        glm::dvec3 g;
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 d(0.0);
            d[axis] = step;
            g[axis] = (field.density(p + d) - field.density(p - d)) / (2.0 * step);
        }
        return g;
    };
    const meshing::TriangleMesh mesh =
        scene::meshWithQuality(*grid, quality, gradient, 0.5 * (scene.region.min + scene.region.max));
    row.meshSeconds = secondsSince(start);
    row.activeVoxels = grid->activeVoxelCount();
    row.triangles = mesh.triangleCount();

    render::SnapshotOptions snapshot = scene::makeSnapshotOptions(scene, mesh, run.size.width, run.size.height);
    if (!run.camera) run.camera = snapshot.camera;
    snapshot.camera = *run.camera;
    const bool useGl = run.renderer.gl && quality.backend != "cpu";
    if (quality.backend == "gl" && !run.renderer.gl) {
        throw Error(ErrorKind::Gl, "bench: backend gl without an OpenGL context");
    }
    image = renderTimed(run.renderer, scene::meshView(mesh), snapshot, useGl, row);
    if (run.reference.pixels.empty()) run.reference = image;
    if (config.name == "balanced") run.balanced = image;
    row.psnr = render::psnr(image, run.reference);
    return row;
}

/// The analytic shapes under one configuration: mesh, then the error
/// against the exact surface in balanced voxels.
void measureShapes(const SceneRun& run, std::size_t configIndex, const scene::QualitySettings& quality,
                   std::vector<QualityRow>& rows)
{
    const double baseVoxel = 16.0 / run.size.across;
    const double scale = quality.voxelSize / run.base.voxelSize;
    for (const meshing::AnalyticShape& shape : run.size.shapes) {
        QualityRow s;
        s.subject = shape.name;
        s.config = configIndex;
        s.quality = quality;
        s.backend = "none";
        s.voxelSize = baseVoxel * scale;
        const auto start = Clock::now();
        const openvdb::FloatGrid::Ptr grid = meshing::levelSetFromShape(shape, s.voxelSize, quality.halfWidth);
        const meshing::TriangleMesh mesh = scene::meshWithQuality(*grid, quality, shape.gradient, glm::dvec3(0.0));
        s.meshSeconds = secondsSince(start);
        s.activeVoxels = grid->activeVoxelCount();
        s.triangles = mesh.triangleCount();
        meshing::SurfaceErrorOptions exact;
        exact.voxelSize = baseVoxel; // errors in balanced voxels, comparable across voxel sizes
        exact.gradient = shape.gradient;
        exact.surfacePoints = meshing::sampleSurface(shape.distance, shape.gradient, shape.min - baseVoxel,
                                                     shape.max + baseVoxel, baseVoxel);
        s.error = meshing::measureSurfaceError(mesh, shape.distance, exact);
        rows.push_back(s);
    }
}

} // namespace

QualityBenchSize qualityBenchSize(bool tiny, bool quick)
{
    const meshing::AnalyticShape sphere = meshing::analyticSphere({0.13, -0.21, 0.07}, 7.3);
    const meshing::AnalyticShape box = meshing::analyticBox({-6.13, -4.41, -5.77}, {5.94, 4.58, 6.06});
    if (tiny) return {"tiny", 12.0, 96, 54, 16, {sphere}};
    if (quick) return {"quick", 40.0, 320, 180, 32, {sphere, box}};
    return {"full", 96.0, 640, 360, 48,
            {sphere, meshing::analyticTorus({0.11, 0.07, -0.13}, 5.0, 2.2), box, meshing::analyticGyroid(6.0, 1.2, 7.0)}};
}

bool changesGeometry(const QualityConfig& c)
{
    if (c.kind == "preset") return true;
    for (const char* key : {"voxel_scale", "voxel_size", "half_width", "mesher", "adaptivity", "normals", "projection",
                            "simplify"}) {
        if (c.knob == key) return true;
    }
    return false;
}

std::vector<QualityConfig> qualityConfigs(bool haveGl)
{
    std::vector<QualityConfig> configs;
    for (const char* preset : {"accurate", "balanced", "fast"}) configs.push_back({preset, "preset", preset, "", "", {}});
    const std::vector<std::pair<std::string, std::vector<std::string>>> sweeps = {
        {"voxel_scale", {"2", "0.5"}},
        {"half_width", {"5"}},
        {"mesher", {"surface-nets", "dual-contouring"}},
        {"adaptivity", {"0.5"}},
        {"normals", {"field", "face"}},
        {"projection", {"2"}},
        {"simplify", {"0.5"}},
        {"filtering", {"bilinear"}},
        {"normal_blend", {"udn", "rnm"}},
        {"projections", {"2"}},
        {"anti_tiling", {"on"}},
        {"shadow_resolution", {"1024", "4096"}},
        {"backend", haveGl ? std::vector<std::string>{"cpu", "gl"} : std::vector<std::string>{"cpu"}},
    };
    for (const auto& [knob, values] : sweeps) {
        for (const std::string& value : values) {
            QualityConfig c{knob + "=" + value, "knob", "balanced", knob, value, {}};
            c.overrides[knob] = scene::checkKnob(knob, value);
            configs.push_back(c);
        }
    }
    return configs;
}

std::string cpuModel()
{
    std::ifstream in("/proc/cpuinfo");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("model name", 0) == 0) {
            const std::size_t colon = line.find(':');
            if (colon != std::string::npos) {
                std::string model = line.substr(colon + 1);
                model.erase(0, model.find_first_not_of(' '));
                return model;
            }
        }
    }
    return "unknown CPU";
}

QualityBenchResult runQualityBench(const QualityBenchSize& size, int threads, std::ostream& notices,
                                   const QualityBenchObserver& observer)
{
    const auto total = Clock::now();
    QualityBenchResult result;
    result.machine = cpuModel();
    result.threads = threads;
    result.size = size;

    SceneRun run;
    run.size = size;
    run.base = scene::defaultScene();
    run.base.region.min.x = run.base.region.min.z = -size.halfExtent;
    run.base.region.max.x = run.base.region.max.z = size.halfExtent;
    result.sceneHeight = run.base.region.max.y - run.base.region.min.y;
    {
        scene::SnapshotRequest request; // auto: GL through EGL, else the CPU with a notice
        run.renderer.context = scene::openBackend(request, notices, run.renderer.description);
        if (run.renderer.context) run.renderer.gl = std::make_unique<render::GlRenderer>(*run.renderer.context);
    }
    result.gl = run.renderer.gl != nullptr;
    result.renderer = run.renderer.description;
    result.configs = qualityConfigs(result.gl);
    if (observer.started) observer.started(result);

    for (std::size_t index = 0; index < result.configs.size(); ++index) {
        const QualityConfig& config = result.configs[index];
        const scene::QualitySettings quality = scene::resolveQuality(run.base, config.preset, config.overrides);
        render::Image image;
        const QualityRow row = measureScene(run, config, index, quality, image);
        run.images.emplace_back(result.rows.size(), std::move(image));
        result.rows.push_back(row);
        if (observer.sceneMeasured) observer.sceneMeasured(config, row);
        if (changesGeometry(config)) measureShapes(run, index, quality, result.rows);
    }
    for (const auto& [index, image] : run.images) result.rows[index].psnrBalanced = render::psnr(image, run.balanced);
    if (result.gl) result.possibleVariants = run.renderer.gl->stats().possible;
    result.seconds = secondsSince(total);
    return result;
}

} // namespace strata::bench
