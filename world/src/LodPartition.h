#pragma once
// Internal: which chunks are resident, at which level, for a set of points of
// interest (the octree partition of World.h), and each chunk's signature.

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
    double distance = 0.0; ///< box distance to the nearest point of interest (metres)
};

/// Chunk width of a level in metres.
double chunkWidth(const LodParams& params, int level);
/// Distance from `p` to the chunk's box (0 inside).
double boxDistance(const LodParams& params, const ChunkKey& key, const glm::dvec3& p);

/// The resident set: deterministic (a sorted map), balanced (face-, edge- and
/// corner-neighbours differ by at most one level when lodDistance >=
/// 2·sqrt(3)·chunkWidth(0)).
std::map<ChunkKey, PartitionEntry> computePartition(const std::vector<glm::dvec3>& points, const LodParams& params);

} // namespace strata::world::detail
