// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "TileGrid.h"

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/IntegerMath.h>
#include <strata/scene/Scene.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>

namespace strata::scene::detail {

namespace {

[[noreturn]] void badFlag(const std::string& flag, const std::string& value, const std::string& why)
{
    throw Error(ErrorKind::BadInput, flag + " " + value + ": " + why, {"", 0, flag, value});
}

} // namespace

TileGrid planTileGrid(const Scene& scene, double tileSize, int lods)
{
    TileGrid grid;
    const double v = scene.voxelSize;
    const std::string shownSize = formatNumber(tileSize);
    if (!std::isfinite(tileSize) || tileSize <= 0.0) badFlag("--tile-size", shownSize, "must be a positive number of metres");
    const double voxels = tileSize / v;
    grid.tileVoxels = roundToInt<std::int64_t>(voxels);
    if (grid.tileVoxels < 1 || std::abs(voxels - double(grid.tileVoxels)) > 1e-9 * std::max(1.0, voxels))
        badFlag("--tile-size", shownSize, "is not a multiple of the voxel size " + formatNumber(v) + " m");
    grid.coarse = std::int64_t(1) << (lods - 1);
    if (grid.tileVoxels % grid.coarse != 0)
        badFlag("--tile-size", shownSize,
                "is not a multiple of the coarsest cell, " + formatNumber(double(grid.coarse) * v) + " m (" +
                    std::to_string(grid.coarse) + " voxels at --lods " + std::to_string(lods) + ")");
    if (grid.tileVoxels > MAX_TILE_VOXELS)
        badFlag("--tile-size", shownSize,
                "holds " + std::to_string(grid.tileVoxels) + " voxels; at most " + std::to_string(MAX_TILE_VOXELS) +
                    " per tile (" + formatNumber(double(MAX_TILE_VOXELS) * v) + " m)");
    grid.tileSize = double(grid.tileVoxels) * v;
    for (int a = 0; a < 3; ++a) {
        const std::int64_t lo = floorToInt<std::int64_t>(scene.region.min[a] / v);
        const std::int64_t hi = ceilToInt<std::int64_t>(scene.region.max[a] / v);
        grid.minVoxel[a] = floorDiv(lo, grid.coarse) * grid.coarse;
        grid.maxVoxel[a] = -floorDiv(-hi, grid.coarse) * grid.coarse;
    }
    return grid;
}

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

} // namespace strata::scene::detail
