// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: where the points of interest go next. The World meshes the
// chunks of the partition they will need after their next level-0 chunk
// border ahead of time (WorldOptions::lookAhead), so that crossing it finds
// most of its chunks already meshed instead of a burst of a few hundred.

#include "LodPartition.h"

#include <vector>

namespace strata::world::detail {

/// Each point's last direction of motion, from successive calls.
class MotionLookAhead
{
public:
    /// Takes the new points. A point keeps the direction of its last move
    /// (the same index in the previous call); when the number of points
    /// changes, the directions are forgotten.
    void update(const std::vector<glm::dvec3>& points);

    /// The level-0 chunks the points enter next: for each moving point, the
    /// chunk across the face (or edge, or corner, where the ray leaves
    /// through one exactly) of its chunk that its ray of motion leaves
    /// through. A point that stops keeps its last direction (one that pauses
    /// keeps the chunks ahead of it); only a point that has not moved since
    /// the directions were forgotten stays in its own chunk. Sorted, without
    /// repeats. Equal to interestChunks() when no point has moved yet.
    std::vector<ChunkKey> nextInterest(const LodParams& params) const;

private:
    std::vector<glm::dvec3> mPoints;
    std::vector<glm::dvec3> mDirections; ///< zero: not moved yet
};

/// The level-0 chunk after `p`'s along the ray p + t·direction (t > 0), or
/// p's own chunk when the direction is zero.
ChunkKey nextChunk(const glm::dvec3& p, const glm::dvec3& direction, const LodParams& params);

} // namespace strata::world::detail
