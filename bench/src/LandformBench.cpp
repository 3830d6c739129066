// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/LandformBench.h>

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/scene/Scene.h>
#include <strata/terrain/ElevationFile.h>
#include <strata/terrain/LandformGoals.h>
#include <strata/terrain/TopSurface.h>

#include <chrono>

namespace strata::bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

std::string range(double lo, double hi) { return formatNumber(lo) + ".." + formatNumber(hi); }

/// Measures `heights` (statistics, then the texture at `cells`) as the
/// stages `stage` and `textureStage` (padded to line up with the stages
/// before).
LandformBenchResult measureHeights(const std::vector<double>& heights, int width, int height, double cellSize,
                                   const std::vector<double>& cells, const std::string& stage,
                                   const std::string& textureStage, scene::PipelineObserver& stages)
{
    LandformBenchResult result;
    stages.beginStage(stage);
    auto start = Clock::now();
    result.statistics = terrain::measureLandforms(heights, width, height, cellSize);
    stages.endStage(stage, secondsSince(start), "");
    stages.beginStage(textureStage);
    start = Clock::now();
    result.texture = terrain::measureSurfaceTextureAtCells(heights, width, height, cellSize, cells);
    stages.endStage(textureStage, secondsSince(start),
                    "roughness, spectrum and slopes at " + std::to_string(cells.size()) + " cell sizes");
    return result;
}

/// The scene's region cropped to the options' x,z corners.
terrain::WorldBox cropRegion(const scene::Scene& scene, const LandformSceneOptions& options)
{
    terrain::WorldBox region{scene.region.min, scene.region.max};
    if (options.cropMin) {
        region.min.x = options.cropMin->x;
        region.min.z = options.cropMin->y;
    }
    if (options.cropMax) {
        region.max.x = options.cropMax->x;
        region.max.z = options.cropMax->y;
    }
    if (!(region.min.x < region.max.x) || !(region.min.z < region.max.z)) {
        throw Error(ErrorKind::BadInput, "the region's x,z corners must satisfy min < max on both axes (x " +
                    range(region.min.x, region.max.x) + ", z " + range(region.min.z, region.max.z) +
                    "): check --region-min and --region-max");
    }
    return region;
}

void noteClipped(const terrain::TopSurfaceGrid& top, const terrain::WorldBox& region, const LandformNote& note)
{
    if (!note) return;
    if (top.columnsAtTop > 0) {
        note(withThousands(top.columnsAtTop) + " columns have rock at the region's top (y = " +
             formatNumber(region.max.y) + " m): the surface there is clipped; raise region.max.y");
    }
    if (top.columnsAtBottom > 0) {
        note(withThousands(top.columnsAtBottom) + " columns have no rock in the region (given y = " +
             formatNumber(region.min.y) + " m)");
    }
}

} // namespace

