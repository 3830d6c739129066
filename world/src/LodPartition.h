// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: which chunks are resident, at which level, for a set of points of
// interest (the octree partition of World.h), and each chunk's signature.
// The partition is computed from the level-0 chunks that hold the points (the
// "interest chunks"), so it changes only when a point crosses a level-0 chunk
// border.

#include <strata/world/WorldTypes.h>

#include "Lattice.h"

#include <map>
#include <vector>

namespace strata::world::detail {

struct LodParams
{
    double voxelSize = 0.5;
    int chunkSize = 32;
    int levels = 4;
    double lodDistance = 64.0;
    double viewRadius = 384.0;
};

struct PartitionEntry
{
    Signature signature{};
    double distance = 0.0; ///< distance from the box to the nearest interest chunk's centre (metres)
};

/// Chunk width of a level in metres.
double chunkWidth(const LodParams& params, int level);
/// Distance from `p` to the chunk's box (0 inside).
double boxDistance(const LodParams& params, const ChunkKey& key, const glm::dvec3& p);

/// The level-0 chunk holding `p`.
ChunkKey level0Chunk(const glm::dvec3& p, const LodParams& params);

/// The level-0 chunks holding `points`, sorted, without repeats.
std::vector<ChunkKey> interestChunks(const std::vector<glm::dvec3>& points, const LodParams& params);

/// Does chunk `a` contain chunk `b` (same key, or `b` a descendant of `a`)?
bool contains(const ChunkKey& a, const ChunkKey& b);

/// The resident set for the interest chunks (see interestChunks), measured
/// from their centres: a top-level chunk is resident within viewRadius of
/// one, a chunk of level l > 0 is split when closer than lodDistance·2^(l−1)
/// to one. Deterministic (a sorted map), balanced (face-, edge- and
/// corner-neighbours differ by at most one level when lodDistance >=
/// 2·sqrt(3)·chunkWidth(0)). O(resident chunks · interest chunks).
std::map<ChunkKey, PartitionEntry> computePartition(const std::vector<ChunkKey>& interest, const LodParams& params);

} // namespace strata::world::detail
