// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/RemoveSmallComponents.h>
#include <strata/meshing/SurfaceNets.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace strata::meshing;

namespace {

// A cube [lo, lo + size]³ appended to `mesh`, 12 triangles, outward.
void appendCube(TriangleMesh& mesh, const glm::vec3& lo, float size)
{
    const auto base = std::uint32_t(mesh.positions.size());
    for (int i = 0; i < 8; ++i) mesh.positions.push_back(lo + size * glm::vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
    for (std::uint32_t i : {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                            2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5}) {
        mesh.indices.push_back(base + i);
    }
}

} // namespace

TEST(RemoveSmallComponents, DefaultOptionsRemoveNothing)
{
    TriangleMesh mesh;
    appendCube(mesh, glm::vec3(0.0f), 1.0f);
    appendCube(mesh, glm::vec3(5.0f), 0.001f);
    const TriangleMesh before = mesh;
    const ComponentRemoval removal = removeSmallComponents(mesh, {});
    EXPECT_EQ(removal.components, 2u);
    EXPECT_EQ(removal.removedComponents, 0u);
    EXPECT_EQ(mesh.positions, before.positions);
    EXPECT_EQ(mesh.indices, before.indices);
}

TEST(RemoveSmallComponents, RemovesTinyClosedShellsAndTheirVertices)
{
    // A 1 m cube, a 3 mm shell before it and a 2 mm shell after it; normals too.
    TriangleMesh mesh;
    appendCube(mesh, glm::vec3(-4.0f), 0.003f);
    appendCube(mesh, glm::vec3(0.0f), 1.0f);
    appendCube(mesh, glm::vec3(3.0f), 0.002f);
    mesh.positions.emplace_back(9.0f, 9.0f, 9.0f); // used by no triangle: kept
    computeFaceNormals(mesh);

    SmallComponentOptions options;
    options.minDiagonal = 0.01; // 1 cm
    const ComponentRemoval removal = removeSmallComponents(mesh, options);
    EXPECT_EQ(removal.components, 3u);
    EXPECT_EQ(removal.removedComponents, 2u);
    EXPECT_EQ(removal.removedTriangles, 24u);
    EXPECT_EQ(removal.removedVertices, 16u);
    ASSERT_EQ(mesh.positions.size(), 9u);
    ASSERT_EQ(mesh.normals.size(), 9u);
    EXPECT_EQ(mesh.triangleCount(), 12u);
    EXPECT_EQ(mesh.positions[0], glm::vec3(0.0f)); // the big cube's vertices, in order
    EXPECT_EQ(mesh.positions[8], glm::vec3(9.0f));
    const MeshTopology topology = analyzeTopology(mesh);
    EXPECT_TRUE(topology.watertight());
    EXPECT_EQ(topology.components, 1u);
    EXPECT_DOUBLE_EQ(signedVolume(mesh), 1.0);
    // The normals moved with their vertices: corner (1,1,1) points out.
    EXPECT_GT(mesh.normals[7].x, 0.3f);

    SmallComponentOptions byArea;
    byArea.minArea = 7.0; // the cube has 6 m²
    EXPECT_EQ(removeSmallComponents(mesh, byArea).removedComponents, 1u);
    EXPECT_TRUE(mesh.indices.empty());
    EXPECT_EQ(mesh.positions.size(), 1u); // only the unused vertex is left
}

// A piece cut open by a chunk border continues in the next chunk: kept
// unless closedOnly is off.
TEST(RemoveSmallComponents, OpenPiecesAreKeptByDefault)
{
    TriangleMesh mesh;
    appendCube(mesh, glm::vec3(0.0f), 0.002f);
    mesh.indices.resize(mesh.indices.size() - 3); // open
    SmallComponentOptions options;
    options.minDiagonal = 0.01;
    EXPECT_EQ(removeSmallComponents(mesh, options).removedComponents, 0u);
    EXPECT_EQ(mesh.triangleCount(), 11u);
    options.closedOnly = false;
    EXPECT_EQ(removeSmallComponents(mesh, options).removedTriangles, 11u);
    EXPECT_TRUE(mesh.positions.empty());
}

// Pieces joined only through coincident vertices (separate indices) are one
// component: welding by position, as analyzeTopology() does.
TEST(RemoveSmallComponents, WeldsByPosition)
{
    TriangleMesh mesh;
    appendCube(mesh, glm::vec3(0.0f), 0.004f);
    appendCube(mesh, glm::vec3(0.004f, 0.0f, 0.0f), 0.004f); // shares a face's corners
    SmallComponentOptions options;
    options.minDiagonal = 0.008; // each cube's diagonal is 6.9 mm, the pair's 9.8 mm
    const ComponentRemoval removal = removeSmallComponents(mesh, options);
    EXPECT_EQ(removal.components, 1u);
    EXPECT_EQ(removal.removedComponents, 0u);
}

// A real mesher's output: a sphere with specks of a few millimetres beside it.
TEST(RemoveSmallComponents, SpecksBesideASurfaceNetsSphere)
{
    const auto grid = levelSetFromShape(analyticSphere({0.0, 0.0, 0.0}, 2.0), 0.1);
    TriangleMesh mesh = surfaceNets(*grid);
    const std::size_t triangles = mesh.triangleCount();
    const double volume = signedVolume(mesh);
    appendCube(mesh, glm::vec3(3.0f), 0.004f);
    appendCube(mesh, glm::vec3(-3.0f), 0.005f);
    SmallComponentOptions options;
    options.minDiagonal = 0.05;
    const ComponentRemoval removal = removeSmallComponents(mesh, options);
    EXPECT_EQ(removal.components, 3u);
    EXPECT_EQ(removal.removedComponents, 2u);
    EXPECT_EQ(mesh.triangleCount(), triangles);
    EXPECT_TRUE(analyzeTopology(mesh).watertight());
    EXPECT_DOUBLE_EQ(signedVolume(mesh), volume);
}
