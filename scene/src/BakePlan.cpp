// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Bake.h>

#include "BakeManifest.h"
#include "TileGrid.h"

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
constexpr int DEFAULT_TILE_VOXELS = 256;

[[noreturn]] void badFlag(const std::string& flag, const std::string& value, const std::string& why)
{
    throw Error(ErrorKind::BadInput, flag + " " + value + ": " + why, {"", 0, flag, value});
}

} // namespace

namespace detail {

std::string sceneHash(const Scene& scene)
{
    // The scene text and the contents of every file its terrain reads, so a
    // changed heightmap is another bake. Each file is named as the scene
    // names it (relative to the scene's folder): the same scene read through
    // another path (a cluster node that mounts the share elsewhere, another
    // working directory) is the same bake.
    std::string identity = scene.text;
    const std::filesystem::path folder = std::filesystem::path(scene.source).parent_path();
    for (const std::filesystem::path& file : scene.inputFiles) {
        const std::filesystem::path named = file.lexically_relative(folder);
        // Appended piece by piece: g++ 12 warns falsely (-Wrestrict) on "\n" + string.
        identity += '\n';
        identity += (named.empty() ? file : named).generic_string();
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
    const double tileSize = options.tileSize > 0.0 ? options.tileSize : DEFAULT_TILE_VOXELS * scene.voxelSize;
    const std::string shownSize = formatNumber(tileSize);
    const detail::TileGrid tiles = detail::planTileGrid(scene, tileSize, plan.lods);
    const std::int64_t coarse = tiles.coarse, tileVoxels = tiles.tileVoxels;
    plan.tileSize = tiles.tileSize;
    plan.minVoxel = tiles.minVoxel;
    plan.maxVoxel = tiles.maxVoxel;
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
    const std::uint64_t band =
        options.grids ? std::uint64_t(tileVoxels * tileVoxels) * std::uint64_t(2 * scene.halfWidth + 8) * 5 : 0;
    plan.tileMemoryBytes = samples + band;
    if (options.maxMemoryBytes > 0 && plan.tileMemoryBytes > options.maxMemoryBytes)
        badFlag("--tile-size", shownSize,
                "needs about " + withThousands(plan.tileMemoryBytes >> 20) + " MiB per tile, over the budget of " +
                    withThousands(options.maxMemoryBytes >> 20) + " MiB: use smaller tiles or raise --max-memory");
    return plan;
}

} // namespace strata::scene
