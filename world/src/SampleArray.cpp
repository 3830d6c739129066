// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "SampleArray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace strata::world::detail {

using openvdb::Coord;
using openvdb::CoordBBox;

void SampleArray::init(const terrain::DensityField* field, const EditSnapshot* edits, double voxelSize,
                       const std::int64_t origin[3], std::int64_t step, const std::array<int, 3>& dims,
                       std::int64_t margin, SampleCache* cache)
{
    mCache = cache;
    mField = field;
    mEdits = edits;
    mVoxelSize = voxelSize;
    for (int a = 0; a < 3; ++a) {
        mOrigin[a] = origin[a];
        mBlocks[a] = (dims[a] + BLOCK - 1) / BLOCK;
    }
    mStep = step;
    mDims = dims;
    mMargin = margin;
    mValues.assign(std::size_t(dims[0]) * dims[1] * dims[2], 0.0f);
    mFilled.assign(std::size_t(mBlocks[0]) * mBlocks[1] * mBlocks[2], 0);
    mBlockBounds.clear();
    if (mCache && mCache->blockMargin.size() != mFilled.size()) {
        mCache->blockMargin.assign(mFilled.size(), 0);
        mCache->values.clear();
    }
}

std::size_t SampleArray::bytesFor(const std::array<int, 3>& dims)
{
    const std::size_t blocks = std::size_t((dims[0] + BLOCK - 1) / BLOCK) * ((dims[1] + BLOCK - 1) / BLOCK) *
                               ((dims[2] + BLOCK - 1) / BLOCK);
    return std::size_t(dims[0]) * dims[1] * dims[2] * sizeof(float) + blocks;
}

void SampleArray::fillAll()
{
    for (int bk = 0; bk < mBlocks[2]; ++bk)
        for (int bj = 0; bj < mBlocks[1]; ++bj)
            for (int bi = 0; bi < mBlocks[0]; ++bi) {
                const std::size_t b = (std::size_t(bk) * mBlocks[1] + bj) * mBlocks[0] + bi;
                if (!mFilled[b]) fill(bi, bj, bk, b);
            }
}

glm::dvec3 SampleArray::centre(const std::int64_t v0[3], const std::int64_t v1[3]) const
{
    const glm::dvec3 c0{double(v0[0]), double(v0[1]), double(v0[2])};
    const glm::dvec3 c1{double(v1[0]), double(v1[1]), double(v1[2])};
    return 0.5 * (c0 + c1) * mVoxelSize;
}

bool SampleArray::provablyFar(const std::int64_t v0[3], const std::int64_t v1[3], double bound)
{
    // The distance bound at the centre: no surface within it.
    const glm::dvec3 c0{double(v0[0]), double(v0[1]), double(v0[2])};
    const glm::dvec3 c1{double(v1[0]), double(v1[1]), double(v1[2])};
    const double radius = 0.5 * glm::length(c1 - c0) * mVoxelSize;
    const double reach = double(mMargin) * mVoxelSize;
    if (std::abs(bound) > radius + reach) {
        mFarValue = bound > 0.0 ? float(bound - radius) : float(bound + radius);
        return true;
    }
    return false;
}

void SampleArray::blockSpan(int bi, int bj, int bk, std::int64_t v0[3], std::int64_t v1[3]) const
{
    const int lo[3] = {bi * BLOCK, bj * BLOCK, bk * BLOCK};
    for (int a = 0; a < 3; ++a) {
        v0[a] = mOrigin[a] + lo[a] * mStep;
        v1[a] = mOrigin[a] + (std::min(lo[a] + BLOCK, mDims[a]) - 1) * mStep;
    }
}

double SampleArray::blockBound(std::size_t b)
{
    if (mBlockBounds.empty()) {
        // Every block's centre in one block evaluation (the same bits as
        // distanceBound() at each): a chunk's blocks cost one field call.
        const std::size_t count = mFilled.size();
        mX.resize(count);
        mY.resize(count);
        mZ.resize(count);
        std::size_t n = 0;
        for (int bk = 0; bk < mBlocks[2]; ++bk)
            for (int bj = 0; bj < mBlocks[1]; ++bj)
                for (int bi = 0; bi < mBlocks[0]; ++bi, ++n) {
                    std::int64_t v0[3], v1[3];
                    blockSpan(bi, bj, bk, v0, v1);
                    const glm::dvec3 c = centre(v0, v1);
                    mX[n] = c.x;
                    mY[n] = c.y;
                    mZ[n] = c.z;
                }
        mBlockBounds.resize(count);
        const glm::dvec3 lo(*std::min_element(mX.begin(), mX.end()), *std::min_element(mY.begin(), mY.end()),
                            *std::min_element(mZ.begin(), mZ.end()));
        const glm::dvec3 hi(*std::max_element(mX.begin(), mX.end()), *std::max_element(mY.begin(), mY.end()),
                            *std::max_element(mZ.begin(), mZ.end()));
        mField->distanceBounds({mX.data(), mY.data(), mZ.data(), count, {lo, hi}}, mBlockBounds.data());
    }
    return mBlockBounds[b];
}

