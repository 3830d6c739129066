// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the tile grid and the --tiles flag of bake and export-terrain.

#include <cstdint>
#include <string>
#include <vector>

namespace strata::scene::detail {

/// The most tiles a bake or an export cuts a region into (and along one axis).
inline constexpr std::int64_t MAX_TILES = std::int64_t(1) << 24;
inline constexpr std::int64_t MAX_TILES_ALONG = std::int64_t(1) << 20;

/// Tiles of `tileVoxels` along an extent of `extentVoxels`, multiplied into
/// `total`; throws strata::Error (BadInput) naming --tile-size (shown as
/// `shownSize`) past MAX_TILES_ALONG or MAX_TILES in all.
int tilesAlong(std::int64_t extentVoxels, std::int64_t tileVoxels, std::int64_t& total, const std::string& shownSize);

/// Parses "all" or comma-separated indices and ranges "A-B" into ascending
/// indices below `count`, without repeats. Throws strata::Error (BadInput)
/// naming --tiles, the text and the count.
std::vector<int> parseTileSelection(const std::string& text, int count);

} // namespace strata::scene::detail
