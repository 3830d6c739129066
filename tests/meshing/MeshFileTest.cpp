#include <strata/meshing/AnalyticShapes.h>
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <gtest/gtest.h>

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
        if (std::string(name) != "m.stl") { // STL stores corners per face: no shared vertices
            EXPECT_EQ(back.vertexCount(), mesh.vertexCount()) << name;
            EXPECT_TRUE(analyzeTopology(back).watertight()) << name;
        }
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