void SampleArray::fill(int bi, int bj, int bk, std::size_t b)
{
    mFilled[b] = 1;
    const int lo[3] = {bi * BLOCK, bj * BLOCK, bk * BLOCK};
    const int hi[3] = {std::min(lo[0] + BLOCK, mDims[0]), std::min(lo[1] + BLOCK, mDims[1]),
                       std::min(lo[2] + BLOCK, mDims[2])};
    std::int64_t v0[3], v1[3];
    blockSpan(bi, bj, bk, v0, v1);
    const CoordBBox box(Coord(int(v0[0] - mMargin), int(v0[1] - mMargin), int(v0[2] - mMargin)),
                        Coord(int(v1[0] + mMargin), int(v1[1] + mMargin), int(v1[2] + mMargin)));
    const bool edited = mEdits && !mEdits->empty() && mEdits->overlaps(box);
    if (!edited && provablyFar(v0, v1, blockBound(b))) {
        for (int k = lo[2]; k < hi[2]; ++k)
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int i = lo[0]; i < hi[0]; ++i) mValues[index(i, j, k)] = mFarValue;
        return;
    }
    const std::int64_t cachedAt = mCache ? mCache->blockMargin[b] : 0;
    const bool cached = cachedAt != 0;
    if (!edited && !(cached && mMargin >= cachedAt)) {
        // Octants this margin prunes get values of their sign only, cached
        // or not: the same values as a chunk meshed without a cache.
        if (fillByOctants(lo, hi)) return;
        if (cached) mCache->blockMargin[b] = mMargin;
    }
    if (mCache && mCache->values.empty()) mCache->values.assign(mValues.size(), 0.0f);
    if (!cached) {
        // The block's procedural samples in one block evaluation: the same
        // bits as baseSample() point by point.
        double axis[3][BLOCK];
        for (int a = 0; a < 3; ++a) {
            for (int t = lo[a]; t < hi[a]; ++t) axis[a][t - lo[a]] = double(mOrigin[a] + t * mStep) * mVoxelSize;
        }
        const std::size_t count = std::size_t(hi[0] - lo[0]) * std::size_t(hi[1] - lo[1]) * std::size_t(hi[2] - lo[2]);
        mX.resize(count);
        mY.resize(count);
        mZ.resize(count);
        std::size_t n = 0;
        for (int k = lo[2]; k < hi[2]; ++k)
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int i = lo[0]; i < hi[0]; ++i, ++n) {
                    mX[n] = axis[0][i - lo[0]];
                    mY[n] = axis[1][j - lo[1]];
                    mZ[n] = axis[2][k - lo[2]];
                }
        mD.resize(count);
        const glm::dvec3 c0{double(v0[0]), double(v0[1]), double(v0[2])};
        const glm::dvec3 c1{double(v1[0]), double(v1[1]), double(v1[2])};
        mField->densities({mX.data(), mY.data(), mZ.data(), count, {c0 * mVoxelSize, c1 * mVoxelSize}}, mD.data());
    }
    std::size_t n = 0;
    for (int k = lo[2]; k < hi[2]; ++k) {
        for (int j = lo[1]; j < hi[1]; ++j) {
            const std::size_t row = index(lo[0], j, k);
            if (!edited) {
                // No edit here: a straight copy of the row (the common case).
                float* values = mValues.data() + row;
                const int width = hi[0] - lo[0];
                if (cached) {
                    std::copy_n(mCache->values.data() + row, width, values);
                } else {
                    for (int i = 0; i < width; ++i) values[i] = float(mD[n + std::size_t(i)]);
                    if (mCache) std::copy_n(values, width, mCache->values.data() + row);
                }
                n += std::size_t(width);
                continue;
            }
            for (int i = lo[0]; i < hi[0]; ++i, ++n) {
                const std::size_t at = row + std::size_t(i - lo[0]);
                const std::int64_t x = mOrigin[0] + i * mStep, y = mOrigin[1] + j * mStep, z = mOrigin[2] + k * mStep;
                float value;
                if (mEdits->lookup(Coord(int(x), int(y), int(z)), value)) {
                    mValues[at] = value;
                    if (!mCache || cached) continue;
                }
                if (cached) {
                    mValues[at] = mCache->values[at];
                    continue;
                }
                value = float(mD[n]);
                if (mCache) mCache->values[at] = value;
                if (!mEdits->lookup(Coord(int(x), int(y), int(z)), mValues[at])) mValues[at] = value;
            }
        }
    }
    if (mCache && !cached) mCache->blockMargin[b] = edited ? SampleCache::UNTESTED : mMargin;
}

