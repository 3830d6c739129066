// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench -o DIR [--quick]`: speed against accuracy, measured. Runs the
// default scene and the analytic shapes under each quality preset and with
// each knob swept on its own from `balanced`; writes DIR/report.md,
// DIR/report.csv and DIR/pareto.png (each atomically). `strata bench mesh`
// (BenchMeshCommand.cpp), `strata bench noise` (BenchNoiseCommand.cpp) and
// `strata bench landforms` (BenchLandformsCommand.cpp) are registered under it.

#include "Commands.h"
#include <strata/scene/Pipeline.h>
#include <strata/scene/ParetoPlot.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>
#include <strata/scene/Snapshot.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/render/CpuRenderer.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/terrain/SampleLevelSet.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace strata::app {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string fixed(double value, int digits)
{
    if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
    if (std::isnan(value)) return "";
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

struct BenchArguments
{
    std::string outputDir;
    bool quick = false;
    bool tiny = false; // hidden: the ctest setting
    int threads = 0;
};

/// How big the run is.
struct BenchSize
{
    std::string name;
    double halfExtent = 96.0; // scene region half size in x and z (metres)
    int width = 640, height = 360;
    int across = 48; // analytic shapes: voxels across 16 m at balanced
    std::vector<meshing::AnalyticShape> shapes;
};

BenchSize benchSize(const BenchArguments& args)
{
    BenchSize s;
    const meshing::AnalyticShape sphere = meshing::analyticSphere({0.13, -0.21, 0.07}, 7.3);
    const meshing::AnalyticShape box = meshing::analyticBox({-6.13, -4.41, -5.77}, {5.94, 4.58, 6.06});
    if (args.tiny) {
        s = {"tiny", 12.0, 96, 54, 16, {sphere}};
    } else if (args.quick) {
        s = {"quick", 40.0, 320, 180, 32, {sphere, box}};
    } else {
        s = {"full", 96.0, 640, 360, 48,
             {sphere, meshing::analyticTorus({0.11, 0.07, -0.13}, 5.0, 2.2), box, meshing::analyticGyroid(6.0, 1.2, 7.0)}};
    }
    return s;
}

struct Config
{
    std::string name; // "fast", "mesher=surface-nets"
    std::string kind; // "preset" or "knob"
    std::string preset = "balanced";
    std::string knob, value;
    QualityOverrides overrides;
};

bool changesGeometry(const Config& c)
{
    if (c.kind == "preset") return true;
    for (const char* key : {"voxel_scale", "voxel_size", "half_width", "mesher", "adaptivity", "normals", "projection",
                            "simplify"}) {
        if (c.knob == key) return true;
    }
    return false;
}

/// Accurate first (the image reference and the camera), then the other
/// presets, then each knob on its own from balanced.
std::vector<Config> benchConfigs(bool haveGl)
{
    std::vector<Config> configs;
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
            Config c{knob + "=" + value, "knob", "balanced", knob, value, {}};
            c.overrides[knob] = checkKnob(knob, value);
            configs.push_back(c);
        }
    }
    return configs;
}

struct Row
{
    std::string subject; // "scene", "sphere", ...
    const Config* config = nullptr;
    std::string backend; // "gl", "cpu", or "none" (not rendered)
    QualitySettings quality;
    double voxelSize = 0.0;
    std::uint64_t activeVoxels = 0, triangles = 0;
    double meshSeconds = 0.0; // sampling + meshing (+ simplification)
    meshing::SurfaceError error;
    double renderSeconds = NAN, psnr = NAN;
    double psnrBalanced = NAN; ///< against the balanced render (render-only knobs: the same mesh)
    std::uint64_t fetches = 0, naiveFetches = 0;
    int variants = 0;
};

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

/// CSV field: quoted when it holds a comma or a quote.
std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

void writeText(const std::filesystem::path& path, const std::string& text)
{
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        out << text;
        if (!out.flush()) throw Error(ErrorKind::Io, "cannot write '" + path.string() + "'", {path.string()});
    });
}

/// The renderer of the bench: one GL renderer (when EGL works) kept for all
/// configurations, or the CPU renderer.
struct BenchRenderer
{
    std::unique_ptr<render::EglContext> context;
    std::unique_ptr<render::GlRenderer> gl;
    std::string description;
};

render::Image renderTimed(BenchRenderer& r, const render::MeshView& view, const render::SnapshotOptions& options,
                          bool useGl, Row& row)
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

