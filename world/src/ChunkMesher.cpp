#include "ChunkMesher.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <unordered_map>

namespace strata::world::detail {

using openvdb::Coord;
using openvdb::CoordBBox;

namespace {

constexpr int BLOCK = 8;

/// The lattice points origin + i·step (voxels), i in [0, dim)³, filled lazily
/// in 8³ blocks. A block whose every point is provably farther than `margin`
/// voxels from the base surface, with no edit within the margin, is filled
/// with values of the right sign only: no sign-changing edge of length
/// <= margin can end in it, so its values are only ever compared with 0.
class SampleArray
{
public:
    void init(const terrain::DensityField* field, const EditSnapshot* edits, double voxelSize, const std::int64_t origin[3],
              std::int64_t step, int dim, std::int64_t margin, SampleCache* cache = nullptr)
    {
        mCache = cache;
        mField = field;
        mEdits = edits;
        mVoxelSize = voxelSize;
        for (int a = 0; a < 3; ++a) mOrigin[a] = origin[a];
        mStep = step;
        mDim = dim;
        mMargin = margin;
        mBlocks = (dim + BLOCK - 1) / BLOCK;
        mValues.assign(std::size_t(dim) * dim * dim, 0.0f);
        mFilled.assign(std::size_t(mBlocks) * mBlocks * mBlocks, 0);
        if (mCache && mCache->blockDone.size() != mFilled.size()) {
            mCache->blockDone.assign(mFilled.size(), 0);
            mCache->values.clear();
        }
    }

    float at(int i, int j, int k)
    {
        assert(i >= 0 && j >= 0 && k >= 0 && i < mDim && j < mDim && k < mDim);
        const std::size_t b = (std::size_t(k / BLOCK) * mBlocks + j / BLOCK) * mBlocks + i / BLOCK;
        if (!mFilled[b]) fill(i / BLOCK, j / BLOCK, k / BLOCK, b);
        return mValues[(std::size_t(k) * mDim + j) * mDim + i];
    }

private:
    void fill(int bi, int bj, int bk, std::size_t b)
    {
        mFilled[b] = 1;
        const int lo[3] = {bi * BLOCK, bj * BLOCK, bk * BLOCK};
        const int hi[3] = {std::min(lo[0] + BLOCK, mDim), std::min(lo[1] + BLOCK, mDim), std::min(lo[2] + BLOCK, mDim)};
        std::int64_t v0[3], v1[3];
        for (int a = 0; a < 3; ++a) {
            v0[a] = mOrigin[a] + lo[a] * mStep;
            v1[a] = mOrigin[a] + (hi[a] - 1) * mStep;
        }
        const CoordBBox box(Coord(int(v0[0] - mMargin), int(v0[1] - mMargin), int(v0[2] - mMargin)),
                            Coord(int(v1[0] + mMargin), int(v1[1] + mMargin), int(v1[2] + mMargin)));
        const bool edited = !mEdits->empty() && mEdits->overlaps(box);
        if (!edited) {
            const glm::dvec3 c0{double(v0[0]), double(v0[1]), double(v0[2])};
            const glm::dvec3 c1{double(v1[0]), double(v1[1]), double(v1[2])};
            const glm::dvec3 centre = 0.5 * (c0 + c1) * mVoxelSize;
            const double radius = 0.5 * glm::length(c1 - c0) * mVoxelSize;
            const double bound = mField->distanceBound(centre);
            if (std::abs(bound) > radius + double(mMargin) * mVoxelSize) {
                const float value = bound > 0.0 ? float(bound - radius) : float(bound + radius);
                for (int k = lo[2]; k < hi[2]; ++k)
                    for (int j = lo[1]; j < hi[1]; ++j)
                        for (int i = lo[0]; i < hi[0]; ++i) mValues[(std::size_t(k) * mDim + j) * mDim + i] = value;
                return;
            }
        }
        const bool cached = mCache && mCache->blockDone[b];
        if (mCache && mCache->values.empty()) mCache->values.assign(mValues.size(), 0.0f);
        for (int k = lo[2]; k < hi[2]; ++k) {
            for (int j = lo[1]; j < hi[1]; ++j) {
                for (int i = lo[0]; i < hi[0]; ++i) {
                    const std::size_t at = (std::size_t(k) * mDim + j) * mDim + i;
                    const std::int64_t x = mOrigin[0] + i * mStep, y = mOrigin[1] + j * mStep,
                                       z = mOrigin[2] + k * mStep;
                    float value;
                    if (edited && mEdits->lookup(Coord(int(x), int(y), int(z)), value)) {
                        mValues[at] = value;
                        if (!mCache || cached) continue;
                    }
                    if (cached) {
                        mValues[at] = mCache->values[at];
                        continue;
                    }
                    value = baseSample(*mField, x, y, z, mVoxelSize);
                    if (mCache) mCache->values[at] = value;
                    if (!(edited && mEdits->lookup(Coord(int(x), int(y), int(z)), mValues[at]))) mValues[at] = value;
                }
            }
        }
        if (mCache) mCache->blockDone[b] = 1;
    }