bool SampleArray::fillByOctants(const int lo[3], const int hi[3])
{
    constexpr int HALF = BLOCK / 2;
    struct Octant
    {
        int lo[3], hi[3];
        bool far = false;
        float farValue = 0.0f;
    };
    Octant octants[8];
    std::int64_t v0[8][3], v1[8][3];
    double cx[8], cy[8], cz[8], bounds[8];
    int live[8], count = 0;
    for (int o = 0; o < 8; ++o) {
        Octant& q = octants[o];
        bool empty = false;
        for (int a = 0; a < 3; ++a) {
            q.lo[a] = lo[a] + ((o >> a) & 1) * HALF;
            q.hi[a] = std::min(q.lo[a] + HALF, hi[a]);
            empty = empty || q.lo[a] >= q.hi[a];
            v0[o][a] = mOrigin[a] + q.lo[a] * mStep;
            v1[o][a] = mOrigin[a] + (q.hi[a] - 1) * mStep;
        }
        if (empty) {
            q.hi[0] = q.lo[0]; // no points
            continue;
        }
        const glm::dvec3 c = centre(v0[o], v1[o]);
        cx[count] = c.x;
        cy[count] = c.y;
        cz[count] = c.z;
        live[count++] = o;
    }
    // The octants' centres in one block evaluation.
    glm::dvec3 blockLo, blockHi;
    for (int a = 0; a < 3; ++a) {
        blockLo[a] = double(mOrigin[a] + lo[a] * mStep) * mVoxelSize;
        blockHi[a] = double(mOrigin[a] + (hi[a] - 1) * mStep) * mVoxelSize;
    }
    mField->distanceBounds({cx, cy, cz, std::size_t(count), {blockLo, blockHi}}, bounds);
    bool anyFar = false, anyNear = false;
    for (int l = 0; l < count; ++l) {
        Octant& q = octants[live[l]];
        q.far = provablyFar(v0[live[l]], v1[live[l]], bounds[l]);
        q.farValue = mFarValue;
        anyFar = anyFar || q.far;
        anyNear = anyNear || !q.far;
    }
    if (!anyFar) return false; // the whole block, evaluated (and cached) by fill()

    // The near octants' points in one block evaluation (the block's box
    // holds them all), then every octant written.
    mX.clear();
    mY.clear();
    mZ.clear();
    for (const Octant& q : octants) {
        if (q.far) continue;
        for (int k = q.lo[2]; k < q.hi[2]; ++k)
            for (int j = q.lo[1]; j < q.hi[1]; ++j)
                for (int i = q.lo[0]; i < q.hi[0]; ++i) {
                    mX.push_back(double(mOrigin[0] + i * mStep) * mVoxelSize);
                    mY.push_back(double(mOrigin[1] + j * mStep) * mVoxelSize);
                    mZ.push_back(double(mOrigin[2] + k * mStep) * mVoxelSize);
                }
    }
    mD.resize(mX.size());
    if (anyNear) {
        glm::dvec3 c0, c1;
        for (int a = 0; a < 3; ++a) {
            c0[a] = double(mOrigin[a] + lo[a] * mStep) * mVoxelSize;
            c1[a] = double(mOrigin[a] + (hi[a] - 1) * mStep) * mVoxelSize;
        }
        mField->densities({mX.data(), mY.data(), mZ.data(), mX.size(), {c0, c1}}, mD.data());
    }
    std::size_t n = 0;
    for (const Octant& q : octants) {
        for (int k = q.lo[2]; k < q.hi[2]; ++k)
            for (int j = q.lo[1]; j < q.hi[1]; ++j)
                for (int i = q.lo[0]; i < q.hi[0]; ++i) mValues[index(i, j, k)] = q.far ? q.farValue : float(mD[n++]);
    }
    return true;
}

} // namespace strata::world::detail
