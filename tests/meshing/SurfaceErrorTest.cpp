// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/meshing/SurfaceNets.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace strata::meshing;

TEST(SurfaceError, ExactForAKnownOffset)
{
    // A sphere meshed at radius 5 measured against radius 5.1: every mesh
    // sample is about 0.1 m (0.4 voxel at 0.25 m) from the surface.
    const auto grid = levelSetFromShape(analyticSphere({0, 0, 0}, 5.0), 0.25);
    const TriangleMesh mesh = surfaceNets(*grid);
    const auto bigger = analyticSphere({0, 0, 0}, 5.1);
    SurfaceErrorOptions options;
    options.voxelSize = 0.25;
    options.surfacePoints = sampleSurface(bigger.distance, bigger.gradient, bigger.min - 0.5, bigger.max + 0.5, 0.25);
    options.gradient = bigger.gradient;
    const SurfaceError e = measureSurfaceError(mesh, bigger.distance, options);
    EXPECT_GT(e.surfaceSamples, 1000u);
    EXPECT_EQ(e.meshSamples, mesh.vertexCount() + mesh.triangleCount());
    EXPECT_NEAR(e.meshToSurfaceMean, 0.4, 0.05);
    EXPECT_NEAR(e.surfaceToMeshMean, 0.4, 0.05);
    EXPECT_GE(e.hausdorff, e.rms);
    EXPECT_GE(e.rms, e.mean);
    EXPECT_LT(e.normalMeanDegrees, 2.0);
    EXPECT_LT(e.normalOver5Percent, 1.0);
}

TEST(SurfaceError, SamplesLieOnTheSurface)
{
    const auto torus = analyticTorus({0.5, 0, 0}, 3.0, 1.0);
    const auto points = sampleSurface(torus.distance, torus.gradient, torus.min - 0.5, torus.max + 0.5, 0.2);
    ASSERT_GT(points.size(), 500u);
    for (const glm::dvec3& p : points) EXPECT_LT(std::abs(torus.distance(p)), 1e-6);
}

TEST(SurfaceError, FindsAMissingPiece)
{
    // Drop a patch of triangles: the surface-to-mesh direction sees the hole.
    const auto shape = analyticSphere({0, 0, 0}, 4.0);
    const auto grid = levelSetFromShape(shape, 0.25);
    TriangleMesh mesh = surfaceNets(*grid);
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        if (mesh.positions[mesh.indices[t]].y > 3.5f) continue;
        kept.insert(kept.end(), mesh.indices.begin() + t, mesh.indices.begin() + t + 3);
    }
    mesh.indices = kept;
    SurfaceErrorOptions options;
    options.voxelSize = 0.25;
    options.surfacePoints = sampleSurface(shape.distance, shape.gradient, shape.min - 0.5, shape.max + 0.5, 0.25);
    const SurfaceError e = measureSurfaceError(mesh, shape.distance, options);
    EXPECT_LT(e.meshToSurfaceMax, 0.2);
    EXPECT_GT(e.surfaceToMeshMax, 2.0);
    EXPECT_EQ(e.hausdorff, e.surfaceToMeshMax);
    EXPECT_THROW(measureSurfaceError(mesh, shape.distance, SurfaceErrorOptions{0.0, {}, {}}), strata::Error);
}
