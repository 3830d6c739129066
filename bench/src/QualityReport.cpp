// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/QualityReport.h>

#include <strata/bench/ReportText.h>
#include <strata/scene/ParetoPlot.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace strata::bench {

namespace {

/// CSV field: quoted when it holds a comma or a quote.
std::string csvField(const std::string& s)
{
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

/// A geometric figure: blank for the scene rows (no exact surface).
std::string geometric(const QualityRow& r, double v, int digits)
{
    return r.subject == "scene" ? std::string() : fixedOrBlank(v, digits);
}

std::array<std::uint8_t, 3> colorOf(const QualityConfig& c)
{
    if (c.name == "fast") return {220, 50, 40};
    if (c.name == "balanced") return {40, 170, 60};
    if (c.name == "accurate") return {40, 90, 220};
    return {150, 150, 150};
}

void writePresets(std::ostream& md, const QualityBenchResult& result)
{
    for (std::size_t index = 0; index < result.configs.size(); ++index) {
        const QualityConfig& c = result.configs[index];
        if (c.kind != "preset") continue;
        const QualityRow* scene = nullptr;
        double shapeTime = 0.0, shapeError = 0.0;
        int shapes = 0;
        for (const QualityRow& r : result.rows) {
            if (r.config != index) continue;
            if (r.subject == "scene") scene = &r;
            else shapeTime += r.meshSeconds, shapeError += r.error.mean, ++shapes;
        }
        md << "| " << c.name << " | " << fixedOrBlank(scene->meshSeconds, 2) << " | " << scene->triangles << " | "
           << fixedOrBlank(scene->renderSeconds, 3) << " | " << fixedOrBlank(scene->psnr, 1) << " | "
           << fixedOrBlank(shapeTime, 3) << " | " << fixedOrBlank(shapes ? shapeError / shapes : NAN, 4) << " |\n";
    }
}

void writeEveryRow(std::ostream& md, const QualityBenchResult& result)
{
    for (const QualityRow& r : result.rows) {
        md << "| " << r.subject << " | " << result.configs[r.config].name << " | " << r.backend << " | " << r.voxelSize
           << " | " << r.activeVoxels << " | " << r.triangles << " | " << fixedOrBlank(r.meshSeconds, 3) << " | "
           << geometric(r, r.error.mean, 4) << " | " << geometric(r, r.error.rms, 4) << " | "
           << geometric(r, r.error.hausdorff, 3) << " | " << geometric(r, r.error.normalMeanDegrees, 2) << " | "
           << fixedOrBlank(r.renderSeconds, 3) << " | " << fixedOrBlank(r.psnr, 1) << " | "
           << fixedOrBlank(r.psnrBalanced, 1) << " | "
           << (r.naiveFetches ? std::to_string(r.fetches) + " / " + std::to_string(r.naiveFetches) : std::string())
           << " |\n";
    }
}

} // namespace

std::string formatQualityCsv(const QualityBenchResult& result)
{
    std::ostringstream csv;
    csv << "machine,threads,backend,subject,config,kind,preset,knob,value,voxel_size_m,active_voxels,triangles,"
           "mesh_s,error_mean_voxels,error_rms_voxels,error_hausdorff_voxels,normal_error_deg,render_s,psnr_db,"
           "psnr_vs_balanced_db,texture_fetches,naive_fetches,shader_variants\n";
    for (const QualityRow& r : result.rows) {
        const QualityConfig& c = result.configs[r.config];
        csv << csvField(result.machine) << "," << result.threads << "," << r.backend << "," << r.subject << ","
            << c.name << "," << c.kind << "," << c.preset << "," << c.knob << "," << c.value << "," << r.voxelSize
            << "," << r.activeVoxels << "," << r.triangles << "," << fixedOrBlank(r.meshSeconds, 4) << ","
            << geometric(r, r.error.mean, 5) << "," << geometric(r, r.error.rms, 5) << ","
            << geometric(r, r.error.hausdorff, 4) << "," << geometric(r, r.error.normalMeanDegrees, 3) << ","
            << fixedOrBlank(r.renderSeconds, 4) << "," << fixedOrBlank(r.psnr, 2) << ","
            << fixedOrBlank(r.psnrBalanced, 2) << "," << r.fetches << "," << r.naiveFetches << "," << r.variants
            << "\n";
    }
    return csv.str();
}

render::Image drawQualityPlot(const QualityBenchResult& result)
{
    // The mean over the shapes per configuration; the scene's renders.
    scene::PlotPanel geometry{"Meshing: time vs geometric error (analytic shapes)",
                              "sampling + meshing time, s (sum over shapes)", "mean error, voxels", true, true, false, {}};
    scene::PlotPanel image{"Rendering: time vs image error (default scene)", "render time, s",
                           "PSNR vs accurate, dB (higher is better)", true, false, true, {}};
    double best = 0.0; // the reference itself is drawn above the best PSNR
    for (const QualityRow& o : result.rows) {
        if (o.subject == "scene" && std::isfinite(o.psnr)) best = std::max(best, o.psnr);
    }
    for (std::size_t index = 0; index < result.configs.size(); ++index) {
        const QualityConfig& c = result.configs[index];
        double time = 0.0, error = 0.0;
        int shapes = 0;
        for (const QualityRow& r : result.rows) {
            if (r.config != index) continue;
            if (r.subject == "scene") {
                scene::PlotPoint p{r.renderSeconds, std::isfinite(r.psnr) ? r.psnr : NAN, c.name, colorOf(c),
                                   c.kind == "preset"};
                if (!std::isfinite(r.psnr)) {
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
        if (shapes > 0) geometry.points.push_back({time, error / shapes, c.name, colorOf(c), c.kind == "preset"});
    }
    return scene::drawPlot({geometry, image}, 760, 620);
}

std::string formatQualityMarkdown(const QualityBenchResult& result)
{
    const QualityBenchSize& size = result.size;
    std::ostringstream md;
    md << "# strata bench: speed against accuracy\n\n"
       << "Machine: " << result.machine << ", " << result.threads << " threads; renderer: "
       << (result.gl ? result.renderer + " (gl)" : std::string("CPU reference renderer (cpu)"))
       << ". Setting: " << size.name << " (default scene region " << 2 * size.halfExtent << " x "
       << result.sceneHeight << " x " << 2 * size.halfExtent << " m, images " << size.width << "x" << size.height
       << "; shapes at " << size.across << " voxels across 16 m at balanced). "
       << "This run took " << fixedOrBlank(result.seconds, 1) << " s.\n\n"
       << "Each preset, then each knob changed on its own from `balanced`. Geometric error is in voxels of the "
          "balanced voxel size, so a coarser preset shows its real loss: for the analytic shapes it is the mean "
          "distance between the mesh and the exact surface (both directions). The scene has no exact surface: its "
          "rows give time, triangles and image error. Image error is PSNR against the `accurate` render from the "
          "same camera (inf = the reference); PSNR vs balanced compares with the balanced render, which isolates "
          "the render-only knobs (same mesh). Mesh time is sampling plus meshing (plus simplification); render "
          "time is one warm frame (GL: after one untimed frame that uploads and compiles). Texture fetches are "
          "counted on the CPU renderer (map samples done, and a naive shader's 3 per map group); shader_variants in "
          "report.csv is how many program variants the bench's one GL renderer has compiled so far (of "
       << (result.gl ? std::to_string(result.possibleVariants) : std::string("-")) << " possible).\n\n"
       << "## Presets\n\n"
       << "| preset | scene mesh (s) | scene triangles | render (s) | PSNR (dB) | shapes mesh (s) | shapes error "
          "(voxels) |\n|---|---:|---:|---:|---:|---:|---:|\n";
    writePresets(md, result);
    md << "\n## Every row\n\n"
       << "| subject | config | backend | voxel (m) | active voxels | triangles | mesh (s) | error mean | RMS | "
          "Hausdorff | normal (deg) | render (s) | PSNR (dB) | PSNR vs balanced | fetches / naive |\n"
       << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
    writeEveryRow(md, result);
    md << "\nEvery row of report.csv also gives the machine (" << result.machine << "), the thread count ("
       << result.threads
       << ") and the backend. The plot is pareto.png: the orange line joins the configurations that no other beats "
          "on both time and error.\n";
    return md.str();
}

void writeQualityReport(const QualityBenchResult& result, const std::filesystem::path& dir)
{
    writeTextFile(dir / "report.csv", formatQualityCsv(result));
    writeTextFile(dir / "report.md", formatQualityMarkdown(result));
    render::writeImage(drawQualityPlot(result), dir / "pareto.png");
}

} // namespace strata::bench
