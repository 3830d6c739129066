// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench landforms [SCENE.toml] [--dem FILE]`: how much a terrain's
// top surface looks like real land. The scene is loaded (its node tree built,
// which is when an `erode` node evolves: the "global pass"), its top surface
// sampled (terrain::sampleTopSurface), measured (terrain::measureLandforms,
// its texture at several cell sizes with terrain::measureSurfaceTextureAtCells,
// its overhangs with terrain::measureOverhangs) and checked against the
// project's goals (terrain/LandformGoals.h); or a digital elevation model is
// read (terrain::readElevationFile) and measured the same way (no overhangs: a
// DEM has no volume). This file parses flags and prints;
// docs/landform-statistics.md says what the numbers mean.

#include "Commands.h"
#include "Progress.h"

#include <strata/scene/Scene.h>
#include <strata/scene/Snapshot.h>

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/ElevationFile.h>
#include <strata/terrain/LandformGoals.h>
#include <strata/terrain/LandformStatistics.h>
#include <strata/terrain/OverhangFraction.h>
#include <strata/terrain/SurfaceTexture.h>
#include <strata/terrain/TopSurface.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

namespace strata::app {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

struct LandformArguments
{
    std::string scenePath;
    double cell = 4.0;                ///< metres
    std::string regionMin, regionMax; ///< "X,Z"
    std::string dem;
    std::optional<double> demCell;
    std::vector<double> textureCells; ///< metres; empty: the grid's cell times 1, 2 and 8
    double overhangDepth = terrain::OverhangOptions{}.depth; ///< metres
    double overhangStep = terrain::OverhangOptions{}.step;   ///< metres
    int threads = 0;
};

std::string range(double lo, double hi)
{
    return formatNumber(lo) + ".." + formatNumber(hi);
}

/// The cell sizes the texture is measured at: --texture-cells, or the grid's
/// cell times 1, 2 and 8. Throws strata::Error (BadInput, naming the flag)
/// for one that is not a whole multiple of the grid's cell.
std::vector<double> textureCells(const LandformArguments& args, double gridCell)
{
    const std::vector<double> cells =
        args.textureCells.empty() ? std::vector<double>{gridCell, 2.0 * gridCell, 8.0 * gridCell} : args.textureCells;
    for (const double cell : cells) {
        try {
            terrain::blockFactor(gridCell, cell);
        } catch (const Error& e) {
            throw Error(e.kind(), std::string("--texture-cells: ") + e.what(),
                        ErrorPlace{"", 0, "--texture-cells", formatNumber(cell)});
        }
    }
    return cells;
}

/// Measures `heights` and prints the statistics, the texture at `cells`, the
/// overhangs (n/a without) and the goals table; the stages are named
/// `stage` and `textureStage` (padded to line up with the stages before).
void measureAndPrint(const std::vector<double>& heights, int width, int height, double cellSize,
                     const std::vector<double>& cells, const std::optional<terrain::OverhangStatistics>& overhangs,
                     const std::string& stage, const std::string& textureStage, TerminalProgress& progress)
{
    progress.beginStage(stage);
    auto start = Clock::now();
    const terrain::LandformStatistics stats = terrain::measureLandforms(heights, width, height, cellSize);
    progress.endStage(stage, secondsSince(start), "");
    progress.beginStage(textureStage);
    start = Clock::now();
    const std::vector<terrain::SurfaceTexture> texture =
        terrain::measureSurfaceTextureAtCells(heights, width, height, cellSize, cells);
    progress.endStage(textureStage, secondsSince(start), "roughness, spectrum and slopes at " +
                                                             std::to_string(cells.size()) + " cell sizes");
    std::cout << '\n' << terrain::formatLandformStatistics(stats) << terrain::formatSurfaceTexture(texture);
    if (overhangs) {
        std::cout << terrain::formatOverhangs(*overhangs);
    } else {
        std::cout << "overhangs               n/a (a DEM is a height grid: it has no volume)\n";
    }
    std::cout << '\n' << terrain::formatLandformGoals(terrain::checkLandformGoals(stats)) << std::flush;
}

int runDem(const LandformArguments& args, const std::string& threads, TerminalProgress& progress)
{
    std::cout << "strata bench landforms: DEM " << args.dem << " (" << threads << ")" << std::endl;
    progress.beginStage("read");
    const auto start = Clock::now();
    const terrain::ElevationGrid dem = terrain::readElevationFile(args.dem);
    const double cellSize = args.demCell.value_or(dem.cellSize);
    const std::string what = dem.format + (dem.member.empty() ? "" : " member " + dem.member) + ", " +
                             std::to_string(dem.width) + " x " + std::to_string(dem.height) + " cells";
    if (cellSize <= 0.0) {
        throw Error(ErrorKind::BadInput,
                    args.dem + " (" + what +
                        ") holds no cell size: give --dem-cell METRES, the ground distance "
                        "between neighbouring cells (a 3 arc-second DEM: about 92 m north-south, "
                        "less east-west away from the equator)",
                    ErrorPlace{args.dem, 0, "--dem-cell", ""});
    }
    if (dem.noDataCells > 0) {
        throw Error(ErrorKind::BadInput,
                    args.dem + " has " + withThousands(dem.noDataCells) + " of " + withThousands(dem.heights.size()) +
                        " cells without data (NODATA or not finite): landform statistics "
                        "need a complete grid; crop the DEM to its complete part",
                    ErrorPlace{args.dem, 0, "--dem", ""});
    }
    progress.endStage("read", secondsSince(start),
                      what + " of " + formatNumber(cellSize) + " m" + (args.demCell ? " (--dem-cell)" : ""));
    if (!args.demCell && cellSize < 0.01) {
        std::cout << "  note: a cell size under 1 cm looks like degrees (a geographic grid): give --dem-cell METRES"
                  << std::endl;
    }
    const std::vector<double> cells = textureCells(args, cellSize);
    measureAndPrint(dem.heights, dem.width, dem.height, cellSize, cells, std::nullopt, "statistics", "texture   ",
                    progress);
    return 0;
}

int runScene(const LandformArguments& args, const std::string& threads, TerminalProgress& progress)
{
    // Bad flags are refused before the (possibly long) global pass.
    std::optional<glm::dvec2> cropMin, cropMax;
    if (!args.regionMin.empty()) cropMin = parseVec2Flag("--region-min", args.regionMin);
    if (!args.regionMax.empty()) cropMax = parseVec2Flag("--region-max", args.regionMax);
    const std::vector<double> cells = textureCells(args, args.cell);
    terrain::OverhangOptions overhangOptions;
    overhangOptions.depth = args.overhangDepth;
    overhangOptions.step = args.overhangStep;
    if (overhangOptions.step > overhangOptions.depth) {
        throw Error(ErrorKind::BadInput, "--overhang-step = " + formatNumber(overhangOptions.step) +
                    " m must be at most --overhang-depth = " + formatNumber(overhangOptions.depth) + " m",
                    ErrorPlace{"", 0, "--overhang-step", formatNumber(overhangOptions.step)});
    }

    const std::string source = args.scenePath.empty() ? std::string("<default scene>") : args.scenePath;
    std::cout << "strata bench landforms: " << source << " (" << threads << ")" << std::endl;
    // Loading builds the node tree: an erode node evolves its whole domain here.
    progress.beginStage("global pass");
    auto start = Clock::now();
    const Scene scene = args.scenePath.empty() ? defaultScene() : loadScene(args.scenePath);
    progress.endStage("global pass", secondsSince(start), "scene loaded, node tree built (erode nodes evolve here)");

    terrain::WorldBox region{scene.region.min, scene.region.max};
    if (cropMin) {
        region.min.x = cropMin->x;
        region.min.z = cropMin->y;
    }
    if (cropMax) {
        region.max.x = cropMax->x;
        region.max.z = cropMax->y;
    }
    if (!(region.min.x < region.max.x) || !(region.min.z < region.max.z)) {
        throw Error(ErrorKind::BadInput, "the region's x,z corners must satisfy min < max on both axes (x " +
                    range(region.min.x, region.max.x) + ", z " + range(region.min.z, region.max.z) +
                    "): check --region-min and --region-max");
    }

    progress.beginStage("top surface");
    start = Clock::now();
    const terrain::TopSurfaceGrid top = terrain::sampleTopSurface(
        *scene.field, region, args.cell, [&progress](double fraction) { return progress.progress(fraction); });
    progress.endStage("top surface", secondsSince(start),
                      std::to_string(top.width) + " x " + std::to_string(top.height) + " columns of " +
                          formatNumber(args.cell) + " m over x " + range(region.min.x, region.max.x) + ", z " +
                          range(region.min.z, region.max.z) + " m (y " + range(region.min.y, region.max.y) + " m)");
    if (top.columnsAtTop > 0) {
        std::cout << "  note: " << withThousands(top.columnsAtTop)
                  << " columns have rock at the region's top (y = " << formatNumber(region.max.y)
                  << " m): the surface there is clipped; raise region.max.y" << std::endl;
    }
    if (top.columnsAtBottom > 0) {
        std::cout << "  note: " << withThousands(top.columnsAtBottom)
                  << " columns have no rock in the region (given y = " << formatNumber(region.min.y) << " m)"
                  << std::endl;
    }
    progress.beginStage("overhangs  ");
    start = Clock::now();
    const terrain::OverhangStatistics overhangs = terrain::measureOverhangs(
        *scene.field, top, overhangOptions, [&progress](double fraction) { return progress.progress(fraction); });
    progress.endStage("overhangs  ", secondsSince(start),
                      withThousands(overhangs.columns) + " columns, " + withThousands(overhangs.samplesPerColumn) +
                          " density samples each");
    // Stage names as wide as "top surface".
    measureAndPrint(top.heights, top.width, top.height, top.cellSize, cells, overhangs, "statistics ", "texture    ",
                    progress);
    return 0;
}

int runLandforms(const LandformArguments& args, const CLI::App& command)
{
    if (!args.dem.empty()) {
        if (!args.scenePath.empty() || !args.regionMin.empty() || !args.regionMax.empty() ||
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
    std::unique_ptr<tbb::global_control> threadLimit;
    if (args.threads > 0) {
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            std::size_t(args.threads));
    }
    const int count = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    const std::string threads = std::to_string(count) + (count == 1 ? " thread" : " threads");
    TerminalProgress progress(std::cout, stdoutIsTerminal(), false);
    return args.dem.empty() ? runScene(args, threads, progress) : runDem(args, threads, progress);
}

} // namespace

Command registerBenchLandformsCommand(CLI::App& bench)
{
    auto args = std::make_shared<LandformArguments>();
    CLI::App* landforms = bench.add_subcommand(
        "landforms", "How much a scene's top surface (or a DEM file) looks like real land: closed depressions, "
                     "flats, Hack's law, slope-area concavity, against the project's goals; surface texture "
                     "(roughness, spectral slopes, slope angles, cliffs) at several cell sizes; overhangs");
    landforms->add_option("scene", args->scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    landforms->add_option("--cell", args->cell, "Distance between the top surface's columns, metres")
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
        ->add_option("--texture-cells", args->textureCells,
                     "Cell sizes (metres, comma-separated, whole multiples of the grid's cell) to block-average the "
                     "grid to and measure its texture at: roughness exponent, spectral slopes, slope percentiles, "
                     "cliffs (default: the grid's cell times 1, 2 and 8)")
        ->delimiter(',')
        ->check(CLI::Range(1e-3, 1e9));
    landforms
        ->add_option("--overhang-depth", args->overhangDepth,
                     "Overhangs: how far below the top surface each column is sampled, metres (deeper caves are "
                     "left out)")
        ->check(CLI::Range(1e-3, 1e5))
        ->capture_default_str();
    landforms
        ->add_option("--overhang-step", args->overhangStep,
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
