// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: skirts that hang from a tile's border into the rock (see
// TileMesh.h, "Seams").

#include "ClipToBox.h"

#include <functional>

namespace strata::world::detail {

/// Skirts are not made where the surface meets the face plane at less than
/// this angle (its sine): such a skirt would lie (nearly) in the surface's
/// own plane, where it shows as a flap above the ground (a slab cut through
/// nearly flat terrain) or fights the surface for the same pixels (a cliff
/// in a vertical face), and the gap between two levels there is wider than
/// any skirt could cover anyway (an error e along the normal moves the cut
/// by e / sin(angle) within the plane).
constexpr double SKIRT_MIN_SINE = 0.5; // 30 degrees

/// For every boundary edge of `surface` (an edge of one triangle) whose two
/// ends lie on the same face of [lo, hi] that `faces` marks (bit 2·a: the
/// minimum face of axis a, bit 2·a + 1: the maximum), a quad from the edge
/// `depth` deep within the face plane, away from the air: each end along
/// the in-plane axis on which its vertex normal's in-plane part, reversed,
/// is largest (−y under terrain on a tile's side); none where that part is
/// shorter than SKIRT_MIN_SINE (see above). The far edge is clamped into
/// [lo, hi] (never outside the box) and, with `density` (the field in
/// the mesh's coordinates, negative in rock; may be empty), ends where the
/// skirt would leave the rock again after entering it (a cave under a thin
/// roof), so a skirt stays hidden in the rock. Every skirt vertex has the normal of
/// the surface vertex it hangs from. Wound to continue the surface's
/// orientation, so the front faces out of the box (a one-sided material
/// shows it from the air side of the seam, lit like the surface); a
/// triangle that would face into the box (the ends hang different ways,
/// or the vertex normal disagrees with its triangle) or that the clamp
/// collapsed is dropped. Returns the skirt mesh.
ClipMesh makeSkirts(const ClipMesh& surface, const glm::dvec3& lo, const glm::dvec3& hi, unsigned faces,
                    double depth, const std::function<double(const glm::dvec3&)>& density = {});

} // namespace strata::world::detail
