// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The `erode_detail` node: voxel-scale erosion (droplets and talus,
/// DetailErosion.h) laid over a height node, tile-parallel and the same
/// bits for any tiling.
///
/// The world's cells are cut into fixed blocks (`block` cells a side,
/// aligned to the world's origin). Each block is eroded as a patch that
/// reaches `halo` cells beyond it, so droplets that start outside the block
/// and run into it are simulated; the change a block computes is kept as a
/// displacement and blended with its neighbours' over the halo (weights
/// that fall smoothly to 0 before the patch's edge), so the result is
/// continuous across block borders. A block depends only on its index, the
/// input node and the options, never on which tile, thread or worker asks
/// for it: any crop of the world sees the same heights. Blocks are computed
/// on demand and kept in a bounded cache.

#include <strata/terrain/DetailErosion.h>
#include <strata/terrain/HeightGraph.h>

#include <cstdint>
#include <memory>

namespace strata::terrain {

struct DetailErodeOptions
{
    DetailErosionOptions erosion; ///< cellSize: the patches' spacing (1 m: voxel-scale detail)
    int blockCells = 64;          ///< cells per block side, 8..1024
    /// Cells the patch reaches beyond its block, 1..blockCells/2; default
    /// (0): erosion.dropletSteps up to blockCells/2, so no droplet that can
    /// reach the block is left out unless it travels over half a block.
    int halo = 0;
};

class DetailErodedHeightfield final : public HeightfieldBase
{
public:
    /// Throws strata::Error naming the option (block, halo, droplets_per_cell...).
    DetailErodedHeightfield(HeightNodePtr child, std::uint64_t seed, const DetailErodeOptions& options);
    ~DetailErodedHeightfield() override;

    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    /// The child's bounds widened by maxDepth.
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;

    /// Blocks computed so far by this node (a diagnostic of its cache).
    std::size_t blocksComputed() const;

private:
    struct Block;
    class Cache;
    std::shared_ptr<const Block> block(std::int64_t bx, std::int64_t bz) const;
    std::shared_ptr<const Block> computeBlock(std::int64_t bx, std::int64_t bz) const;
    double displacement(const Block& block, double u, double v) const;

    HeightNodePtr mChild;
    std::uint64_t mSeed;
    DetailErodeOptions mOptions;
    std::unique_ptr<Cache> mCache;
};

} // namespace strata::terrain
