// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Bake.h>

#include "BakeManifest.h"
#include "TileSelection.h"

#include <strata/Error.h>
#include <strata/IntegerMath.h>
#include <strata/Format.h>
#include <strata/Sha256.h>

#include <algorithm>
#include <charconv>
#include <cmath>

namespace strata::scene {

namespace {

constexpr int MAX_LODS = 8;
constexpr std::int64_t MAX_TILE_VOXELS = 1024;
constexpr int DEFAULT_TILE_VOXELS = 256;

[[noreturn]] void badFlag(const std::string& flag, const std::string& value, const std::string& why)
{
    throw Error(ErrorKind::BadInput, flag + " " + value + ": " + why, {"", 0, flag, value});
}



} // namespace

namespace detail {

/// Parses "all" or comma-separated indices and ranges "A-B" into ascending
/// indices below `count`, without repeats.
int tilesAlong(std::int64_t extentVoxels, std::int64_t tileVoxels, std::int64_t& total, const std::string& shownSize)
{
    const std::int64_t n = (extentVoxels + tileVoxels - 1) / tileVoxels;
    if (n > MAX_TILES_ALONG || total * n > MAX_TILES)
        badFlag("--tile-size", shownSize, "cuts the region into more than " + std::to_string(MAX_TILES) + " tiles");
    total *= n;
    return int(n);
}

std::vector<int> parseTileSelection(const std::string& text, int count)
{
    std::vector<int> out;
    if (text == "all") {
        for (int i = 0; i < count; ++i) out.push_back(i);
        return out;
    }
    const auto number = [&](std::string_view part) {
        long long value = -1;
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (ec != std::errc() || end != part.data() + part.size() || part.empty())
            badFlag("--tiles", text, "expected all, an index I, a range A-B, or a comma-separated list of them");
        if (value < 0 || value >= count)
            badFlag("--tiles", text,
                    "tile " + std::to_string(value) + " is out of range: the world has " + std::to_string(count) +
                        " tiles (0 to " + std::to_string(count - 1) + ")");
        return int(value);
    };
    std::string_view rest(text);
    while (true) {
        const std::size_t comma = rest.find(',');
        const std::string_view part = rest.substr(0, comma);
        const std::size_t dash = part.find('-');
        const int first = number(dash == std::string_view::npos ? part : part.substr(0, dash));
        const int last = dash == std::string_view::npos ? first : number(part.substr(dash + 1));
        if (last < first) badFlag("--tiles", text, "the range " + std::string(part) + " ends before it starts");
        for (int i = first; i <= last; ++i) out.push_back(i);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

} // namespace detail

namespace detail {

std::string sceneHash(const Scene& scene)
{
    // The scene text and the contents of every file its terrain reads, so a
    // changed heightmap is another bake.
    std::string identity = scene.text;
    for (const std::filesystem::path& file : scene.inputFiles) {
        // Appended piece by piece: g++ 12 warns falsely (-Wrestrict) on "\n" + string.
        identity += '\n';
        identity += file.string();
        identity += ' ';
        identity += sha256File(file);
    }
    return sha256Hex(identity);
}

} // namespace detail

BakeTile BakePlan::tile(int index) const
{
    BakeTile t;
    t.index = index;
    t.cell = {index % counts[0], index / (counts[0] * counts[2]), (index / counts[0]) % counts[2]};
    const auto tileVoxels = roundToInt<std::int64_t>(tileSize / voxelSize);
    for (int a = 0; a < 3; ++a) {
        t.box.min[a] = minVoxel[a] + t.cell[a] * tileVoxels;
        t.box.size[a] = std::min(tileVoxels, maxVoxel[a] - t.box.min[a]);
    }
    t.box.neighbourFaces = 0;
    for (int a = 0; a < 3; ++a) {
        if (t.cell[a] > 0) t.box.neighbourFaces |= 1u << (2 * a);
        if (t.cell[a] + 1 < counts[a]) t.box.neighbourFaces |= 1u << (2 * a + 1);
    }
    t.name = std::to_string(t.cell[0]) + "_" + (counts[1] > 1 ? std::to_string(t.cell[1]) + "_" : std::string()) +
             std::to_string(t.cell[2]);
    return t;
}

BakePlan planBake(const Scene& scene, const BakeOptions& options)
{
    BakePlan plan;
    plan.voxelSize = scene.voxelSize;
    plan.seed = options.seed.value_or(scene.terrain.seed);
    plan.sceneHash = detail::sceneHash(scene);
    if (options.lods < 1 || options.lods > MAX_LODS)
        badFlag("--lods", std::to_string(options.lods), "must be in [1, " + std::to_string(MAX_LODS) + "]");
    plan.lods = options.lods;
    const std::int64_t coarse = std::int64_t(1) << (plan.lods - 1);

    const double tileSize = options.tileSize > 0.0 ? options.tileSize : DEFAULT_TILE_VOXELS * scene.voxelSize;
    const std::string shownSize = formatNumber(tileSize);
    if (!std::isfinite(tileSize) || tileSize <= 0.0) badFlag("--tile-size", shownSize, "must be a positive number of metres");
    const double voxels = tileSize / scene.voxelSize;
    const auto tileVoxels = roundToInt<std::int64_t>(voxels);
    if (tileVoxels < 1 || std::abs(voxels - double(tileVoxels)) > 1e-9 * std::max(1.0, voxels))
        badFlag("--tile-size", shownSize,
                "is not a multiple of the voxel size " + formatNumber(scene.voxelSize) + " m");
    if (tileVoxels % coarse != 0)
        badFlag("--tile-size", shownSize,
                "is not a multiple of the coarsest cell, " + formatNumber(double(coarse) * scene.voxelSize) + " m (" +
                    std::to_string(coarse) + " voxels at --lods " + std::to_string(plan.lods) + ")");
    if (tileVoxels > MAX_TILE_VOXELS)
        badFlag("--tile-size", shownSize,
                "holds " + std::to_string(tileVoxels) + " voxels; at most " + std::to_string(MAX_TILE_VOXELS) +
                    " per tile (" + formatNumber(double(MAX_TILE_VOXELS) * scene.voxelSize) + " m)");
    plan.tileSize = double(tileVoxels) * scene.voxelSize;

    for (int a = 0; a < 3; ++a) {
        const double lo = scene.region.min[a] / scene.voxelSize, hi = scene.region.max[a] / scene.voxelSize;
        plan.minVoxel[a] = floorDiv(floorToInt<std::int64_t>(lo), coarse) * coarse;
        plan.maxVoxel[a] = -floorDiv(-ceilToInt<std::int64_t>(hi), coarse) * coarse;
    }
    for (int a : {0, 2}) {
        const std::int64_t extent = plan.maxVoxel[a] - plan.minVoxel[a];
        if (extent < tileVoxels)
            badFlag("--tile-size", shownSize,
                    std::string("the region is ") + formatNumber(double(extent) * scene.voxelSize) + " m along " +
                        (a == 0 ? "x" : "z") + ", smaller than one tile: use a tile size of at most " +
                        formatNumber(double(extent - extent % coarse) * scene.voxelSize) + " m");
    }
    std::int64_t total = 1;
    for (int a = 0; a < 3; ++a) plan.counts[a] = detail::tilesAlong(plan.maxVoxel[a] - plan.minVoxel[a], tileVoxels, total, shownSize);
    plan.skirtDepth = options.skirtDepth > 0.0 ? options.skirtDepth : 2.0 * double(coarse) * scene.voxelSize;
    plan.tileFormat = options.tileFormat;
    plan.selected = detail::parseTileSelection(options.tiles, plan.tileCount());
    // A georeferenced DEM places the scene unless the flag says otherwise.
    if (options.georeference == "none") plan.georeference.reset();
    else if (!options.georeference.empty()) plan.georeference = parseGeoreference(options.georeference);
    else plan.georeference = scene.georeference;

    // Per tile: the level-0 sample array (the largest), and the grid's
    // narrow band estimated as a sheet through the tile (4 bytes a voxel,
    // 2·halfWidth voxels thick, with OpenVDB's leaf overhead).
    world::TileBox full;
    full.size = {tileVoxels, std::min(tileVoxels, plan.maxVoxel[1] - plan.minVoxel[1]), tileVoxels};
    const std::uint64_t samples = world::tileSampleBytes(full, 0);
    const std::uint64_t grid =
        options.grids ? std::uint64_t(tileVoxels * tileVoxels) * std::uint64_t(2 * scene.halfWidth + 8) * 5 : 0;
    plan.tileMemoryBytes = samples + grid;
    if (options.maxMemoryBytes > 0 && plan.tileMemoryBytes > options.maxMemoryBytes)
        badFlag("--tile-size", shownSize,
                "needs about " + withThousands(plan.tileMemoryBytes >> 20) + " MiB per tile, over the budget of " +
                    withThousands(options.maxMemoryBytes >> 20) + " MiB: use smaller tiles or raise --max-memory");
    return plan;
}

} // namespace strata::scene
