// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The `erode` node: a height node run through landscape evolution
/// (StreamPowerErosion.h) over an explicit world domain, so any crop of a
/// scene's region, any tile of a bake and any worker see the same terrain.
/// The input is sampled at the domain's cell corners, evolved once, and
/// read back through a uniform cubic B-spline: C² (no cell steps at any
/// voxel size), within the range of its 4×4 control cells (so bounds are
/// exact and cheap), with |∇h| at most the steepest cell difference.
/// Outside the domain the edge values continue.
///
/// The evolution runs once per process for the same input and options
/// (a cache keyed by a hash of the sampled input and the options).

#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/StreamPowerErosion.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <memory>
#include <vector>

namespace strata::terrain {

struct ErodeOptions
{
    glm::dvec2 min{-1024.0, -1024.0}; ///< world (x, z) of the first cell corner, metres
    glm::dvec2 max{1024.0, 1024.0};   ///< world (x, z) the last corner reaches, metres
    StreamPowerOptions evolution;     ///< cellSize is the grid's spacing
    /// Drainage area (m²) from which a channel counts as a river for the
    /// water mask.
    double riverArea = 2.0e5;
};

/// The evolved grid and its masks (shared by every node with the same key).
struct ErodedGrid
{
    int width = 0, height = 0;
    glm::dvec2 min{0.0};
    double cellSize = 1.0;
    std::vector<double> heights;    ///< metres, per corner
    std::vector<glm::vec4> masks;   ///< flow, wear, deposition, water (LandformMasks.h)
    double slopeBound = 0.0;        ///< of the B-spline of `heights`
    double lo = 0.0, hi = 0.0;      ///< the range of `heights`
    std::vector<double> blockLo, blockHi; ///< per 16×16 block of corners
    int blocksX = 0;
    double seconds = 0.0;           ///< the evolution's wall time when it ran
    StreamPowerResult budget;       ///< the run's budget and step count (grids emptied)
};

class ErodedHeightfield final : public HeightfieldBase, public LandformMasks
{
public:
    /// Samples `input` (and `upliftMap`, may be null: uniform) over the
    /// domain and evolves it, or takes the cached result. Throws
    /// strata::Error naming the option for bad options, and "cell_size"
    /// when the grid would exceed MAX_CELLS.
    ErodedHeightfield(HeightNodePtr input, HeightNodePtr upliftMap, const ErodeOptions& options,
                      const std::function<bool(double)>& progress = {});

    double height(double x, double z) const override;
    void heights(const double* x, const double* z, std::size_t n, double* out) const override;
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override;
    void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override;

    const ErodedGrid& grid() const { return *mGrid; }
    const ErodeOptions& options() const { return mOptions; }
    /// Whether this node's evolution came from the cache.
    bool cached() const { return mCached; }
    /// Empties the process-wide cache of evolutions (nodes built before
    /// keep theirs): the next node of any key evolves anew.
    static void clearCache();

    /// Cells (corners) the domain of `options` holds, and the memory its
    /// evolution needs at its peak (bytes): for plans and --max-memory.
    static std::size_t cellCount(const ErodeOptions& options);
    static std::size_t peakBytes(const ErodeOptions& options);
    static constexpr std::size_t MAX_CELLS = std::size_t(8193) * 8193;

private:
    std::shared_ptr<const ErodedGrid> mGrid;
    ErodeOptions mOptions;
    bool mCached = false;
};

} // namespace strata::terrain
