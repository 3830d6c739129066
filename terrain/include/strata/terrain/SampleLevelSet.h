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

struct SampleStats
{
    std::uint64_t evaluatedPoints = 0; ///< density() calls, pruning probes included
    std::uint64_t activeVoxels = 0;
    std::uint64_t tilesVisited = 0;    ///< 8³ leaf tiles overlapping the region
    std::uint64_t tilesSkipped = 0;    ///< of those, tiles pruned whole by the gradient bound
    std::uint64_t estimatedBytes = 0;  ///< the memory estimate checked against maxMemoryBytes
    std::uint64_t activeVoxelsBeforeRenormalize = 0; ///< = activeVoxels without renormalize
};

/// Samples `field` into a FloatGrid of class GRID_LEVEL_SET named "surface",
/// with background halfWidth·voxelSize and transform `linear(voxelSize)`
/// (voxel (i,j,k) is centred on world (i,j,k)·voxelSize).
///
/// Pruning: 128³ blocks are probed at their centre and subdivided down to 8³
/// tiles and then 2³ sub-blocks; a part is skipped when
/// |b(centre)| > radius + background, b = field.distanceBound(), or (for
/// fields with L = field.lipschitz() > 1) when |d(centre)| > L·radius +
/// background, d = field.density(), which proves every voxel of the part
/// would be stored inactive anyway. Only the
/// remaining voxels are evaluated; those with |density| < background are
/// stored active, the others as inactive ±background. Every skipped part's
/// sign is known from its probe, so the interior is signed exactly (inside
/// tiles hold −background); this replaces signedFloodFill, whose scanline
/// guess goes wrong where the region boundary cuts the band open. Outside the
/// region the grid holds the background (air).
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
