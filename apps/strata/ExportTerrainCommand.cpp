// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata export-terrain`: the command-line front of strata/scene/TerrainExport.h.

#include "Commands.h"
#include "MemoryFlag.h"
#include "Progress.h"

#include <strata/Format.h>
#include <strata/scene/Bake.h>
#include <strata/scene/TerrainExport.h>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

namespace strata::app {

namespace {

struct ExportTerrainArguments
{
    std::string input;
    std::string outputDir;
    std::string engine = "raw";
    double tileSize = 0.0;
    int resolution = 0;
    std::string tiles = "all";
    double heightStep = 0.0;
    std::optional<std::uint64_t> seed;
    bool noMeshes = false;
    int threads = 0;
    std::string maxMemory = "8GiB";
    bool quiet = false;
    bool force = false;
};

} // namespace

Command registerExportTerrainCommand(CLI::App& app)
{
    auto args = std::make_shared<ExportTerrainArguments>();
    CLI::App* command = app.add_subcommand(
        "export-terrain",
        "Export the world for a game engine's terrain system (Unreal Landscape, Unity Terrain, Godot): per tile a "
        "heightmap of the top surface, weight maps of the [[layer]] rules, a hole mask, and caves and overhangs as "
        ".glb meshes in the same frame; DIR/terrain.json lists the numbers to type into the import dialog");
    command->add_option("input", args->input,
                        "Scene file (TOML) or a bake folder (its scene, tile size and seed); without one, the "
                        "embedded default scene")
        ->check(CLI::ExistingPath);
    command->add_option("-o,--output", args->outputDir, "Output directory (created if missing)");
    command->add_option("--engine", args->engine, "unreal, unity, godot or raw")->capture_default_str();
    command->add_option("--tile-size", args->tileSize,
                        "Tile edge in metres, a multiple of the voxel size, at most 1024 voxels (default: 252 voxels "
                        "for Unreal, 256 otherwise; a bake's own)");
    command->add_option("--resolution", args->resolution,
                        "Heightmap samples per tile side (default: one per voxel, raised to the engine's next legal "
                        "size: Unity 2^n+1, Unreal q·n+1 with q in 7,15,31,63,127,255)");
    command->add_option("--tiles", args->tiles, "Which tiles: all, or indices and ranges A-B with commas (index = z·tiles_x + x)")
        ->capture_default_str();
    command->add_option("--height-step", args->heightStep,
                        "Metres per 16-bit height unit (default: the smallest power of two that spans the region's "
                        "height); a region taller than 65535 steps is refused");
    command->add_option("--seed", args->seed, "Override the scene's seed")->check(seedValidator());
    command->add_flag("--no-meshes", args->noMeshes, "Skip the cave and overhang meshes (meshes/NAME.glb)");
    command->add_option("--threads", args->threads, "Tiles at once (0 = all cores); the files are the same bytes for any count")
        ->check(CLI::Range(0, 1024));
    command->add_option("--max-memory", args->maxMemory, "Memory budget per tile, e.g. 8GiB (default), 512MiB")
        ->capture_default_str();
    command->add_flag("--force", args->force,
                      "Export over a folder that holds another export (another engine, scene, seed or setting)");
        command->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");

    return {command, [args]() {
                if (args->outputDir.empty())
                    throw Error(ErrorKind::BadInput, "--output is required (strata export-terrain SCENE -o DIR --engine ENGINE)",
                                {"", 0, "--output", ""});
                TerrainExportOptions options;
                options.outputDir = args->outputDir;
                options.engine = parseTerrainEngine(args->engine);
                options.tileSize = args->tileSize;
                options.resolution = args->resolution;
                options.tiles = args->tiles;
                options.heightStep = args->heightStep;
                options.seed = args->seed;
                options.meshes = !args->noMeshes;
                options.threads = args->threads;
                options.force = args->force;
                options.maxMemoryBytes = parseMemory(args->maxMemory);
                TerminalProgress progress(std::cout, stdoutIsTerminal(), args->quiet);
                std::optional<std::filesystem::path> bake;
                Scene scene;
                if (!args->input.empty() && std::filesystem::is_directory(args->input)) {
                    bake = args->input;
                    scene = loadBakedScene(args->input);
                } else {
                    const SceneLoadOptions load = sceneLoadOptions(options.maxMemoryBytes, progress);
                    scene = args->input.empty() ? defaultScene() : loadScene(args->input, load);
                }
                const TerrainExportPlan plan = planTerrainExport(scene, options, bake); // bad flags: exit 2
                if (!args->quiet)
                    std::cout << "strata export-terrain: " << scene.source << " → " << args->outputDir << "/ ("
                              << terrainEngineName(plan.engine) << ")\n  plan      " << plan.tilesX << " × "
                              << plan.tilesZ << " tiles of " << formatNumber(plan.tileSize) << " m, "
                              << plan.selected.size() << " selected; " << plan.resolution << "² samples "
                              << formatNumber(plan.spacing) << " m apart; heights " << formatNumber(plan.base)
                              << " m + value × " << formatNumber(plan.heightStep) << " m; " << plan.layers.size()
                              << " layers" << std::endl;
                const TerrainExportSummary summary = exportTerrain(scene, options, plan, &progress);
                if (!args->quiet) {
                    std::cout << "  tiles     " << summary.tiles << " written, " << withThousands(summary.holeCells)
                              << " hole cells, " << withThousands(summary.meshTriangles)
                              << " mesh triangles (caves and overhangs)\n";
                    if (summary.clippedColumns > 0)
                        std::cout << "  warning   " << withThousands(summary.clippedColumns)
                                  << " columns are rock at the region's top: raise [region] max y\n";
                    std::cout << "  import    " << args->outputDir << "/terrain.json\n  total     " << std::fixed
                              << std::setprecision(3) << summary.seconds << " s" << std::defaultfloat << std::endl;
                }
                return 0;
            }};
}

} // namespace strata::app