int runBench(const BenchArguments& args)
{
    const auto total = Clock::now();
    const std::filesystem::path dir(args.outputDir);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        throw Error(ErrorKind::Io, "cannot create output directory '" + dir.string() + "': " + ec.message(), {dir.string()});
    }
    std::unique_ptr<tbb::global_control> threadLimit;
    if (args.threads > 0) {
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            std::size_t(args.threads));
    }
    const int threads = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    const std::string machine = cpuModel();
    const BenchSize size = benchSize(args);

    Scene base = defaultScene();
    base.region.min.x = base.region.min.z = -size.halfExtent;
    base.region.max.x = base.region.max.z = size.halfExtent;

    BenchRenderer renderer;
    {
        SnapshotRequest request; // auto: GL through EGL, else the CPU with a notice
        renderer.context = openBackend(request, std::cerr, renderer.description);
        if (renderer.context) renderer.gl = std::make_unique<render::GlRenderer>(*renderer.context);
    }
    const std::vector<Config> configs = benchConfigs(renderer.gl != nullptr);
    std::cout << "strata bench (" << size.name << "): " << configs.size() << " configurations on " << machine << ", "
              << threads << " threads, renderer: " << (renderer.gl ? renderer.description : "CPU") << std::endl;

    std::vector<Row> rows;
    render::Image reference, balancedImage;
    std::vector<std::pair<std::size_t, render::Image>> sceneImages; // row index, render
    std::optional<render::Camera> camera;
    for (const Config& config : configs) {
        const QualitySettings quality = resolveQuality(base, config.preset, config.overrides);
        const Scene scene = applyQuality(base, quality);

        // The default scene: sample, mesh, measure, render.
        Row row;
        row.subject = "scene";
        row.config = &config;
        row.quality = quality;
        row.voxelSize = quality.voxelSize;
        auto start = Clock::now();
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
            meshWithQuality(*grid, quality, gradient, 0.5 * (scene.region.min + scene.region.max));
        row.meshSeconds = secondsSince(start);
        row.activeVoxels = grid->activeVoxelCount();
        row.triangles = mesh.triangleCount();

        render::SnapshotOptions snapshot = makeSnapshotOptions(scene, mesh, size.width, size.height);
        if (!camera) camera = snapshot.camera; // the accurate mesh frames every render
        snapshot.camera = *camera;
        const bool useGl = renderer.gl && quality.backend != "cpu";
        if (quality.backend == "gl" && !renderer.gl) throw Error(ErrorKind::Gl, "bench: backend gl without an OpenGL context");
        const render::Image image = renderTimed(renderer, meshView(mesh), snapshot, useGl, row);
        if (reference.pixels.empty()) reference = image;
        if (config.name == "balanced") balancedImage = image;
        row.psnr = render::psnr(image, reference);
        sceneImages.emplace_back(rows.size(), image);
        rows.push_back(row);
        std::cout << "  " << config.name << ": scene " << fixed(row.meshSeconds, 2) << " s mesh, "
                  << fixed(row.renderSeconds, 3) << " s render (" << row.backend << "), PSNR " << fixed(row.psnr, 1)
                  << " dB" << std::endl;

        // The analytic shapes, for the configurations that change geometry.
        if (!changesGeometry(config)) continue;
        const double baseVoxel = 16.0 / size.across;
        const double scale = quality.voxelSize / base.voxelSize;
        for (const meshing::AnalyticShape& shape : size.shapes) {
            Row s;
            s.subject = shape.name;
            s.config = &config;
            s.quality = quality;
            s.backend = "none";
            s.voxelSize = baseVoxel * scale;
            start = Clock::now();
            const openvdb::FloatGrid::Ptr shapeGrid = meshing::levelSetFromShape(shape, s.voxelSize, quality.halfWidth);
            const meshing::TriangleMesh shapeMesh = meshWithQuality(*shapeGrid, quality, shape.gradient, glm::dvec3(0.0));
            s.meshSeconds = secondsSince(start);
            s.activeVoxels = shapeGrid->activeVoxelCount();
            s.triangles = shapeMesh.triangleCount();
            meshing::SurfaceErrorOptions exact;
            exact.voxelSize = baseVoxel; // errors in balanced voxels, comparable across voxel sizes
            exact.gradient = shape.gradient;
            exact.surfacePoints = meshing::sampleSurface(shape.distance, shape.gradient, shape.min - baseVoxel,
                                                         shape.max + baseVoxel, baseVoxel);
            s.error = meshing::measureSurfaceError(shapeMesh, shape.distance, exact);
            rows.push_back(s);
        }
    }
    for (const auto& [index, sceneImage] : sceneImages) rows[index].psnrBalanced = render::psnr(sceneImage, balancedImage);
    const double runSeconds = secondsSince(total);

    // report.csv; the scene rows have no geometric error (no exact surface).
    std::ostringstream csv;
    csv << "machine,threads,backend,subject,config,kind,preset,knob,value,voxel_size_m,active_voxels,triangles,"
           "mesh_s,error_mean_voxels,error_rms_voxels,error_hausdorff_voxels,normal_error_deg,render_s,psnr_db,"
           "psnr_vs_balanced_db,texture_fetches,naive_fetches,shader_variants\n";
    for (const Row& r : rows) {
        const Config& c = *r.config;
        auto geo = [&r](double v, int digits) { return r.subject == "scene" ? std::string() : fixed(v, digits); };
        csv << csvField(machine) << "," << threads << "," << r.backend << "," << r.subject << "," << c.name << ","
            << c.kind << "," << c.preset << "," << c.knob << "," << c.value << "," << r.voxelSize << ","
            << r.activeVoxels << "," << r.triangles << "," << fixed(r.meshSeconds, 4) << "," << geo(r.error.mean, 5)
            << "," << geo(r.error.rms, 5) << "," << geo(r.error.hausdorff, 4) << "," << geo(r.error.normalMeanDegrees, 3)
            << ","
            << fixed(r.renderSeconds, 4) << "," << fixed(r.psnr, 2) << "," << fixed(r.psnrBalanced, 2) << "," << r.fetches << "," << r.naiveFetches
            << "," << r.variants << "\n";
    }

    // pareto.png: mean over the shapes per configuration; the scene's renders.
    PlotPanel geometry{"Meshing: time vs geometric error (analytic shapes)",
                       "sampling + meshing time, s (sum over shapes)", "mean error, voxels", true, true, false, {}};
    PlotPanel image{"Rendering: time vs image error (default scene)", "render time, s",
                    "PSNR vs accurate, dB (higher is better)", true, false, true, {}};
    auto colorOf = [](const Config& c) -> std::array<std::uint8_t, 3> {
        if (c.name == "fast") return {220, 50, 40};
        if (c.name == "balanced") return {40, 170, 60};
        if (c.name == "accurate") return {40, 90, 220};
        return {150, 150, 150};
    };
    for (const Config& c : configs) {
        double time = 0.0, error = 0.0;
        int shapes = 0;
        for (const Row& r : rows) {
            if (r.config != &c) continue;
            if (r.subject == "scene") {
                PlotPoint p{r.renderSeconds, std::isfinite(r.psnr) ? r.psnr : NAN, c.name, colorOf(c), c.kind == "preset"};
                if (!std::isfinite(r.psnr)) { // the reference itself: drawn at the top
                    double best = 0.0;
                    for (const Row& o : rows) {
                        if (o.subject == "scene" && std::isfinite(o.psnr)) best = std::max(best, o.psnr);
                    }
                    p.y = best + 3.0;
                    p.label = c.name + " (reference)";
                }
                image.points.push_back(p);
            } else {
                time += r.meshSeconds;
                error += r.error.mean;
                ++shapes;
            }
        }
        if (shapes > 0) {
            geometry.points.push_back({time, error / shapes, c.name, colorOf(c), c.kind == "preset"});
        }
    }
    const render::Image plot = drawPlot({geometry, image}, 760, 620);

    // report.md
    std::ostringstream md;
    md << "# strata bench: speed against accuracy\n\n"
       << "Machine: " << machine << ", " << threads << " threads; renderer: "
       << (renderer.gl ? renderer.description + " (gl)" : std::string("CPU reference renderer (cpu)"))
       << ". Setting: " << size.name << " (default scene region " << 2 * size.halfExtent << " x "
       << base.region.max.y - base.region.min.y << " x " << 2 * size.halfExtent << " m, images " << size.width
       << "x" << size.height << "; shapes at " << size.across << " voxels across 16 m at balanced). "
       << "This run took " << fixed(runSeconds, 1) << " s.\n\n"
       << "Each preset, then each knob changed on its own from `balanced`. Geometric error is in voxels of the "
          "balanced voxel size, so a coarser preset shows its real loss: for the analytic shapes it is the mean "
          "distance between the mesh and the exact surface (both directions). The scene has no exact surface: its "
          "rows give time, triangles and image error. Image error is PSNR against the `accurate` render from the "
          "same camera (inf = the reference); PSNR vs balanced compares with the balanced render, which isolates "
          "the render-only knobs (same mesh). Mesh time is sampling plus meshing (plus simplification); render "
          "time is one warm frame (GL: after one untimed frame that uploads and compiles). Texture fetches are "
          "counted on the CPU renderer (map samples done, and a naive shader's 3 per map group); shader_variants in "
          "report.csv is how many program variants the bench's one GL renderer has compiled so far (of "
       << (renderer.gl ? std::to_string(renderer.gl->stats().possible) : std::string("-")) << " possible).\n\n"
       << "## Presets\n\n"
       << "| preset | scene mesh (s) | scene triangles | render (s) | PSNR (dB) | shapes mesh (s) | shapes error "
          "(voxels) |\n|---|---:|---:|---:|---:|---:|---:|\n";
    for (const Config& c : configs) {
        if (c.kind != "preset") continue;
        const Row* scene = nullptr;
        double shapeTime = 0.0, shapeError = 0.0;
        int shapes = 0;
        for (const Row& r : rows) {
            if (r.config != &c) continue;
            if (r.subject == "scene") scene = &r;
            else shapeTime += r.meshSeconds, shapeError += r.error.mean, ++shapes;
        }
        md << "| " << c.name << " | " << fixed(scene->meshSeconds, 2) << " | " << scene->triangles << " | "
           << fixed(scene->renderSeconds, 3) << " | " << fixed(scene->psnr, 1) << " | " << fixed(shapeTime, 3) << " | "
           << fixed(shapes ? shapeError / shapes : NAN, 4) << " |\n";
    }
    md << "\n## Every row\n\n"
       << "| subject | config | backend | voxel (m) | active voxels | triangles | mesh (s) | error mean | RMS | "
          "Hausdorff | normal (deg) | render (s) | PSNR (dB) | PSNR vs balanced | fetches / naive |\n"
       << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const Row& r : rows) {
        auto geo = [&r](double v, int digits) { return r.subject == "scene" ? std::string() : fixed(v, digits); };
        md << "| " << r.subject << " | " << r.config->name << " | " << r.backend << " | " << r.voxelSize << " | "
           << r.activeVoxels << " | " << r.triangles << " | " << fixed(r.meshSeconds, 3) << " | "
           << geo(r.error.mean, 4) << " | " << geo(r.error.rms, 4) << " | " << geo(r.error.hausdorff, 3) << " | "
           << geo(r.error.normalMeanDegrees, 2) << " | " << fixed(r.renderSeconds, 3)
           << " | " << fixed(r.psnr, 1) << " | " << fixed(r.psnrBalanced, 1) << " | "
           << (r.naiveFetches ? std::to_string(r.fetches) + " / " + std::to_string(r.naiveFetches) : std::string())
           << " |\n";
    }
    md << "\nEvery row of report.csv also gives the machine (" << machine << "), the thread count (" << threads
       << ") and the backend. The plot is pareto.png: the orange line joins the configurations that no other beats "
          "on both time and error.\n";

    writeText(dir / "report.csv", csv.str());
    writeText(dir / "report.md", md.str());
    render::writeImage(plot, dir / "pareto.png");
    std::cout << "wrote " << (dir / "report.md").string() << ", " << (dir / "report.csv").string() << " and "
              << (dir / "pareto.png").string() << " in " << fixed(secondsSince(total), 1) << " s" << std::endl;
    return 0;
}

} // namespace

