// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Analytic reference shapes with exact (or first-order) signed distances and
/// gradients, and narrow-band level sets sampled from them: the ground truth
/// for measuring meshers (SurfaceError.h), as `strata bench mesh` does.

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/SurfaceError.h>

#include <openvdb/openvdb.h>

#include <string>

namespace strata::meshing {

struct AnalyticShape
{
    std::string name;
    DistanceFunction distance; ///< signed distance, negative inside (metres)
    GradientFunction gradient; ///< its gradient (unit where the distance is exact)
    glm::dvec3 min{0.0}, max{0.0}; ///< bounds of the surface (metres)
    double volume = 0.0;       ///< enclosed volume (m³), 0 if unknown
    bool exact = true;         ///< distance is exact (false: first order)
};

/// Sphere of radius `r` around `c`.
AnalyticShape analyticSphere(const glm::dvec3& c, double r);
/// Axis-aligned box [lo, hi] with sharp edges and corners (exact distance).
AnalyticShape analyticBox(const glm::dvec3& lo, const glm::dvec3& hi);
/// Torus around the y axis through `c`: major radius R, minor radius r.
AnalyticShape analyticTorus(const glm::dvec3& c, double R, double r);
/// Gyroid sheet (period, thickness, metres) clipped by a sphere of radius
/// `clip` at the origin; distance is |g| / |grad g| - thickness/2 (first order).
AnalyticShape analyticGyroid(double period, double thickness, double clip);

/// A narrow-band level set of `shape` (half width in voxels) on a grid of
/// cubic voxels with voxel centres at integer multiples of `voxelSize`:
/// band voxels hold the shape's distance, the rest are signed-flood-filled.
/// O(bounding-box voxels).
openvdb::FloatGrid::Ptr levelSetFromShape(const AnalyticShape& shape, double voxelSize, double halfWidth = 3.0);

} // namespace strata::meshing
