// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: skirts that hang from a tile's border into the rock (see
// TileMesh.h, "Seams").

#include "ClipToBox.h"

namespace strata::world::detail {

/// For every boundary edge of `surface` (an edge of one triangle) whose two
/// ends lie on the same face of [lo, hi] that `faces` marks (bit 2·a: the
/// minimum face of axis a, bit 2·a + 1: the maximum), a quad from the edge
/// `depth` deep within the face plane, away from the air: along the
/// vertex normal's in-plane part, reversed (−y where that part vanishes on
/// a vertical face; no skirt where it vanishes on a horizontal face).
/// Wound to continue the surface's orientation. Returns the skirt mesh.
ClipMesh makeSkirts(const ClipMesh& surface, const glm::dvec3& lo, const glm::dvec3& hi, unsigned faces,
                    double depth);

} // namespace strata::world::detail
