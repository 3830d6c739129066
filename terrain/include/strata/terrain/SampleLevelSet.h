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
    int halfWidth = 3;       ///< narrow-band half width in voxels, >= 3
    Region region;           ///< what to sample; voxels whose centre lies inside
    /// Called now and then with the fraction done (0..1); return false to stop,
    /// which makes sampleLevelSet throw strata::Error("interrupted"). May be empty.
    std::function<bool(double)> progress;
};

struct SampleStats
{
    std::uint64_t evaluatedPoints = 0; ///< density() calls
    std::uint64_t activeVoxels = 0;
    std::uint64_t tilesVisited = 0;    ///< 8³ leaf tiles considered
    std::uint64_t tilesSkipped = 0;    ///< tiles pruned by the gradient bound
};

/// Samples `field` into a FloatGrid of class GRID_LEVEL_SET with background
/// halfWidth·voxelSize and transform `linear(voxelSize)` (voxel (i,j,k) is
/// centred on world (i,j,k)·voxelSize). Only 8³ tiles that can contain the
/// surface (by the field's Lipschitz bound) are evaluated; within them, only
/// voxels with |density| < background are stored as active. The interior is
/// then signed with signedFloodFill. Multithreaded (TBB), and the result is
/// bitwise identical whatever the thread count.
/// Throws strata::Error on an invalid voxel size, half width or empty region.
openvdb::FloatGrid::Ptr sampleLevelSet(const DensityField& field, const SampleOptions& options,
                                       SampleStats* stats = nullptr);

} // namespace strata::terrain
