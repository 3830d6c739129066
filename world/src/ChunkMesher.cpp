// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ChunkMesher.h"

#include <strata/world/LandformAttributes.h>

#include <strata/meshing/DualMesh.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace strata::world::detail {

using openvdb::Coord;
using openvdb::CoordBBox;

namespace {

/// Gathers one chunk's samples (the field and the edits through
/// SampleArray) and meshes them with meshing::dualMesh(): surface nets, one
/// vertex per cell, the cells of lower neighbours at their own levels.
class Mesher
{
public:
    Mesher(const terrain::DensityField& field, const MesherParams& params, const ChunkKey& key,
           const Signature& signature, const EditSnapshot& edits, SampleCache* cache)
        : mField(field)
        , mParams(params)
        , mKey(key)
        , mSig(signature)
        , mEdits(edits)
        , mCache(cache)
    {
        mL = key.level;
        mS = std::int64_t(1) << mL;
        mN = params.chunkSize;
        const std::int64_t k[3] = {key.x, key.y, key.z};
        for (int a = 0; a < 3; ++a) mMin[a] = k[a] * mN * mS;
        mHasFiner = false;
        for (int m = 1; m < 8; ++m) mHasFiner = mHasFiner || mSig[m] < 0;
        mHasFiner = mHasFiner && mL > 0;
    }

    ChunkMeshData run()
    {
        ChunkMeshData out;
        out.key = mKey;
        out.mesh.origin = glm::dvec3(double(mMin[0]), double(mMin[1]), double(mMin[2])) * mParams.voxelSize;
        if (emptyByBound()) return out;

        std::int64_t origin[3];
        for (int a = 0; a < 3; ++a) origin[a] = mMin[a] - 2 * mS;
        // Values of pruned blocks are only ever compared with 0; a block is
        // pruned when no sign-changing edge can end in it: edges of this
        // level's cells, and of the coarser neighbours' cells when there are
        // any (they read this array too).
        bool coarser = false;
        for (int m = 1; m < 8; ++m) coarser = coarser || mSig[m] > 0;
        const int dim = int(mN) + 3;
        mCoarse.init(&mField, &mEdits, mParams.voxelSize, origin, mS, {dim, dim, dim}, coarser ? 2 * mS : mS, mCache);
        mCoarse.fillAll(); // the walk reads every block of it anyway
        meshing::DualSamples samples;
        samples.values = mCoarse.data();
        samples.cells = {int(mN), int(mN), int(mN)};
        samples.size = mCoarse.dims();
        samples.stride = {1, dim, std::ptrdiff_t(dim) * dim};
        samples.apron = 2;
        samples.signature = mSig;
        if (mHasFiner) {
            for (int a = 0; a < 3; ++a) origin[a] = mMin[a] - mS;
            const int fineDim = 2 * int(mN) + 3;
            mFine.init(&mField, &mEdits, mParams.voxelSize, origin, mS / 2, {fineDim, fineDim, fineDim}, mS / 2);
            samples.fine = [this](int x, int y, int z) { return mFine.at(x + 2, y + 2, z + 2); };
        } else {
            // Level 0 has no finer level: a finer entry cannot occur.
            for (std::int8_t& level : samples.signature) level = std::max<std::int8_t>(level, 0);
        }
        meshing::DualMeshSettings settings;
        settings.gradients = meshing::DualGradient::Cell;
        const meshing::DualMeshResult result = meshing::dualMesh(samples, settings);

        out.mesh.positions.reserve(result.vertices.size());
        out.mesh.normals.reserve(result.vertices.size());
        out.vertexCells.reserve(result.vertices.size());
        for (std::size_t i = 0; i < result.vertices.size(); ++i) {
            const meshing::DualVertex& v = result.vertices[i];
            const glm::dvec3& g = result.gradients[i];
            const int level = mL + v.level;
            // Scaling by the power of two 2^mL is exact: one rounding, as from the cell.
            const glm::dvec3 position = result.positions[i] * (double(mS) * mParams.voxelSize);
            const double len = glm::length(g);
            const glm::dvec3 n = len > 0.0 ? g / len : glm::dvec3(0.0, 1.0, 0.0);
            out.mesh.positions.emplace_back(float(position.x), float(position.y), float(position.z));
            out.mesh.normals.emplace_back(float(n.x), float(n.y), float(n.z));
            out.vertexCells.push_back(VertexCell{level, std::int32_t(v.cell[0] + (mMin[0] >> level)),
                                                 std::int32_t(v.cell[1] + (mMin[1] >> level)),
                                                 std::int32_t(v.cell[2] + (mMin[2] >> level))});
        }
        out.mesh.indices = std::move(result.indices);
        return out;
    }

private:
    /// No edit near and the field's distance bound proves one sign over the
    /// whole sample footprint.
    bool emptyByBound() const
    {
        if (!mEdits.empty()) return false;
        const double v = mParams.voxelSize;
        const double lo = -2.0 * double(mS), hi = double(mN * mS);
        const glm::dvec3 c0 = glm::dvec3(double(mMin[0]), double(mMin[1]), double(mMin[2])) + lo;
        const glm::dvec3 c1 = glm::dvec3(double(mMin[0]), double(mMin[1]), double(mMin[2])) + hi;
        const glm::dvec3 centre = 0.5 * (c0 + c1) * v;
        const double radius = 0.5 * glm::length(c1 - c0) * v;
        return std::abs(mField.distanceBound(centre)) > radius + 2.0 * double(mS) * v;
    }

    const terrain::DensityField& mField;
    MesherParams mParams;
    ChunkKey mKey;
    Signature mSig;
    const EditSnapshot& mEdits;
    SampleCache* mCache;
    int mL = 0;
    std::int64_t mS = 1;
    std::int64_t mN = 32;
    std::int64_t mMin[3] = {0, 0, 0};
    bool mHasFiner = false;
    SampleArray mCoarse, mFine;
};

} // namespace

CoordBBox editFootprint(const MesherParams& params, const ChunkKey& key)
{
    const std::int64_t s = std::int64_t(1) << key.level;
    const std::int64_t w = std::int64_t(params.chunkSize) * s;
    const std::int64_t m[3] = {key.x * w, key.y * w, key.z * w};
    return CoordBBox(Coord(int(m[0] - 4 * s), int(m[1] - 4 * s), int(m[2] - 4 * s)),
                     Coord(int(m[0] + w + 2 * s), int(m[1] + w + 2 * s), int(m[2] + w + 2 * s)));
}

ChunkMeshData meshChunk(const terrain::DensityField& field, const MesherParams& params, const ChunkKey& key,
                        const Signature& signature, const EditSnapshot& edits, SampleCache* cache)
{
    ChunkMeshData out = Mesher(field, params, key, signature, edits, cache).run();
    if (params.landform && !out.mesh.positions.empty()) out.mesh.landform = computeLandformAttributes(*params.landform, out.mesh);
    if (params.rock && !out.mesh.positions.empty()) out.mesh.rock = computeRockAttributes(*params.rock, out.mesh);
    return out;
}

} // namespace strata::world::detail
