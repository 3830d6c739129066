// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata generate`: the command-line front of strata/scene/Pipeline.h.

#include "Commands.h"
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>
#include <strata/scene/SceneOffset.h>
#include "MemoryFlag.h"
#include "SnapshotFlags.h"

#include <strata/Error.h>
#include <strata/Format.h>
#include "Progress.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <regex>

namespace strata::app {

namespace {

struct GenerateArguments
{
    std::string scenePath;
    std::string outputDir;
    std::optional<std::uint64_t> seed;
    int threads = 0;
    std::string maxMemory = "8GiB";
    std::string size;
    bool noSnapshot = false;
    std::string offset; ///< --offset X,Y,Z
    SnapshotFlags snapshot;
    bool writePly = false;
    bool quiet = false;
    std::optional<std::string> preset;  ///< --preset
    std::vector<std::string> quality;   ///< --quality KEY=VALUE, repeatable
};

/// The closing lines of `strata generate`: what the model saved, the
/// quality settings and the total time.
void printSummary(const GenerateResult& result, const std::filesystem::path& outputDir)
{
    std::ostringstream model;
    model << std::fixed << std::setprecision(2) << "  model     " << withThousands(result.evaluatedPoints)
          << " points evaluated for " << withThousands(result.activeVoxels) << " active voxels ("
          << (result.activeVoxels ? double(result.evaluatedPoints) / double(result.activeVoxels) : 0.0)
          << " per voxel)";
    if (result.programsPossible > 0) {
        model << "; " << result.programsCompiled << " of " << result.programsPossible << " shader variants compiled";
    }
    if (result.naiveFetches > 0) {
        model << "; " << withThousands(result.textureFetches) << " texture fetches of "
              << withThousands(result.naiveFetches) << " naive ("
              << 100.0 * double(result.naiveFetches - result.textureFetches) / double(result.naiveFetches)
              << "% skipped)";
    }
    std::cout << model.str() << "\n  quality   " << describeQuality(result.quality) << '\n';
    std::cout << "  total     " << std::fixed << std::setprecision(3) << std::setw(8) << result.timings.at("total")
              << " s   wrote " << outputDir.string() << "/" << std::defaultfloat << std::endl;
}

} // namespace

Command registerGenerateCommand(CLI::App& app)
{
    auto args = std::make_shared<GenerateArguments>();
    CLI::App* generate = app.add_subcommand(
        "generate", "Generate a terrain: writes DIR/terrain.vdb, DIR/terrain.glb, DIR/snapshot.png (or .exr, or "
        "snapshot_000.png ... with --turntable), DIR/report.json");
    generate->add_option("scene", args->scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    generate->add_option("-o,--output", args->outputDir, "Output directory (created if missing)")->required();
    generate->add_option("--seed", args->seed, "Override the scene's seed")
        ->check(seedValidator());
    generate->add_option("--max-memory", args->maxMemory,
                         "Memory budget: the material maps count first, then a grid that would need more than the rest is refused, e.g. 8GiB (default), 512MiB")
        ->capture_default_str();
    generate->add_option("--threads", args->threads, "Worker threads (0 = all cores); output is identical for any count")
        ->check(CLI::Range(0, 1024));
    generate->add_option("--size", args->size, "Snapshot size WIDTHxHEIGHT (default from the scene, 1280x720)");
    generate->add_option("--offset", args->offset,
                         "Move the whole scene (terrain, region, camera; camera flags included) by X,Y,Z world "
                         "metres, |value| <= 1e9");
    args->snapshot.add(generate);
    generate->add_option("--preset", args->preset,
                         "Quality preset: fast, balanced (default: the scene as written) or accurate; "
                         "overrides the scene's [quality] preset");
    generate->add_option("--quality", args->quality,
                         "Override one quality knob, KEY=VALUE (repeatable; wins over the preset and [quality]): "
                         "voxel_size, voxel_scale, half_width, mesher, adaptivity, normals, projection, simplify, "
                         "filtering, normal_blend, shadow_resolution, backend");
    generate->add_flag("--no-snapshot", args->noSnapshot, "Skip the snapshot (no OpenGL/EGL needed)");
    generate->add_flag("--ply", args->writePly, "Also write DIR/terrain.ply (binary PLY)");
    generate->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");

    return {generate, [args, generate]() {
                // First: from here on the first Ctrl-C is a clean stop (exit 130), even
                // while the scene and its maps are still being read.
                TerminalProgress progress(std::cout, stdoutIsTerminal(), args->quiet);
                GenerateOptions options;
                options.outputDir = args->outputDir;
                options.seed = args->seed;
                options.snapshot = !args->noSnapshot;
                options.request = args->snapshot.request(); // bad values: exit 2 before anything is written
                options.preset = args->preset;
                if (args->preset && std::find(presetNames().begin(), presetNames().end(), *args->preset) ==
                                        presetNames().end()) { // an unknown preset: exit 2, nothing written
                    throw Error(ErrorKind::BadInput, "--preset '" + *args->preset + "' is not a preset (use fast, balanced or accurate)");
                }
                for (const std::string& text : args->quality) addQualityFlag(text, options.quality);
                // --backend is the backend knob's flag: it wins over [quality] and the preset.
                if (generate->get_option("--backend")->count() > 0) {
                    options.quality["backend"] = checkKnob("backend", options.request.backend);
                }
                options.writePly = args->writePly;
                options.threads = args->threads;
                options.maxMemoryBytes = parseMemory(args->maxMemory);
                if (!args->size.empty()) {
                    const auto [width, height] = parseSizeFlag(args->size);
                    options.width = width;
                    options.height = height;
                }
                const glm::dvec3 offset =
                    args->offset.empty() ? glm::dvec3(0.0) : parseVec3Flag("--offset", args->offset);
                offsetRequest(options.request, offset);
                const SceneLoadOptions load = sceneLoadOptions(options.maxMemoryBytes, progress);
                const Scene scene = offsetScene(args->scenePath.empty() ? defaultScene() : loadScene(args->scenePath, load),
                                                offset);

                std::unique_ptr<tbb::global_control> threadLimit;
                if (args->threads > 0) {
                    threadLimit = std::make_unique<tbb::global_control>(
                        tbb::global_control::max_allowed_parallelism, std::size_t(args->threads));
                }
                if (!args->quiet) {
                    std::cout << "strata generate: " << scene.source << " → " << args->outputDir << "/" << std::endl;
                    for (const LandformPass& pass : scene.landformPasses) {
                        std::printf("  landform %8.3f s   %s: %s cells, %d steps%s\n", pass.seconds, pass.node.c_str(),
                                    withThousands(pass.cells).c_str(), pass.steps, pass.cached ? " (cached)" : "");
                    }
                }
                const GenerateResult result = scene::generate(scene, options, &progress);
                if (!args->quiet) printSummary(result, options.outputDir);
                return 0;
            }};
}

Command registerSceneCommand(CLI::App& app)
{
    CLI::App* scene = app.add_subcommand("scene", "Print the embedded default scene (a starting point for your own)");
    return {scene, []() {
                std::cout << defaultSceneText();
                return 0;
            }};
}

} // namespace strata::app
