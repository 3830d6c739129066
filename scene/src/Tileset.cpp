// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The bake's OGC 3D Tiles 1.1 tileset. A quadtree over the tile columns
// (x, z): inner nodes have no content and group their children; each tile
// (each slab of a column) ends in a chain, one node per level of detail from
// the coarsest down to level 0, each holding that level's .glb (one
// `content` per node: 1.1's `contents` arrays are not read by every client,
// e.g. 3d-tiles-renderer 0.5), with REPLACE refinement, so a client shows one level per column and refines it
// as the camera comes closer. geometricError of a chain node is that tile's
// own measured error at that level (TileLevelRecord::error: the two-sided
// Hausdorff distance to its level 0), made non-decreasing up the chain so a
// parent's error is never below its child's (as 3D Tiles requires), 0 at
// level 0: a flat tile refines late, a rough one early, instead of every
// tile refining at the worst tile's error. An inner node's is its box's
// diagonal (a client refines it unless the whole node would be a few pixels
// across), never less than its children's.
//
// Frames: glTF content is y-up and 3D Tiles z-up; a client turns content by
// x' = x, y' = −z, z' = y, so the bounding boxes here are given in that
// turned frame. With a georeference the root's transform is east-north-up
// at that point (Georeference.h): the scene's x east, −z north, y up.

#include "BakeManifest.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>

namespace strata::scene::detail {

namespace {

using nlohmann::json;

struct Box
{
    glm::dvec3 min{std::numeric_limits<double>::max()};
    glm::dvec3 max{std::numeric_limits<double>::lowest()};
    bool empty() const { return min.x > max.x; }
    void add(const glm::dvec3& lo, const glm::dvec3& hi)
    {
        min = glm::min(min, lo);
        max = glm::max(max, hi);
    }
    void add(const Box& b)
    {
        if (!b.empty()) add(b.min, b.max);
    }
};

/// A 3D Tiles box (centre, three half axes) of a y-up box, in the z-up frame.
json boxVolume(const Box& b)
{
    const glm::dvec3 c = 0.5 * (b.min + b.max), h = 0.5 * (b.max - b.min);
    return {{"box", json::array({c.x, -c.z, c.y, h.x, 0.0, 0.0, 0.0, h.z, 0.0, 0.0, 0.0, h.y})}};
}

/// Children gathered under a node without content: null children are
/// skipped, one child stands for the group, and the group's error is its
/// box's diagonal, never less than a child's.
class Group
{
public:
    void add(json child, const Box& childBounds)
    {
        if (child.is_null()) return;
        mError = std::max(mError, child["geometricError"].get<double>());
        mBounds.add(childBounds);
        mChildren.push_back(std::move(child));
    }

    /// The group's node (or its only child, or null); adds its box to `bounds`.
    json finish(Box& bounds)
    {
        bounds.add(mBounds);
        if (mChildren.empty()) return nullptr;
        if (mChildren.size() == 1) return mChildren[0];
        return {{"boundingVolume", boxVolume(mBounds)},
                {"geometricError", std::max(glm::length(mBounds.max - mBounds.min), mError)},
                {"children", mChildren}};
    }

private:
    json mChildren = json::array();
    double mError = 0.0;
    Box mBounds;
};

class Builder
{
public:
    explicit Builder(const BakeManifest& m)
        : mManifest(m)
    {
        for (const auto& [index, tile] : m.tiles) mColumns[{tile.cell[0], tile.cell[2]}].push_back(&tile);
    }

    /// The node for columns [x0, x1) × [z0, z1), or null when nothing in it has content.
    json node(int x0, int x1, int z0, int z1, Box& bounds) const
    {
        if (x1 - x0 == 1 && z1 - z0 == 1) return column(x0, z0, bounds);
        Group group;
        const int xm = x1 - x0 > 1 ? (x0 + x1) / 2 : x1, zm = z1 - z0 > 1 ? (z0 + z1) / 2 : z1;
        for (const auto& [a0, a1] : {std::pair{x0, xm}, std::pair{xm, x1}})
            for (const auto& [b0, b1] : {std::pair{z0, zm}, std::pair{zm, z1}}) {
                if (a0 >= a1 || b0 >= b1) continue;
                Box childBounds;
                group.add(node(a0, a1, b0, b1, childBounds), childBounds);
            }
        return group.finish(bounds);
    }

private:
    /// A column of slabs: one chain per slab (several under a node without
    /// content, like the quadtree's inner nodes).
    json column(int x, int z, Box& bounds) const
    {
        const auto found = mColumns.find({x, z});
        if (found == mColumns.end()) return nullptr;
        Group group;
        for (const TileRecord* tile : found->second) {
            Box tileBounds;
            group.add(chain(*tile, tileBounds), tileBounds);
        }
        return group.finish(bounds);
    }

    /// One tile's levels from the coarsest (the chain's root) to level 0,
    /// each node holding that level's .glb (none where the level has no
    /// surface), all with the tile's bounds over every level.
    json chain(const TileRecord& tile, Box& bounds) const
    {
        for (const TileLevelRecord& level : tile.levels)
            if (level.file) bounds.add(level.min, level.max);
        if (bounds.empty()) return nullptr;
        json below = nullptr;
        double error = 0.0;
        for (int l = 0; l < mManifest.lods; ++l) {
            for (const TileLevelRecord& level : tile.levels)
                if (level.level == l && l > 0) error = std::max(error, level.error);
            json node = {{"boundingVolume", boxVolume(bounds)}, {"geometricError", error}};
            for (const TileLevelRecord& level : tile.levels)
                if (level.level == l && level.file) node["content"] = {{"uri", level.file->path}};
            if (!below.is_null()) node["children"] = json::array({below});
            below = std::move(node);
        }
        return below;
    }

    const BakeManifest& mManifest;
    std::map<std::pair<int, int>, std::vector<const TileRecord*>> mColumns;
};

} // namespace

json makeTileset(const BakeManifest& manifest)
{
    Builder builder(manifest);
    Box bounds;
    json root = builder.node(0, manifest.counts[0], 0, manifest.counts[2], bounds);
    if (root.is_null()) {
        // No tile has a surface: an empty root over the baked box.
        bounds.add(manifest.min, manifest.max);
        root = {{"boundingVolume", boxVolume(bounds)}, {"geometricError", 0.0}};
    }
    root["refine"] = "REPLACE";
    // East-north-up at the georeference: the tileset's z-up frame (x east,
    // y north, z up) placed on the WGS84 ellipsoid for globe clients.
    if (manifest.georeference) root["transform"] = eastNorthUpToEcef(*manifest.georeference);
    return {{"asset", {{"version", "1.1"}, {"generator", "Strata"}}},
            {"geometricError", root["geometricError"]},
            {"root", root}};
}

} // namespace strata::scene::detail