    const terrain::DensityField* mField = nullptr;
    const EditSnapshot* mEdits = nullptr;
    SampleCache* mCache = nullptr;
    double mVoxelSize = 1.0;
    std::int64_t mOrigin[3] = {0, 0, 0};
    std::int64_t mStep = 1;
    int mDim = 0;
    int mBlocks = 0;
    std::int64_t mMargin = 0;
    std::vector<float> mValues;
    std::vector<std::uint8_t> mFilled;
};

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
        mOut.key = mKey;
        mOut.mesh.origin = glm::dvec3(double(mMin[0]), double(mMin[1]), double(mMin[2])) * mParams.voxelSize;
        if (emptyByBound()) return std::move(mOut);

        std::int64_t origin[3];
        for (int a = 0; a < 3; ++a) origin[a] = mMin[a] - 2 * mS;
        // Values of pruned blocks are only ever compared with 0; a block is
        // pruned when no sign-changing edge can end in it: edges of this
        // level's cells, and of the coarser neighbours' cells when there are
        // any (they read this array too).
        bool coarser = false;
        for (int m = 1; m < 8; ++m) coarser = coarser || mSig[m] > 0;
        mCoarse.init(&mField, &mEdits, mParams.voxelSize, origin, mS, mN + 3, coarser ? 2 * mS : mS, mCache);
        if (mHasFiner) {
            for (int a = 0; a < 3; ++a) origin[a] = mMin[a] - mS;
            mFine.init(&mField, &mEdits, mParams.voxelSize, origin, mS / 2, 2 * mN + 3, mS / 2);
        }

        // Edits of this chunk's own level.
        for (int z = 0; z < mN; ++z) {
            for (int y = 0; y < mN; ++y) {
                for (int x = 0; x < mN; ++x) {
                    const std::int64_t p[3] = {x * mS, y * mS, z * mS};
                    const float v0 = sample(mL, p[0], p[1], p[2]);
                    for (int a = 0; a < 3; ++a) {
                        std::int64_t q[3] = {p[0], p[1], p[2]};
                        q[a] += mS;
                        const float v1 = sample(mL, q[0], q[1], q[2]);
                        if ((v0 < 0.0f) == (v1 < 0.0f)) continue;
                        if (minNeighbourLevel(p, a) < 0) continue; // subdivided by a finer neighbour
                        quad(a, p, mS, v0 < 0.0f);
                    }
                }
            }
        }
        // The seam with finer lower neighbours: their edges on this chunk's lower faces.
        if (mHasFiner) {
            const std::int64_t h = mS / 2;
            for (int z = 0; z < 2 * mN; ++z) {
                for (int y = 0; y < 2 * mN; ++y) {
                    const bool anyX = z == 0 || y == 0;
                    for (int x = 0; x < 2 * mN; x = anyX ? x + 1 : 2 * mN) {
                        const std::int64_t p[3] = {x * h, y * h, z * h};
                        for (int a = 0; a < 3; ++a) {
                            if (minNeighbourLevel(p, a) != -1) continue;
                            std::int64_t q[3] = {p[0], p[1], p[2]};
                            q[a] += h;
                            const float v0 = sample(mL - 1, p[0], p[1], p[2]);
                            const float v1 = sample(mL - 1, q[0], q[1], q[2]);
                            if ((v0 < 0.0f) == (v1 < 0.0f)) continue;
                            quad(a, p, h, v0 < 0.0f);
                        }
                    }
                }
            }
        }
        return std::move(mOut);
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

    /// The level (relative to this chunk's) of the finest chunk touching the
    /// edge from p along axis a, p inside this chunk; in {-1, 0}.
    int minNeighbourLevel(const std::int64_t p[3], int a) const
    {
        int face = 0;
        for (int b = 0; b < 3; ++b)
            if (b != a && p[b] == 0) face |= 1 << b;
        int level = 0;
        for (int sub = face; sub; sub = (sub - 1) & face) level = std::min(level, int(mSig[sub]));
        return level;
    }

    /// A lattice sample at `level` (L−1, L or L+1), p relative to the chunk minimum (voxels).
    float sample(int level, std::int64_t x, std::int64_t y, std::int64_t z)
    {
        if (level >= mL) return mCoarse.at(int((x + 2 * mS) / mS), int((y + 2 * mS) / mS), int((z + 2 * mS) / mS));
        const std::int64_t h = mS / 2;
        return mFine.at(int((x + mS) / h), int((y + mS) / h), int((z + mS) / h));
    }

