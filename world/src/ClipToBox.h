// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: clips an indexed triangle mesh to a closed axis-aligned box so
// that two boxes sharing a face cut their shared triangles identically.

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace strata::world::detail {

/// A mesh in double precision (tile cells relative to the box minimum).
struct ClipMesh
{
    std::vector<glm::dvec3> positions;
    std::vector<glm::dvec3> normals; ///< unit, one per position
    std::vector<std::uint32_t> indices;
};

/// Keeps the part of every triangle inside [lo, hi] (closed). A cut edge
/// gets a new vertex: computed from the edge's endpoints ordered along the
/// cutting axis (so both triangles beside the edge, and the tile beyond the
/// face, compute the same bits), set exactly on the face, its other
/// coordinates rounded to multiples of 1/quantum, its normal interpolated.
/// Cut points at the same position are one vertex. Vertices no triangle
/// uses any more are dropped; the rest keep their order. Triangles that
/// collapse to a repeated vertex are dropped. O(triangles · log vertices).
void clipToBox(ClipMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi, double quantum);

} // namespace strata::world::detail
