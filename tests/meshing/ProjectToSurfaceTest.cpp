// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/ProjectToSurface.h>

#include <openvdb/tools/Interpolation.h>

#include <gtest/gtest.h>

using namespace strata::meshing;

TEST(ProjectToSurface, VolumeToMeshVerticesLandOnTheGridSurface)
{
    const double voxel = 0.25;
    const auto grid = levelSetFromShape(analyticTorus({0.1, 0.2, 0.3}, 4.0, 1.5), voxel);
    GridToMeshOptions options;
    options.adaptivity = 0.5;
    const TriangleMesh before = gridToMesh(*grid, options);
    options.projectionSteps = 2;
    const TriangleMesh after = gridToMesh(*grid, options);
    ASSERT_EQ(before.vertexCount(), after.vertexCount());
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
    auto residual = [&](const TriangleMesh& mesh) {
        double sum = 0.0;
        for (const glm::vec3& p : mesh.positions) sum += std::abs(sampler.wsSample(openvdb::Vec3d(p.x, p.y, p.z)));
        return sum / double(mesh.vertexCount()) / voxel;
    };
    EXPECT_LT(residual(after), 0.2 * residual(before));
    EXPECT_TRUE(analyzeTopology(after).watertight());
}
