// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/MeshMetrics.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace strata::meshing;

namespace {

// A unit cube [0,1]³, 12 triangles, counter-clockwise seen from outside.
TriangleMesh unitCube()
{
    TriangleMesh m;
    for (int i = 0; i < 8; ++i) m.positions.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    m.indices = {0, 2, 3, 0, 3, 1,  // z = 0, normal −z
                 4, 5, 7, 4, 7, 6,  // z = 1, normal +z
                 0, 1, 5, 0, 5, 4,  // y = 0, normal −y
                 2, 6, 7, 2, 7, 3,  // y = 1, normal +y
                 0, 4, 6, 0, 6, 2,  // x = 0, normal −x
                 1, 3, 7, 1, 7, 5}; // x = 1, normal +x
    return m;
}

} // namespace

TEST(MeshMetrics, CubeIsWatertightWithUnitVolume)
{
    const TriangleMesh cube = unitCube();
    const MeshTopology t = analyzeTopology(cube);
    EXPECT_EQ(t.edges, 18u);
    EXPECT_TRUE(t.watertight());
    EXPECT_EQ(t.degenerateTriangles, 0u);
    EXPECT_DOUBLE_EQ(signedVolume(cube), 1.0);
}

TEST(MeshMetrics, FlippedTriangleAndHoleAreDetected)
{
    TriangleMesh flipped = unitCube();
    std::swap(flipped.indices[1], flipped.indices[2]);
    const MeshTopology t = analyzeTopology(flipped);
    EXPECT_EQ(t.inconsistentEdges, 3u);
    EXPECT_FALSE(t.watertight());

    TriangleMesh open = unitCube();
    open.indices.resize(open.indices.size() - 3);
    EXPECT_EQ(analyzeTopology(open).boundaryEdges, 3u);

    TriangleMesh inverted = unitCube();
    for (std::size_t i = 0; i < inverted.indices.size(); i += 3) std::swap(inverted.indices[i + 1], inverted.indices[i + 2]);
    EXPECT_DOUBLE_EQ(signedVolume(inverted), -1.0);
}

TEST(MeshMetrics, DegenerateAndNonManifoldAreCounted)
{
    TriangleMesh m = unitCube();
    m.indices.insert(m.indices.end(), {0, 0, 1});          // repeated index
    m.indices.insert(m.indices.end(), {0, 2, 4});          // third triangle on edge 0-2
    const MeshTopology t = analyzeTopology(m);
    EXPECT_EQ(t.degenerateTriangles, 1u);
    EXPECT_GE(t.nonManifoldEdges, 1u);
}

TEST(MeshMetrics, FaceNormalsAreUnitAndFiniteEvenForDegenerateInput)
{
    TriangleMesh m = unitCube();
    m.positions.emplace_back(5.0f, 5.0f, 5.0f); // isolated vertex
    computeFaceNormals(m);
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    // Corner 7 = (1,1,1) averages +x, +y, +z faces.
    EXPECT_GT(m.normals[7].x, 0.3f);
    EXPECT_GT(m.normals[7].y, 0.3f);
    EXPECT_GT(m.normals[7].z, 0.3f);
    EXPECT_EQ(m.normals[8], glm::vec3(0, 1, 0));
}

TEST(MeshMetrics, WorldBoundsAddTheOrigin)
{
    TriangleMesh m = unitCube();
    m.origin = {1e6, -2.0, 3.0};
    const Bounds b = worldBounds(m);
    EXPECT_DOUBLE_EQ(b.min.x, 1e6);
    EXPECT_DOUBLE_EQ(b.max.x, 1e6 + 1.0);
    EXPECT_DOUBLE_EQ(b.min.y, -2.0);
}

TEST(MeshMetrics, NonManifoldVerticesAngleStatisticsAndDegenerateRemoval)
{
    // Two cubes touching at one corner (vertex 7 of the first is shared).
    TriangleMesh m = unitCube();
    const std::uint32_t offset = 7;
    for (int i = 0; i < 8; ++i) {
        if (i == 0) continue;
        m.positions.emplace_back(1 + (i & 1), 1 + ((i >> 1) & 1), 1 + ((i >> 2) & 1));
    }
    const TriangleMesh cube = unitCube();
    for (std::uint32_t i : cube.indices) m.indices.push_back(i == 0 ? 7 : offset + i);
    const MeshTopology t = analyzeTopology(m);
    EXPECT_EQ(t.nonManifoldVertices, 1u);
    EXPECT_EQ(t.nonManifoldEdges, 0u);
    EXPECT_TRUE(t.watertight()); // edge-manifold, but not vertex-manifold

    const AngleStatistics angles = angleStatistics(unitCube());
    EXPECT_NEAR(angles.minDegrees, 45.0, 1e-9);
    EXPECT_NEAR(angles.meanMinDegrees, 45.0, 1e-9);
    EXPECT_EQ(angles.below10Percent, 0.0);

    TriangleMesh d = unitCube();
    d.positions.emplace_back(0.5f, 0.0f, 0.0f); // on edge 0-1: zero area
    d.indices.insert(d.indices.end(), {0, 1, 8, 2, 2, 3});
    EXPECT_EQ(analyzeTopology(d).degenerateTriangles, 2u);
    EXPECT_EQ(removeDegenerateTriangles(d), 2u);
    EXPECT_EQ(d.triangleCount(), 12u);
    EXPECT_EQ(analyzeTopology(d).degenerateTriangles, 0u);
}