Command registerBenchCommand(CLI::App& app)
{
    auto args = std::make_shared<BenchArguments>();
    CLI::App* bench = app.add_subcommand(
        "bench", "Speed against accuracy: the default scene and analytic shapes under each quality preset and each "
                 "knob on its own; writes DIR/report.md, DIR/report.csv, DIR/pareto.png. `bench mesh`: the meshers; `bench noise`: the noise bases; `bench landforms`: the top surface against real land");
    bench->add_option("-o,--output", args->outputDir, "Output directory (created if missing)");
    bench->add_flag("--quick", args->quick, "A smaller scene region, images and fewer shapes (under a minute on 2 cores)");
    bench->add_flag("--tiny", args->tiny, "The test setting (seconds)")->group("");
    bench->add_option("--threads", args->threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
    const Command mesh = registerBenchMeshCommand(*bench);
    const Command noise = registerBenchNoiseCommand(*bench);
    const Command landforms = registerBenchLandformsCommand(*bench);
    return {bench, [args, mesh, noise, landforms]() {
                if (mesh.subcommand->parsed()) return mesh.run();
                if (noise.subcommand->parsed()) return noise.run();
                if (landforms.subcommand->parsed()) return landforms.run();
                if (args->outputDir.empty()) throw Error(ErrorKind::BadInput, "bench: -o DIR is required");
                return runBench(*args);
            }};
}

} // namespace strata::app
