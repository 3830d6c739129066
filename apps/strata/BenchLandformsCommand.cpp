// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench landforms [SCENE.toml] [--dem FILE]`: how much a terrain's
// top surface (or a DEM's) looks like real land, measured by
// bench::measureSceneLandforms / bench::measureDemLandforms
// (bench/LandformBench.h). This file parses flags and prints;
// docs/landform-statistics.md says what the numbers mean.

#include "Commands.h"
#include "Progress.h"

#include <strata/bench/LandformBench.h>
#include <strata/scene/Snapshot.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <iostream>
#include <memory>
#include <optional>

namespace strata::app {

namespace {

struct LandformArguments
{
    bench::LandformSceneOptions scene;
    std::string regionMin, regionMax; ///< "X,Z"
    std::string dem;
    std::optional<double> demCell;
    int threads = 0;
};

void checkFlags(const LandformArguments& args, const CLI::App& command)
{
    if (!args.dem.empty()) {
        if (!args.scene.scenePath.empty() || !args.regionMin.empty() || !args.regionMax.empty() ||
            command.count("--cell") > 0) {
            throw Error(ErrorKind::BadInput, "--dem measures a DEM file: give no scene, --cell, --region-min or --region-max with it "
                        "(--dem-cell sets the DEM's cell size)");
        }
        if (command.count("--overhang-depth") > 0 || command.count("--overhang-step") > 0) {
            throw Error(ErrorKind::BadInput, "--overhang-depth and --overhang-step measure a scene's volume: a --dem "
                        "file has none");
        }
    } else if (args.demCell) {
        throw Error(ErrorKind::BadInput, "--dem-cell is the cell size of a --dem file: give --dem FILE, or --cell for a scene");
    }
}

int runLandforms(const LandformArguments& args, const CLI::App& command)
{
    checkFlags(args, command);
    std::optional<tbb::global_control> threadLimit;
    if (args.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(args.threads));
    const int count = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    const std::string threads = std::to_string(count) + (count == 1 ? " thread" : " threads");
    TerminalProgress progress(std::cout, stdoutIsTerminal(), false);
    const auto note = [](const std::string& line) { std::cout << "  note: " << line << std::endl; };
    bench::LandformBenchResult result;
    if (!args.dem.empty()) {
        std::cout << "strata bench landforms: DEM " << args.dem << " (" << threads << ")" << std::endl;
        result = bench::measureDemLandforms({args.dem, args.demCell, args.scene.textureCells}, progress, note);
    } else {
        // Bad flags are refused before the (possibly long) global pass.
        bench::LandformSceneOptions options = args.scene;
        if (!args.regionMin.empty()) options.cropMin = parseVec2Flag("--region-min", args.regionMin);
        if (!args.regionMax.empty()) options.cropMax = parseVec2Flag("--region-max", args.regionMax);
        bench::checkLandformSceneOptions(options);
        std::cout << "strata bench landforms: " << (options.scenePath.empty() ? "<default scene>" : options.scenePath)
                  << " (" << threads << ")" << std::endl;
        result = bench::measureSceneLandforms(options, progress, note);
    }
    std::cout << bench::formatLandformBench(result) << std::flush;
    return 0;
}

} // namespace

Command registerBenchLandformsCommand(CLI::App& bench)
{
    auto args = std::make_shared<LandformArguments>();
    CLI::App* landforms = bench.add_subcommand(
        "landforms", "How much a scene's top surface (or a DEM file) looks like real land: closed depressions, "
                     "flats, Hack's law, slope-area concavity, against the project's goals; surface texture "
                     "(roughness, spectral slopes, slope angles, cliffs) at several cell sizes; overhangs");
    landforms->add_option("scene", args->scene.scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    landforms->add_option("--cell", args->scene.cell, "Distance between the top surface's columns, metres")
        ->check(CLI::Range(1e-3, 1e6))
        ->capture_default_str();
    landforms->add_option("--region-min", args->regionMin,
                          "Crop: the lowest x,z corner to sample, metres (default: the scene's [region])");
    landforms->add_option("--region-max", args->regionMax,
                          "Crop: the highest x,z corner to sample, metres (default: the scene's [region])");
    landforms->add_option("--dem", args->dem,
                          "Measure this DEM instead of a scene: NumPy .npy, .npz (stored or deflated members) or an "
                          "ESRI ASCII grid .asc");
    landforms
        ->add_option("--dem-cell", args->demCell,
                     "The DEM's cell size in metres: needed for .npy and .npz (they hold none); overrides an "
                     ".asc file's cellsize")
        ->check(CLI::Range(1e-3, 1e6));
    landforms
        ->add_option("--texture-cells", args->scene.textureCells,
                     "Cell sizes (metres, comma-separated, whole multiples of the grid's cell) to block-average the "
                     "grid to and measure its texture at: roughness exponent, spectral slopes, slope percentiles, "
                     "cliffs (default: the grid's cell times 1, 2 and 8)")
        ->delimiter(',')
        ->check(CLI::Range(1e-3, 1e9));
    landforms
        ->add_option("--overhang-depth", args->scene.overhangs.depth,
                     "Overhangs: how far below the top surface each column is sampled, metres (deeper caves are "
                     "left out)")
        ->check(CLI::Range(1e-3, 1e5))
        ->capture_default_str();
    landforms
        ->add_option("--overhang-step", args->scene.overhangs.step,
                     "Overhangs: the largest step between density samples along a column, metres")
        ->check(CLI::Range(1e-3, 1e5))
        ->capture_default_str();
    landforms
        ->add_option("--threads", args->threads,
                     "Worker threads (0 = all cores); the numbers are the same for any count")
        ->check(CLI::Range(0, 1024));
    return {landforms, [args, landforms]() { return runLandforms(*args, *landforms); }};
}

} // namespace strata::app
