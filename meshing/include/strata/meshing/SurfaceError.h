// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Accuracy of a mesh against an analytic surface: distances both ways and
/// normal error, in voxel units so grids of different resolution compare.

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/TriangleMesh.h>

#include <functional>
#include <vector>

namespace strata::meshing {

/// Signed distance to the analytic surface at a world position (metres),
/// negative inside. Must be thread-safe.
using DistanceFunction = std::function<double(const glm::dvec3& world)>;

struct SurfaceErrorOptions
{
    double voxelSize = 1.0; ///< metres per voxel: distances are divided by it
    /// Points on the analytic surface (world metres) for the surface-to-mesh
    /// direction, e.g. from sampleSurface(). Empty: that direction is skipped.
    std::vector<glm::dvec3> surfacePoints;
    /// Exact gradient for the normal error; empty: normal error not measured.
    GradientFunction gradient;
    /// False: only the surface-to-mesh direction (mesh-to-surface and normal
    /// figures stay 0; `distance` may then be empty), e.g. mesh against mesh.
    bool meshToSurface = true;
};

struct SurfaceError
{
    // Mesh to surface: |distance| at every vertex and triangle centroid.
    double meshToSurfaceMean = 0.0, meshToSurfaceRms = 0.0, meshToSurfaceMax = 0.0;
    // Surface to mesh: distance from each surface point to the nearest triangle.
    double surfaceToMeshMean = 0.0, surfaceToMeshRms = 0.0, surfaceToMeshMax = 0.0;
    double mean = 0.0;      ///< over both directions' samples, voxels
    double rms = 0.0;       ///< over both directions' samples, voxels
    double hausdorff = 0.0; ///< the larger maximum of the two directions, voxels
    double normalMeanDegrees = 0.0;   ///< mean angle between mesh normals and the gradient
    double normalOver5Percent = 0.0;  ///< % of vertices whose normal is off by more than 5°
    std::size_t meshSamples = 0, surfaceSamples = 0;
};

/// Measures `mesh` against the surface `distance` = 0. O((V + T) + S·k)
/// with a uniform bucket grid over the triangles (k triangles near a point).
/// Throws strata::Error if voxelSize is not positive or distance is empty
/// (while options.meshToSurface).
SurfaceError measureSurfaceError(const TriangleMesh& mesh, const DistanceFunction& distance,
                                 const SurfaceErrorOptions& options);

/// Points on the surface `distance` = 0, about `spacing` metres apart: the
/// lattice points of [min, max] within one spacing of the surface, moved
/// onto it by Newton steps along `gradient` and kept when within 1e-6
/// spacing of it. Deterministic order.
std::vector<glm::dvec3> sampleSurface(const DistanceFunction& distance, const GradientFunction& gradient,
                                      const glm::dvec3& min, const glm::dvec3& max, double spacing);

} // namespace strata::meshing
