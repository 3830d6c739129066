// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the one tile grid of bake and export-terrain (and their --tiles
// flag): the tile size checked against the voxel and the coarsest level,
// the region's corners snapped out to the coarsest cell, the tile counts.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::scene {
struct Scene;
}

namespace strata::scene::detail {

/// The most tiles a bake or an export cuts a region into (and along one axis).
inline constexpr std::int64_t MAX_TILES = std::int64_t(1) << 24;
inline constexpr std::int64_t MAX_TILES_ALONG = std::int64_t(1) << 20;

/// The most voxels along a tile's side.
inline constexpr std::int64_t MAX_TILE_VOXELS = 1024;

/// A region cut into tiles of whole voxels.
struct TileGrid
{
    std::int64_t tileVoxels = 0;            ///< voxels along a tile's side
    double tileSize = 0.0;                  ///< tileVoxels · voxel size, metres
    std::int64_t coarse = 1;                ///< the coarsest level's cell, voxels (2^(lods − 1))
    std::array<std::int64_t, 3> minVoxel{}; ///< the region's corner snapped down to `coarse`
    std::array<std::int64_t, 3> maxVoxel{}; ///< the far corner snapped up to `coarse`
};

/// The grid of `tileSize` metres over the scene's region for `lods` levels.
/// Throws strata::Error (BadInput) naming --tile-size and the value: not a
/// positive finite number, not a whole number of voxels (within 1e-9), over
/// MAX_TILE_VOXELS, not a multiple of the coarsest cell.
TileGrid planTileGrid(const Scene& scene, double tileSize, int lods);

/// Tiles of `tileVoxels` along an extent of `extentVoxels`, multiplied into
/// `total`; throws strata::Error (BadInput) naming --tile-size (shown as
/// `shownSize`) past MAX_TILES_ALONG or MAX_TILES in all.
int tilesAlong(std::int64_t extentVoxels, std::int64_t tileVoxels, std::int64_t& total, const std::string& shownSize);

/// Parses "all" or comma-separated indices and ranges "A-B" into ascending
/// indices below `count`, without repeats. Throws strata::Error (BadInput)
/// naming --tiles, the text and the count.
std::vector<int> parseTileSelection(const std::string& text, int count);

} // namespace strata::scene::detail
