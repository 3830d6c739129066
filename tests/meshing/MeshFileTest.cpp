// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

using namespace strata::meshing;

TEST(MeshFile, EveryFormatReadsBack)
{
    const auto dir = strata::test::freshTestDir();
    const auto grid = levelSetFromShape(analyticSphere({100.0, 0.0, 0.0}, 3.0), 0.25);
    ChunkMeshOptions options;
    options.origin = {100.0, 0.0, 0.0};
    const TriangleMesh mesh = surfaceNets(*grid, options);
    const double volume = signedVolume(mesh);
    for (const char* name : {"m.glb", "m.ply", "m.obj", "m.off", "m.stl", "UPPER.OBJ"}) {
        writeMeshFile(mesh, dir / name);
        const TriangleMesh back = readMesh(dir / name);
        EXPECT_EQ(back.triangleCount(), mesh.triangleCount()) << name;
        const Bounds a = worldBounds(mesh), b = worldBounds(back);
        EXPECT_NEAR(a.min.x, b.min.x, 1e-4) << name;
        EXPECT_NEAR(a.max.y, b.max.y, 1e-4) << name;
        // STL stores corners per face (no shared vertices): welding by
        // position in analyzeTopology() still finds the mesh closed.
        if (std::string(name) != "m.stl") {
            EXPECT_EQ(back.vertexCount(), mesh.vertexCount()) << name;
        }
        EXPECT_TRUE(analyzeTopology(back).watertight()) << name;
        // Volume is translation invariant for a closed mesh.
        EXPECT_NEAR(signedVolume(back), volume, 1e-3 * volume) << name;
    }
    EXPECT_EQ(readMesh(dir / "m.glb").origin, mesh.origin);
}

TEST(MeshFile, UnknownExtensionAndMissingFileAreErrors)
{
    const auto dir = strata::test::freshTestDir();
    TriangleMesh mesh;
    try {
        writeMeshFile(mesh, dir / "mesh.fbx");
        FAIL();
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find(".fbx"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readMesh(dir / "missing.glb"), strata::Error);
    EXPECT_THROW(readMesh(dir / "missing.obj"), strata::Error);
}

namespace {

// Same float bits (so -0 differs from +0 and a NaN is caught).
bool sameBits(const glm::vec3& a, const glm::vec3& b)
{
    return std::memcmp(&a, &b, sizeof(glm::vec3)) == 0;
}

// The positions the text and STL writers store: world metres in float.
std::vector<glm::vec3> worldFloats(const TriangleMesh& mesh)
{
    std::vector<glm::vec3> world;
    for (const glm::vec3& p : mesh.positions) world.emplace_back(glm::vec3(mesh.origin + glm::dvec3(p)));
    return world;
}

// The same triangles in the same order, each possibly starting at another corner.
bool sameTriangles(const TriangleMesh& a, const TriangleMesh& b)
{
    if (a.indices.size() != b.indices.size()) return false;
    for (std::size_t t = 0; t < a.indices.size(); t += 3) {
        bool same = false;
        for (int r = 0; r < 3 && !same; ++r) {
            same = a.indices[t] == b.indices[t + r] && a.indices[t + 1] == b.indices[t + (r + 1) % 3] &&
                   a.indices[t + 2] == b.indices[t + (r + 2) % 3];
        }
        if (!same) return false;
    }
    return true;
}

} // namespace

// A small sphere 1 km from the origin with 2 cm voxels: six significant
// digits (1000.12) are coarser than the vertex spacing, so a writer that
// rounds to them collapses vertices into zero-area triangles.
TEST(MeshFile, PositionsAndNormalsReadBackBitIdentical)
{
    const auto dir = strata::test::freshTestDir();
    const glm::dvec3 centre(1000.0, 0.0, 0.0);
    const auto grid = levelSetFromShape(analyticSphere(centre, 0.5), 0.02);
    ChunkMeshOptions options;
    options.origin = centre;
    const TriangleMesh mesh = surfaceNets(*grid, options);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    const std::vector<glm::vec3> world = worldFloats(mesh);
    TriangleMesh worldMesh = mesh; // what the writers store: world floats
    worldMesh.positions = world;
    worldMesh.origin = glm::dvec3(0.0);
    // Float itself (6e-5 m apart at 1 km) flattens a few slivers; the
    // writers must add none (six digits flattened hundreds).
    const std::size_t degenerate = analyzeTopology(worldMesh).degenerateTriangles;
    EXPECT_LT(degenerate, mesh.triangleCount() / 100);
    for (const char* name : {"m.obj", "m.off", "m.ply"}) {
        writeMeshFile(mesh, dir / name);
        const TriangleMesh back = readMesh(dir / name);
        ASSERT_EQ(back.vertexCount(), mesh.vertexCount()) << name;
        ASSERT_EQ(back.normals.size(), mesh.normals.size()) << name;
        std::size_t differing = 0, differingNormals = 0;
        for (std::size_t i = 0; i < world.size(); ++i) {
            differing += sameBits(back.positions[i], world[i]) ? 0 : 1;
            differingNormals += sameBits(back.normals[i], mesh.normals[i]) ? 0 : 1;
        }
        EXPECT_EQ(differing, 0u) << name;
        EXPECT_EQ(differingNormals, 0u) << name;
        EXPECT_TRUE(sameTriangles(back, mesh)) << name;
        EXPECT_EQ(analyzeTopology(back).degenerateTriangles, degenerate) << name;
    }
}

// Binary STL stores floats: every triangle corner reads back exact. OpenMesh's
// reader drops zero-area triangles, so the sphere has none: off the voxel
// lattice (a pole on a lattice point gives coincident surface nets vertices).
TEST(MeshFile, StlCornersReadBackBitIdentical)
{
    const auto dir = strata::test::freshTestDir();
    const glm::dvec3 centre(10.003, -3.007, 0.5011);
    ChunkMeshOptions options;
    options.origin = centre;
    const TriangleMesh mesh = surfaceNets(*levelSetFromShape(analyticSphere(centre, 0.5), 0.02), options);
    const std::vector<glm::vec3> world = worldFloats(mesh);
    TriangleMesh worldMesh = mesh;
    worldMesh.positions = world;
    ASSERT_EQ(analyzeTopology(worldMesh).degenerateTriangles, 0u);
    writeMeshFile(mesh, dir / "m.stl");
    const TriangleMesh stl = readMesh(dir / "m.stl");
    ASSERT_EQ(stl.triangleCount(), mesh.triangleCount());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        differing += sameBits(stl.positions[stl.indices[i]], world[mesh.indices[i]]) ? 0 : 1;
    }
    EXPECT_EQ(differing, 0u);
}

