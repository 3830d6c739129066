// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "LodPartition.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <set>

namespace strata::world::detail {

double chunkWidth(const LodParams& params, int level)
{
    return double(params.chunkSize) * double(std::int64_t(1) << level) * params.voxelSize;
}

double boxDistance(const LodParams& params, const ChunkKey& key, const glm::dvec3& p)
{
    const double w = chunkWidth(params, key.level);
    const glm::dvec3 lo = glm::dvec3(key.x, key.y, key.z) * w;
    const glm::dvec3 hi = lo + w;
    const glm::dvec3 d = glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0));
    return glm::length(d);
}

ChunkKey level0Chunk(const glm::dvec3& p, const LodParams& params)
{
    const glm::dvec3 k = glm::floor(p / chunkWidth(params, 0));
    return ChunkKey{0, std::int32_t(k.x), std::int32_t(k.y), std::int32_t(k.z)};
}

std::vector<ChunkKey> interestChunks(const std::vector<glm::dvec3>& points, const LodParams& params)
{
    std::vector<ChunkKey> out;
    out.reserve(points.size());
    for (const glm::dvec3& p : points) out.push_back(level0Chunk(p, params));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

bool contains(const ChunkKey& a, const ChunkKey& b)
{
    if (a.level < b.level) return false;
    const int shift = a.level - b.level; // >> of a negative int32 floors (C++20)
    return (b.x >> shift) == a.x && (b.y >> shift) == a.y && (b.z >> shift) == a.z;
}

namespace {

double nearest(const LodParams& params, const ChunkKey& key, const std::vector<glm::dvec3>& points)
{
    double d = HUGE_VAL;
    for (const glm::dvec3& p : points) d = std::min(d, boxDistance(params, key, p));
    return d;
}

void refine(const LodParams& params, const std::vector<glm::dvec3>& interest, const ChunkKey& key, double distance,
            std::map<ChunkKey, PartitionEntry>& out)
{
    if (key.level > 0 && distance < params.lodDistance * double(std::int64_t(1) << (key.level - 1))) {
        for (int c = 0; c < 8; ++c) {
            const ChunkKey child{key.level - 1, 2 * key.x + (c & 1), 2 * key.y + ((c >> 1) & 1),
                                 2 * key.z + ((c >> 2) & 1)};
            refine(params, interest, child, nearest(params, child, interest), out);
        }
        return;
    }
    out[key].distance = distance;
}

} // namespace

std::map<ChunkKey, PartitionEntry> computePartition(const std::vector<ChunkKey>& interestKeys, const LodParams& params)
{
    std::map<ChunkKey, PartitionEntry> out;
    if (interestKeys.empty()) return out;
    const int top = params.levels - 1;
    const double w = chunkWidth(params, top);
    const double w0 = chunkWidth(params, 0);
    std::vector<glm::dvec3> interest; // the centres of the interest chunks
    for (const ChunkKey& k : interestKeys) interest.push_back((glm::dvec3(k.x, k.y, k.z) + 0.5) * w0);
    std::set<ChunkKey> tops;
    for (const glm::dvec3& i : interest) {
        const glm::dvec3 lo = glm::floor((i - params.viewRadius) / w);
        const glm::dvec3 hi = glm::floor((i + params.viewRadius) / w);
        for (double z = lo.z; z <= hi.z; ++z)
            for (double y = lo.y; y <= hi.y; ++y)
                for (double x = lo.x; x <= hi.x; ++x) {
                    const ChunkKey key{top, std::int32_t(x), std::int32_t(y), std::int32_t(z)};
                    if (boxDistance(params, key, i) < params.viewRadius) tops.insert(key);
                }
    }
    for (const ChunkKey& key : tops) refine(params, interest, key, nearest(params, key, interest), out);

    // Signatures: the level of each lower neighbour region relative to the chunk.
    for (auto& [key, entry] : out) {
        entry.signature.fill(0);
        for (int mask = 1; mask < 8; ++mask) {
            const std::int32_t nx = key.x - (mask & 1), ny = key.y - ((mask >> 1) & 1), nz = key.z - ((mask >> 2) & 1);
            std::int8_t rel = 0;
            if (out.count(ChunkKey{key.level, nx, ny, nz})) {
                rel = 0;
            } else if (key.level + 1 < params.levels &&
                       out.count(ChunkKey{key.level + 1, std::int32_t(floorDiv(nx, 2)), std::int32_t(floorDiv(ny, 2)),
                                          std::int32_t(floorDiv(nz, 2))})) {
                rel = 1;
            } else if (key.level > 0) {
                // The child of the neighbour region that touches this chunk's
                // lower corner: the upper child along offset axes.
                const ChunkKey child{key.level - 1, 2 * nx + (mask & 1), 2 * ny + ((mask >> 1) & 1),
                                     2 * nz + ((mask >> 2) & 1)};
                if (out.count(child)) rel = -1;
            }
            entry.signature[mask] = rel;
        }
    }
    return out;
}

} // namespace strata::world::detail
