// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The `talus` node: scree cones and aprons at the foot of steep faces, at
/// the angle of repose, over a height node.
///
/// On a lattice of `cell_size`, for every node y:
///   L(y) = the lowest ground within a square around y (the foot of its face),
///   S(y) = L + min(fill · (H − L), max_height)   (how high debris shed from
///          y piles: a fraction of the face above the foot, at most max_height),
///   C(x) = max over y of S(y) − tan(angle) · |x − y|   (cones from every S),
/// and the talus lies where C is above the ground: the surface is max(H, C),
/// its thickness the talus mask. C is an exact dilation by a cone with an
/// octagonal footprint (four 1D passes, along x, z and both diagonals, whose
/// slopes are set so that no direction is steeper than `angle`): the talus
/// is never steeper than its angle of repose. Each pass reaches only as far
/// as a cone of max_height can (R = max_height / slope), and the square of
/// L is wide enough (3R) that a cone cut off there is already under the
/// ground: nothing is lost by the cut, so every lattice node is a pure
/// function of the heights within 6R of it. The world is cut into fixed
/// blocks, each computed from a window 6R wider on every side: any block
/// size, tiling, thread count or worker gives the same bits.
///
/// Between lattice nodes the surface is the child's own height where no
/// talus is near, the bilinear talus surface where it is thicker than one
/// cell, and a blend between (so the child's detail is kept off the talus
/// and the field stays continuous).

#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/LandformMasks.h>

#include <cstdint>
#include <memory>

namespace strata::terrain {

struct TalusOptions
{
    double angle = 34.0;     ///< degrees, 5..60: the angle of repose
    double fill = 0.4;       ///< 0..1: fraction of a face's height (above its foot) its talus may bury
    double maxHeight = 30.0; ///< metres, > 0: the tallest cone above the foot of its face
    double cellSize = 2.0;   ///< metres, > 0: the lattice the cones are computed on
    int blockCells = 256;    ///< 16..1024: lattice cells per block side (a block computes a window
                             ///< 12·reach() wider: larger blocks waste less)
};

/// The talus surface over `child`. As a landform mask source, it gives the
/// child's masks (when the child has them) with the talus thickness added
/// to the deposition (z), or, over a child without masks, only that.
class TalusHeightfield final : public HeightfieldBase, public LandformMasks
{
public:
    /// Throws strata::Error naming the option (angle, fill, max_height,
    /// cell_size, block) when one is out of range or the window of a block
    /// would be too large (max_height / cell_size too large).
    TalusHeightfield(HeightNodePtr child, const TalusOptions& options);
    ~TalusHeightfield() override;

    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    /// The child's bounds, raised by max_height (the cones never rise more
    /// than that above the ground of their face's foot).
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;
    void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override;

    /// Talus thickness (metres, >= 0) at n columns.
    void thickness(const double* x, const double* z, std::size_t n, double* out) const;
    /// The lattice's fields at n columns, bilinear between nodes: the
    /// ground H, the cones C and the foot L (metres). Beyond ±2^62 cells
    /// (or at NaN) −inf, −inf and +inf. The `scree` node lays the talus
    /// over 3D rock with them.
    void lattice(const double* x, const double* z, std::size_t n, double* ground, double* cone, double* foot) const;
    /// Ranges of the cones C and the foot L over the rectangle [min, max]
    /// (world x, z): the extremes of the lattice nodes around it, which hold
    /// every bilinear value inside. False (and nothing set) beyond the
    /// lattice or over more than 65,536 nodes.
    struct LatticeRange
    {
        double coneLo = 0.0, coneHi = 0.0, footLo = 0.0, footHi = 0.0;
    };
    bool latticeRange(const glm::dvec2& min, const glm::dvec2& max, LatticeRange& out) const;
    const TalusOptions& options() const { return mOptions; }
    /// Lattice steps a cone pass reaches (R above); a block's window is
    /// block + 12R + 1 nodes a side.
    int reach() const { return mReach; }
    /// Blocks computed so far (a diagnostic of its cache).
    std::size_t blocksComputed() const;

private:
    struct Block;
    class Cache;
    struct Corners;
    bool corners(double x, double z, Corners& out) const;
    std::shared_ptr<const Block> block(std::int64_t bx, std::int64_t bz) const;
    std::shared_ptr<const Block> computeBlock(std::int64_t bx, std::int64_t bz) const;
    /// Child heights into `ground`, talus surface into `out`.
    void surface(const double* x, const double* z, std::size_t n, double* ground, double* out) const;

    HeightNodePtr mChild;
    TalusOptions mOptions;
    double mAxisSlope = 0.0; ///< the passes' slope along their own direction (m/m)
    int mReach = 0;
    std::unique_ptr<Cache> mCache;
};

} // namespace strata::terrain