std::vector<double> landformTextureCells(const std::vector<double>& requested, double gridCell)
{
    const std::vector<double> cells =
        requested.empty() ? std::vector<double>{gridCell, 2.0 * gridCell, 8.0 * gridCell} : requested;
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

void checkLandformSceneOptions(const LandformSceneOptions& options)
{
    landformTextureCells(options.textureCells, options.cell);
    const terrain::OverhangOptions& overhangs = options.overhangs;
    if (overhangs.step > overhangs.depth) {
        throw Error(ErrorKind::BadInput, "--overhang-step = " + formatNumber(overhangs.step) +
                    " m must be at most --overhang-depth = " + formatNumber(overhangs.depth) + " m",
                    ErrorPlace{"", 0, "--overhang-step", formatNumber(overhangs.step)});
    }
}

LandformBenchResult measureSceneLandforms(const LandformSceneOptions& options, scene::PipelineObserver& stages,
                                          const LandformNote& note)
{
    checkLandformSceneOptions(options);
    const std::vector<double> cells = landformTextureCells(options.textureCells, options.cell);
    // Loading builds the node tree: an erode node evolves its whole domain here.
    stages.beginStage("global pass");
    auto start = Clock::now();
    const scene::Scene scene = options.scenePath.empty() ? scene::defaultScene() : scene::loadScene(options.scenePath);
    stages.endStage("global pass", secondsSince(start), "scene loaded, node tree built (erode nodes evolve here)");
    const terrain::WorldBox region = cropRegion(scene, options);

    stages.beginStage("top surface");
    start = Clock::now();
    const auto progress = [&stages](double fraction) { return stages.progress(fraction); };
    const terrain::TopSurfaceGrid top = terrain::sampleTopSurface(*scene.field, region, options.cell, progress);
    stages.endStage("top surface", secondsSince(start),
                    std::to_string(top.width) + " x " + std::to_string(top.height) + " columns of " +
                        formatNumber(options.cell) + " m over x " + range(region.min.x, region.max.x) + ", z " +
                        range(region.min.z, region.max.z) + " m (y " + range(region.min.y, region.max.y) + " m)");
    noteClipped(top, region, note);
    stages.beginStage("overhangs  ");
    start = Clock::now();
    const terrain::OverhangStatistics overhangs =
        terrain::measureOverhangs(*scene.field, top, options.overhangs, progress);
    stages.endStage("overhangs  ", secondsSince(start),
                    withThousands(overhangs.columns) + " columns, " + withThousands(overhangs.samplesPerColumn) +
                        " density samples each");
    // Stage names as wide as "top surface".
    LandformBenchResult result =
        measureHeights(top.heights, top.width, top.height, top.cellSize, cells, "statistics ", "texture    ", stages);
    result.overhangs = overhangs;
    return result;
}

LandformBenchResult measureDemLandforms(const LandformDemOptions& options, scene::PipelineObserver& stages,
                                        const LandformNote& note)
{
    stages.beginStage("read");
    const auto start = Clock::now();
    const terrain::ElevationGrid dem = terrain::readElevationFile(options.path);
    const double cellSize = options.cell.value_or(dem.cellSize);
    const std::string what = dem.format + (dem.member.empty() ? "" : " member " + dem.member) + ", " +
                             std::to_string(dem.width) + " x " + std::to_string(dem.height) + " cells";
    if (cellSize <= 0.0) {
        throw Error(ErrorKind::BadInput,
                    options.path + " (" + what +
                        ") holds no cell size: give --dem-cell METRES, the ground distance "
                        "between neighbouring cells (a 3 arc-second DEM: about 92 m north-south, "
                        "less east-west away from the equator)",
                    ErrorPlace{options.path, 0, "--dem-cell", ""});
    }
    if (dem.noDataCells > 0) {
        throw Error(ErrorKind::BadInput,
                    options.path + " has " + withThousands(dem.noDataCells) + " of " +
                        withThousands(dem.heights.size()) +
                        " cells without data (NODATA or not finite): landform statistics "
                        "need a complete grid; crop the DEM to its complete part",
                    ErrorPlace{options.path, 0, "--dem", ""});
    }
    stages.endStage("read", secondsSince(start),
                    what + " of " + formatNumber(cellSize) + " m" + (options.cell ? " (--dem-cell)" : ""));
    if (!options.cell && cellSize < 0.01 && note) {
        note("a cell size under 1 cm looks like degrees (a geographic grid): give --dem-cell METRES");
    }
    const std::vector<double> cells = landformTextureCells(options.textureCells, cellSize);
    return measureHeights(dem.heights, dem.width, dem.height, cellSize, cells, "statistics", "texture   ", stages);
}

std::string formatLandformBench(const LandformBenchResult& result)
{
    std::string text = '\n' + terrain::formatLandformStatistics(result.statistics) +
                       terrain::formatSurfaceTexture(result.texture);
    text += result.overhangs ? terrain::formatOverhangs(*result.overhangs)
                             : std::string("overhangs               n/a (a DEM is a height grid: it has no volume)\n");
    return text + '\n' + terrain::formatLandformGoals(terrain::checkLandformGoals(result.statistics));
}

} // namespace strata::bench
