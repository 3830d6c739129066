// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace strata::meshing;

namespace {

openvdb::FloatGrid::Ptr sphereGrid(float radius, const openvdb::Vec3f& center, float voxelSize)
{
    openvdb::initialize();
    return openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, center, voxelSize, 3.0f);
}

} // namespace

TEST(GridToMesh, SphereIsClosedOutwardAndHasTheRightVolume)
{
    // 64 voxels across the diameter.
    const float radius = 8.0f, voxelSize = 0.25f;
    const TriangleMesh mesh = gridToMesh(*sphereGrid(radius, {1.0f, 2.0f, 3.0f}, voxelSize));

    ASSERT_GT(mesh.triangleCount(), 1000u);
    const MeshTopology topology = analyzeTopology(mesh);
    EXPECT_EQ(topology.boundaryEdges, 0u);
    EXPECT_EQ(topology.nonManifoldEdges, 0u);
    EXPECT_EQ(topology.inconsistentEdges, 0u);
    EXPECT_TRUE(topology.watertight());

    const double exact = 4.0 / 3.0 * std::numbers::pi * std::pow(double(radius), 3.0);
    const double volume = signedVolume(mesh);
    EXPECT_GT(volume, 0.0) << "triangles must wind counter-clockwise seen from outside";
    EXPECT_NEAR(volume / exact, 1.0, 0.01);
}

TEST(GridToMesh, GridNormalsPointOutwardAndAreUnit)
{
    const glm::vec3 center(1.0f, 2.0f, 3.0f);
    const TriangleMesh mesh = gridToMesh(*sphereGrid(5.0f, {center.x, center.y, center.z}, 0.2f));
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
    double worstDegrees = 0.0;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f);
        const glm::vec3 exact = glm::normalize(mesh.positions[i] - center);
        const double angle = std::acos(std::clamp(double(glm::dot(exact, mesh.normals[i])), -1.0, 1.0));
        worstDegrees = std::max(worstDegrees, angle * 180.0 / std::numbers::pi);
    }
    EXPECT_LT(worstDegrees, 5.0);
}

TEST(GridToMesh, OriginIsSubtractedInDoublePrecision)
{
    // A sphere far from the origin, stored relative to a nearby origin.
    const openvdb::Vec3f center(1.0e5f, 0.0f, -1.0e5f);
    GridToMeshOptions options;
    options.origin = glm::dvec3(1.0e5, 0.0, -1.0e5);
    const TriangleMesh mesh = gridToMesh(*sphereGrid(4.0f, center, 0.25f), options);
    ASSERT_FALSE(mesh.positions.empty());
    for (const glm::vec3& p : mesh.positions) {
        EXPECT_NEAR(glm::length(p), 4.0f, 0.25f);
    }
    const Bounds bounds = worldBounds(mesh);
    EXPECT_NEAR(bounds.min.x, 1.0e5 - 4.0, 0.3);
    EXPECT_NEAR(bounds.max.z, -1.0e5 + 4.0, 0.3);
}

TEST(GridToMesh, AdaptivityReducesTrianglesAndStaysClosed)
{
    auto grid = sphereGrid(6.0f, {0, 0, 0}, 0.2f);
    GridToMeshOptions adaptive;
    adaptive.adaptivity = 0.5;
    const TriangleMesh uniform = gridToMesh(*grid);
    const TriangleMesh merged = gridToMesh(*grid, adaptive);
    EXPECT_LT(merged.triangleCount(), uniform.triangleCount());
    EXPECT_GT(signedVolume(merged), 0.0);
}

TEST(GridToMesh, IsDeterministic)
{
    auto grid = sphereGrid(6.0f, {0.3f, 0.1f, -0.2f}, 0.2f);
    const TriangleMesh a = gridToMesh(*grid);
    const TriangleMesh b = gridToMesh(*grid);
    EXPECT_EQ(a.indices, b.indices);
    ASSERT_EQ(a.positions.size(), b.positions.size());
    EXPECT_EQ(0, std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)));
}

TEST(GridToMesh, RejectsBadOptions)
{
    auto grid = sphereGrid(2.0f, {0, 0, 0}, 0.5f);
    GridToMeshOptions options;
    options.adaptivity = 1.5;
    EXPECT_THROW(gridToMesh(*grid, options), strata::Error);
    options.adaptivity = std::nan("");
    EXPECT_THROW(gridToMesh(*grid, options), strata::Error);
    options.adaptivity = 0.0;
    options.isovalue = INFINITY;
    EXPECT_THROW(gridToMesh(*grid, options), strata::Error);
}

TEST(GridToMesh, EmptyGridGivesEmptyMesh)
{
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.5f);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    const TriangleMesh mesh = gridToMesh(*grid);
    EXPECT_EQ(mesh.triangleCount(), 0u);
    EXPECT_EQ(mesh.vertexCount(), 0u);
}

TEST(GridToMesh, TorusAndBoxAreWatertightWithTheRightVolume)
{
    // 64 voxels across, like the chunk meshers' tests.
    for (const AnalyticShape& shape : {analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5),
                                       analyticBox({-7.93, -5.1, -6.37}, {8.04, 5.77, 6.11})}) {
        const TriangleMesh mesh = gridToMesh(*levelSetFromShape(shape, 0.25));
        EXPECT_TRUE(analyzeTopology(mesh).watertight()) << shape.name;
        EXPECT_NEAR(signedVolume(mesh) / shape.volume, 1.0, 0.01) << shape.name;
    }
}

TEST(GridToMesh, SurfaceBetweenVoxelsPastTheBandIsClosed)
{
    // A field far steeper than 1 per metre (beds' contacts under a ledge):
    // a 12³ block of rock whose every voxel, and the air around it, lies
    // past the band (±background, inactive), with one active voxel on its
    // top. The surface crosses only between inactive voxels, or between an
    // active and an inactive one: volumeToMesh alone meshed nothing of it
    // but the corner of the active voxel (slits at 0.25 m in canyon2k).
    openvdb::initialize();
    const float background = 0.75f;
    const openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(0.25));
    auto accessor = grid->getAccessor();
    for (int x = -2; x < 14; ++x)
        for (int y = -2; y < 14; ++y)
            for (int z = -2; z < 14; ++z) {
                const bool rock = x >= 0 && x < 12 && y >= 0 && y < 12 && z >= 0 && z < 12;
                accessor.setValueOff({x, y, z}, rock ? -background : background);
            }
    accessor.setValueOn({5, 12, 5}, 0.3f);

    const TriangleMesh mesh = gridToMesh(*grid);
    ASSERT_GT(mesh.triangleCount(), 6u * 12u * 12u);
    EXPECT_TRUE(analyzeTopology(mesh).watertight());
    // The block is 12 voxels (3 m) on a side; the surface lies between
    // voxel centres, half a voxel out of the rock's: 3.0 m³, a little more
    // for the active voxel's bump and the bevelled edges' inward cut.
    EXPECT_NEAR(signedVolume(mesh), 27.0, 27.0 * 0.1);
}
