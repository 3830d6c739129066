// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: a box of lattice samples filled lazily in 8³ blocks, pruned by
// the field's distance bound, evaluated a block at a time.
// Shared by the World's chunk mesher and the bake's tile mesher, so both
// read the same floats for the same point.

#include "EditLayer.h"
#include "Lattice.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <mutex>
#include <vector>

namespace strata::world::detail {

/// The procedural samples of one chunk's own-level lattice, kept between
/// re-meshes (after an edit only the edits are looked up again). Used by one
/// task at a time (`mutex`); the values are the same whether cached or not.
struct SampleCache
{
    /// blockMargin of a block cached from an edited block, whose octants
    /// were not tested.
    static constexpr std::int64_t UNTESTED = INT64_MAX;

    std::mutex mutex;
    std::vector<float> values; ///< empty until a block is evaluated
    /// Per 8³ block: 0 = not cached; else `values` hold its procedural
    /// samples, and no octant of it was prunable with this margin (voxels)
    /// or any wider one. A narrower margin may prune octants: the array
    /// tests them again, so a mesh never depends on which signatures (and
    /// margins) the chunk was meshed with before.
    std::vector<std::int64_t> blockMargin;
    std::size_t bytes() const
    {
        return values.capacity() * sizeof(float) + blockMargin.capacity() * sizeof(std::int64_t);
    }
};

/// The lattice points origin + i·step (voxels), i in [0, dims), filled lazily
/// in 8³ blocks. A block whose every point is provably farther than `margin`
/// voxels from the base surface, with no edit within the margin, is filled
/// with values of the right sign only: no sign-changing edge of length
/// <= margin can end in it, so its values are only ever compared with 0.
class SampleArray
{
public:
    static constexpr int BLOCK = 8;

    /// `edits` and `cache` may be null (no edits; no cache).
    void init(const terrain::DensityField* field, const EditSnapshot* edits, double voxelSize,
              const std::int64_t origin[3], std::int64_t step, const std::array<int, 3>& dims, std::int64_t margin,
              SampleCache* cache = nullptr);

    float at(int i, int j, int k)
    {
        const std::size_t b = (std::size_t(k / BLOCK) * mBlocks[1] + j / BLOCK) * mBlocks[0] + i / BLOCK;
        if (!mFilled[b]) fill(i / BLOCK, j / BLOCK, k / BLOCK, b);
        return mValues[index(i, j, k)];
    }

    /// Fills every block not filled yet (the same values as on demand).
    void fillAll();

    /// The values, x fastest, then y, then z (fillAll() first).
    const float* data() const { return mValues.data(); }
    const std::array<int, 3>& dims() const { return mDims; }
    /// Heap bytes an array of `dims` takes.
    static std::size_t bytesFor(const std::array<int, 3>& dims);

private:
    std::size_t index(int i, int j, int k) const { return (std::size_t(k) * mDims[1] + j) * mDims[0] + i; }
    void fill(int bi, int bj, int bk, std::size_t b);
    /// True when no surface lies within the margin of the block spanning
    /// lattice points v0..v1 (the distance bound at its centre); sets
    /// mFarValue to a value of its sign. (The field's interval over the
    /// block was tried too: on the World benchmark's field it cost more
    /// than it pruned.)
    bool provablyFar(const std::int64_t v0[3], const std::int64_t v1[3], double bound);
    /// The centre (metres) of the block spanning lattice points v0..v1.
    glm::dvec3 centre(const std::int64_t v0[3], const std::int64_t v1[3]) const;
    /// Lattice points of block b's first and last sample.
    void blockSpan(int bi, int bj, int bk, std::int64_t v0[3], std::int64_t v1[3]) const;
    /// The distance bound at block b's centre: every block's at once, in one
    /// DensityField::distanceBounds() call, when first asked.
    double blockBound(std::size_t b);
    /// For a block neither far as a whole nor edited: fills its provably far
    /// 4³ octants with values of their sign and evaluates the others.
    /// Returns false, filling nothing, when no octant is far. A block
    /// filled this way is not cached: its far values are not samples.
    bool fillByOctants(const int lo[3], const int hi[3]);

    const terrain::DensityField* mField = nullptr;
    const EditSnapshot* mEdits = nullptr;
    SampleCache* mCache = nullptr;
    double mVoxelSize = 1.0;
    std::int64_t mOrigin[3] = {0, 0, 0};
    std::int64_t mStep = 1;
    std::array<int, 3> mDims{0, 0, 0};
    std::array<int, 3> mBlocks{0, 0, 0};
    std::int64_t mMargin = 0;
    std::vector<float> mValues;
    std::vector<std::uint8_t> mFilled;
    float mFarValue = 0.0f;
    std::vector<double> mX, mY, mZ, mD; ///< one block's points and densities
    std::vector<double> mBlockBounds;   ///< blockBound() per block; empty until first asked
};

} // namespace strata::world::detail