    /// The vertex of cell c (relative to the chunk, at level `level`).
    std::uint32_t vertex(int level, const std::int64_t c[3])
    {
        const std::uint64_t id = (std::uint64_t(level - mL + 1) << 60) | (std::uint64_t(c[0] + 1024) << 40) |
                                 (std::uint64_t(c[1] + 1024) << 20) | std::uint64_t(c[2] + 1024);
        const auto found = mIds.find(id);
        if (found != mIds.end()) return found->second;

        const std::int64_t size = std::int64_t(1) << level;
        float f[8];
        for (int i = 0; i < 8; ++i)
            f[i] = sample(level, (c[0] + (i & 1)) * size, (c[1] + ((i >> 1) & 1)) * size,
                          (c[2] + ((i >> 2) & 1)) * size);
        glm::dvec3 sum(0.0);
        int count = 0;
        for (int a = 0; a < 3; ++a) {
            const int bit = 1 << a;
            for (int i = 0; i < 8; ++i) {
                if (i & bit) continue;
                const int j = i | bit;
                if ((f[i] < 0.0f) == (f[j] < 0.0f)) continue;
                const double t = std::clamp(double(f[i]) / (double(f[i]) - double(f[j])), 0.0, 1.0);
                glm::dvec3 q(double(i & 1), double((i >> 1) & 1), double((i >> 2) & 1));
                q[a] = t;
                sum += q;
                ++count;
            }
        }
        const glm::dvec3 local = count ? sum / double(count) : glm::dvec3(0.5);
        const double cell = double(size) * mParams.voxelSize;
        const glm::dvec3 position = (glm::dvec3{double(c[0]), double(c[1]), double(c[2])} + local) * cell;

        // Gradient of the trilinear interpolant at `local`.
        glm::dvec3 g(0.0);
        for (int i = 0; i < 8; ++i) {
            const double wx = (i & 1) ? local.x : 1.0 - local.x;
            const double wy = ((i >> 1) & 1) ? local.y : 1.0 - local.y;
            const double wz = ((i >> 2) & 1) ? local.z : 1.0 - local.z;
            const double sx = (i & 1) ? 1.0 : -1.0, sy = ((i >> 1) & 1) ? 1.0 : -1.0, sz = ((i >> 2) & 1) ? 1.0 : -1.0;
            g.x += sx * wy * wz * f[i];
            g.y += sy * wx * wz * f[i];
            g.z += sz * wx * wy * f[i];
        }
        const double len = glm::length(g);
        const glm::dvec3 n = len > 0.0 ? g / len : glm::dvec3(0.0, 1.0, 0.0);

        const std::uint32_t index = std::uint32_t(mOut.mesh.positions.size());
        mOut.mesh.positions.emplace_back(float(position.x), float(position.y), float(position.z));
        mOut.mesh.normals.emplace_back(float(n.x), float(n.y), float(n.z));
        mOut.vertexCells.push_back(VertexCell{level, std::int32_t(c[0] + (mMin[0] >> level)),
                                              std::int32_t(c[1] + (mMin[1] >> level)),
                                              std::int32_t(c[2] + (mMin[2] >> level))});
        mIds.emplace(id, index);
        return index;
    }

    /// The polygon of the minimal edge from p along a, length h voxels.
    void quad(int a, const std::int64_t p[3], std::int64_t h, bool lowerInside)
    {
        static const int SB[4] = {-1, 1, 1, -1};
        static const int SC[4] = {-1, -1, 1, 1};
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        std::uint32_t poly[4];
        int n = 0;
        for (int i = 0; i < 4; ++i) {
            std::int64_t q[3] = {2 * p[0], 2 * p[1], 2 * p[2]}; // half-voxel units
            q[a] += h;
            q[b] += SB[i] * h;
            q[c] += SC[i] * h;
            const int mask = (q[0] < 0 ? 1 : 0) | (q[1] < 0 ? 2 : 0) | (q[2] < 0 ? 4 : 0);
            const int level = mL + mSig[mask];
            const std::int64_t cellHalf = std::int64_t(2) << level;
            const std::int64_t cell[3] = {floorDiv(q[0], cellHalf), floorDiv(q[1], cellHalf), floorDiv(q[2], cellHalf)};
            const std::uint32_t v = vertex(level, cell);
            if (n == 0 || poly[n - 1] != v) poly[n++] = v;
        }
        if (n > 1 && poly[n - 1] == poly[0]) --n;
        if (n < 3) return;
        if (!lowerInside) std::reverse(poly, poly + n);
        std::vector<std::uint32_t>& idx = mOut.mesh.indices;
        idx.insert(idx.end(), {poly[0], poly[1], poly[2]});
        if (n == 4) idx.insert(idx.end(), {poly[0], poly[2], poly[3]});
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
    std::unordered_map<std::uint64_t, std::uint32_t> mIds;
    ChunkMeshData mOut;
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
    return Mesher(field, params, key, signature, edits, cache).run();
}

} // namespace strata::world::detail
