// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/PlyIO.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <fstream>

using namespace strata::meshing;

TEST(PlyIO, BinaryPlyRoundTripKeepsGeometryAndTopology)
{
    const auto dir = strata::test::freshTestDir();
    openvdb::initialize();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {0.f, 0.f, 0.f}, 0.2f);
    const TriangleMesh mesh = gridToMesh(*grid);
    writePly(mesh, dir / "sphere.ply");

    std::ifstream in(dir / "sphere.ply", std::ios::binary);
    std::string magic, format, encoding;
    in >> magic >> format >> encoding;
    EXPECT_EQ(magic, "ply");
    EXPECT_EQ(encoding, "binary_little_endian");

    const TriangleMesh back = readMeshFile(dir / "sphere.ply");
    EXPECT_EQ(back.vertexCount(), mesh.vertexCount());
    EXPECT_EQ(back.triangleCount(), mesh.triangleCount());
    EXPECT_TRUE(analyzeTopology(back).watertight());
    EXPECT_NEAR(signedVolume(back), signedVolume(mesh), 1e-3);
    ASSERT_EQ(back.normals.size(), back.positions.size());
}

TEST(PlyIO, NonManifoldFacesAreKept)
{
    // Three triangles sharing one edge: OpenMesh cannot attach the third.
    TriangleMesh fan;
    fan.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    fan.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4};
    const auto dir = strata::test::freshTestDir();
    writePly(fan, dir / "fan.ply");
    EXPECT_EQ(readMeshFile(dir / "fan.ply").triangleCount(), 3u);
}

TEST(PlyIO, MissingFileThrows)
{
    EXPECT_THROW(readMeshFile("/nonexistent/mesh.ply"), strata::Error);
}
