// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Per-vertex surface attributes from the level set, for terrain layer
/// rules (render::LayerRule::cavity and cover): how deep in a crevice a
/// vertex lies, and whether rock hangs over it.

#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

#include <glm/vec2.hpp>

#include <vector>

namespace strata::meshing {

struct SurfaceAttributeOptions
{
    /// Cavity probe radius in metres; 0: 4 voxels. Clamped to 0.9 × the
    /// grid's background (its narrow band): beyond it the stored distances
    /// saturate and every vertex would look concave.
    double cavityRadius = 0.0;
    /// How far above a vertex rock still counts as cover, metres.
    double coverDistance = 64.0;
};

/// (cavity, cover) per vertex of `mesh` (positions relative to its origin,
/// normals required):
///  - cavity in [0, 1]: the mean shortfall of the signed distance at ¼, ½
///    and 1 radius along the normal from what a flat surface gives
///    (1 − φ(p + d·n)/d): 0 on flat ground and ridges, towards 1 in
///    crevices and inner corners;
///  - cover, 0 or 1: 1 when a ray straight up from just off the surface
///    meets rock (φ < 0) within coverDistance (cave floors and walls,
///    ground under overhangs and arches; ceilings always), sphere-traced on
///    the grid.
/// Deterministic and O(vertices); multithreaded. Throws strata::Error when
/// the mesh has no normals or the grid is not a level set.
std::vector<glm::vec2> computeSurfaceAttributes(const openvdb::FloatGrid& grid, const TriangleMesh& mesh,
                                                const SurfaceAttributeOptions& options = {});

} // namespace strata::meshing