TEST(MeshMetrics, CountsVerticesComponentsAndEulerCharacteristic)
{
    const MeshTopology t = analyzeTopology(unitCube());
    EXPECT_EQ(t.vertices, 8u);
    EXPECT_EQ(t.triangles, 12u);
    EXPECT_EQ(t.components, 1u);
    EXPECT_EQ(t.coincidentVertices, 0u);
    EXPECT_EQ(t.eulerCharacteristic(), 2);

    // Two disjoint cubes: two components, Euler characteristic 4.
    TriangleMesh two = unitCube();
    const TriangleMesh cube = unitCube();
    for (const glm::vec3& p : cube.positions) two.positions.push_back(p + glm::vec3(5.0f, 0.0f, 0.0f));
    for (std::uint32_t i : cube.indices) two.indices.push_back(i + 8);
    const MeshTopology pair = analyzeTopology(two);
    EXPECT_EQ(pair.components, 2u);
    EXPECT_EQ(pair.eulerCharacteristic(), 4);
    EXPECT_TRUE(pair.watertight());
}

// Two cubes touching along an edge, each with its own vertices: by index
// both are closed and apart; by position the shared edge has four triangles.
TEST(MeshMetrics, CoincidentVerticesMakingANonManifoldEdgeAreDetected)
{
    TriangleMesh m = unitCube();
    const TriangleMesh cube = unitCube();
    // Second cube [1,2] x [0,1] x [1,2]: its edge x = 1, z = 1 is the first cube's.
    for (const glm::vec3& p : cube.positions) m.positions.push_back(p + glm::vec3(1.0f, 0.0f, 1.0f));
    for (std::uint32_t i : cube.indices) m.indices.push_back(i + 8);

    TopologyOptions byIndex;
    byIndex.weldByPosition = false;
    const MeshTopology unwelded = analyzeTopology(m, byIndex);
    EXPECT_EQ(unwelded.nonManifoldEdges, 0u);
    EXPECT_EQ(unwelded.components, 2u);
    EXPECT_EQ(unwelded.coincidentVertices, 2u);

    const MeshTopology welded = analyzeTopology(m); // the default
    EXPECT_EQ(welded.nonManifoldEdges, 1u);
    EXPECT_EQ(welded.components, 1u);
    EXPECT_EQ(welded.vertices, 14u);
    EXPECT_EQ(welded.coincidentVertices, 2u);
    EXPECT_FALSE(welded.watertight());
    EXPECT_EQ(welded.nonManifoldVertices, 0u); // the two fans join through the shared edge
}

// A cube whose faces have their own vertices (as an STL reader or an unwelded
// writer gives): closed once welded; -0 and +0 weld too.
TEST(MeshMetrics, SplitVerticesWeldByPosition)
{
    const TriangleMesh cube = unitCube();
    TriangleMesh split;
    for (std::uint32_t i : cube.indices) {
        glm::vec3 p = cube.positions[i];
        if (split.positions.size() % 2 == 1 && p.x == 0.0f) p.x = -0.0f;
        split.indices.push_back(std::uint32_t(split.positions.size()));
        split.positions.push_back(p);
    }
    const MeshTopology welded = analyzeTopology(split);
    EXPECT_TRUE(welded.watertight());
    EXPECT_EQ(welded.vertices, 8u);
    EXPECT_EQ(welded.edges, 18u);
    EXPECT_EQ(welded.eulerCharacteristic(), 2);
    EXPECT_EQ(welded.coincidentVertices, 36u - 8u);
    EXPECT_EQ(welded.nonManifoldVertices, 0u);

    TopologyOptions byIndex;
    byIndex.weldByPosition = false;
    const MeshTopology unwelded = analyzeTopology(split, byIndex);
    EXPECT_EQ(unwelded.boundaryEdges, 36u);
    EXPECT_EQ(unwelded.components, 12u);
}
