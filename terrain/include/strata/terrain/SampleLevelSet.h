// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Sparse sampling of a density field into an OpenVDB narrow-band level set.

#include <strata/terrain/DensityField.h>

#include <openvdb/openvdb.h>

#include <cstdint>
#include <functional>

namespace strata::terrain {

/// An axis-aligned world box, metres, min inclusive, max exclusive.
struct Region
{
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
};

struct SampleOptions
{
    double voxelSize = 0.5;  ///< metres, > 0
    int halfWidth = 3;       ///< narrow-band half width in voxels, 3..64
    Region region;           ///< what to sample; voxels whose centre lies inside
    /// True: the field is intersected with the region box (its surface half a
    /// voxel inside the outermost voxel centres), so the level set is closed:
    /// solid cut by the region shows flat caps and meshes watertight. False:
    /// the surface is left open at the region boundary (for chunks meshed
    /// with overlap); a mesher should then drop faces outside the region.
    bool closed = true;
    /// Called now and then, from the calling thread, with the fraction done
    /// (0..1); return false to stop, which makes sampleLevelSet throw
    /// strata::Error("sampling interrupted"). May be empty.
    std::function<bool(double)> progress;
    /// Memory budget in bytes (0 = none). After the cheap coarse pass the
    /// grid's memory is estimated (an upper bound: every tile that may hold
    /// the surface counted as a leaf, plus internal nodes); above the budget
    /// sampleLevelSet throws strata::Error with the estimate and a suggestion,
    /// before the expensive fine pass allocates anything.
    std::uint64_t maxMemoryBytes = 0;
    /// Reinitialise the band to a true signed distance after sampling
    /// (OpenVDB LevelSetTracker::normalize, first-order upwind, then voxels
    /// beyond the half width are made inactive). Costs about one sampling
    /// pass of time; the result is still the same on any thread count.
    bool renormalize = false;
    int renormalizeIterations = 8; ///< Eikonal iterations, 1..64
};

/// What sampling cost and produced. Accounting: every density() call and
/// every DensityField::bounds() call counts as one evaluated point, and
/// boundEvaluations says how many of them were bounds() calls. A bounds()
/// call evaluates the same noise sums as a density() call (at the box
/// centre) plus interval arithmetic, so it costs more than one: for the
/// default scene's tree about 1.6× without and 2.3× with the heightfield's
/// mean value form (instruction counts inside sampleLevelSet, callgrind).
/// evaluatedPoints / activeVoxels therefore counts calls; weight
/// boundEvaluations by that factor for a cost-equivalent figure.
struct SampleStats
{
    std::uint64_t evaluatedPoints = 0;  ///< density() calls + bounds() calls
    std::uint64_t boundEvaluations = 0; ///< of those, bounds() calls (how hard pruning worked)
    std::uint64_t activeVoxels = 0;
    std::uint64_t tilesVisited = 0;    ///< 8³ leaf tiles overlapping the region
    std::uint64_t tilesSkipped = 0;    ///< of those, tiles pruned whole by their interval bound
    std::uint64_t estimatedBytes = 0;  ///< the memory estimate checked against maxMemoryBytes
    std::uint64_t activeVoxelsBeforeRenormalize = 0; ///< = activeVoxels without renormalize
};

/// Samples `field` into a FloatGrid of class GRID_LEVEL_SET named "surface",
/// with background halfWidth·voxelSize and transform `linear(voxelSize)`
/// (voxel (i,j,k) is centred on world (i,j,k)·voxelSize).
///
/// Pruning: 128³ blocks are bounded and subdivided down to 8³ tiles, and
/// inside each remaining tile 4³ sub-blocks; a part is skipped
/// when field.bounds() over the box of its voxel centres lies entirely at or
/// beyond ±background (with `closed`, intersected with the region box's
/// distance). That proves every voxel of the part would be stored as an
/// inactive ±background anyway, and gives its sign; only the remaining
/// voxels are evaluated. So the grid is exactly the dense sampling: a voxel
/// is active iff |density| < background (holding float(density)), else it
/// holds ±background with density's sign, whatever the pruning did.
/// The interior is signed from the bounds (inside tiles hold −background);
/// this replaces signedFloodFill, whose scanline guess goes wrong where the
/// region boundary cuts the band open. Outside the region the grid holds the
/// background (air).
///
/// Multithreaded (TBB); the result is bitwise identical whatever the thread
/// count. With `closed` false, two regions that share voxels give them the
/// same values (pruning decisions depend only on aligned cubes), so a world
/// can be sampled box by box. Memory and time grow with the surface area inside the region.
/// Throws strata::Error on an invalid voxel size, half width or region (not
/// finite, empty, more than 2^30 voxels from the origin or more than 2^40
/// voxels in all), on a memory estimate above maxMemoryBytes, on
/// interruption, and passes on whatever field.density() throws.
openvdb::FloatGrid::Ptr sampleLevelSet(const DensityField& field, const SampleOptions& options,
                                       SampleStats* stats = nullptr);

} // namespace strata::terrain