// STL has no shared vertices; the checks weld by position, so a closed mesh
// reads back closed, with the same Euler characteristic, and the index-only
// view sees every edge as boundary.
TEST(MeshFile, StlRoundTripOfAClosedMeshHasNoBoundaryEdges)
{
    const auto dir = strata::test::freshTestDir();
    const auto grid = levelSetFromShape(analyticTorus({0.1, 0.2, -0.3}, 3.0, 1.2), 0.25);
    const TriangleMesh mesh = surfaceNets(*grid);
    const MeshTopology original = analyzeTopology(mesh);
    ASSERT_TRUE(original.watertight());
    writeMeshFile(mesh, dir / "torus.stl");
    const TriangleMesh back = readMesh(dir / "torus.stl");

    const MeshTopology welded = analyzeTopology(back);
    EXPECT_EQ(welded.boundaryEdges, 0u);
    EXPECT_EQ(welded.nonManifoldEdges, 0u);
    EXPECT_EQ(welded.inconsistentEdges, 0u);
    EXPECT_EQ(welded.vertices, original.vertices);
    EXPECT_EQ(welded.edges, original.edges);
    EXPECT_EQ(welded.components, 1u);
    EXPECT_EQ(welded.eulerCharacteristic(), 0); // a torus

    if (back.vertexCount() == 3 * back.triangleCount()) { // the reader did not merge corners
        TopologyOptions byIndex;
        byIndex.weldByPosition = false;
        const MeshTopology unwelded = analyzeTopology(back, byIndex);
        EXPECT_EQ(unwelded.boundaryEdges, unwelded.edges);
        EXPECT_EQ(unwelded.components, back.triangleCount());
        EXPECT_GT(welded.coincidentVertices, 0u);
    }
}

TEST(MeshFile, GlbIsNamedAfterTheFileOrTheOption)
{
    const auto dir = strata::test::freshTestDir();
    const TriangleMesh mesh = surfaceNets(*levelSetFromShape(analyticSphere({0.0, 0.0, 0.0}, 2.0), 0.25));
    writeMeshFile(mesh, dir / "cave.glb");
    MeshFileOptions named;
    named.name = "island";
    writeMeshFile(mesh, dir / "other.glb", named);
    // readGltf() does not return names: look for the JSON strings.
    auto contains = [](const std::filesystem::path& path, const std::string& text) {
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), {});
        return bytes.find(text) != std::string::npos;
    };
    EXPECT_TRUE(contains(dir / "cave.glb", "\"name\":\"cave\""));
    EXPECT_TRUE(contains(dir / "other.glb", "\"name\":\"island\""));
    EXPECT_FALSE(contains(dir / "other.glb", "\"name\":\"other\""));
}
