// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "MotionLookAhead.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace strata::world::detail {

void MotionLookAhead::update(const std::vector<glm::dvec3>& points)
{
    if (points.size() != mPoints.size()) {
        mDirections.assign(points.size(), glm::dvec3(0.0));
    } else {
        for (std::size_t i = 0; i < points.size(); ++i) {
            const glm::dvec3 d = points[i] - mPoints[i];
            if (d != glm::dvec3(0.0)) mDirections[i] = d;
        }
    }
    mPoints = points;
}

std::vector<ChunkKey> MotionLookAhead::nextInterest(const LodParams& params) const
{
    std::vector<ChunkKey> out;
    out.reserve(mPoints.size());
    for (std::size_t i = 0; i < mPoints.size(); ++i) out.push_back(nextChunk(mPoints[i], mDirections[i], params));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

ChunkKey nextChunk(const glm::dvec3& p, const glm::dvec3& direction, const LodParams& params)
{
    const double w = chunkWidth(params, 0);
    ChunkKey key = level0Chunk(p, params);
    const glm::dvec3 cell(key.x, key.y, key.z);
    // The ray's exit parameter through each axis' far face; the axes that
    // reach theirs first (ties: an edge or a corner) step.
    double t[3];
    double first = HUGE_VAL;
    for (int a = 0; a < 3; ++a) {
        t[a] = HUGE_VAL;
        if (direction[a] > 0.0) t[a] = ((cell[a] + 1.0) * w - p[a]) / direction[a];
        else if (direction[a] < 0.0) t[a] = (cell[a] * w - p[a]) / direction[a];
        first = std::min(first, t[a]);
    }
    if (first == HUGE_VAL) return key;
    std::int32_t* const c[3] = {&key.x, &key.y, &key.z};
    for (int a = 0; a < 3; ++a)
        if (t[a] == first) *c[a] += direction[a] > 0.0 ? 1 : -1;
    return key;
}

} // namespace strata::world::detail
