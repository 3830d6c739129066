#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridToMesh.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <fstream>

using namespace strata::meshing;

namespace {

TriangleMesh sphereMesh(const glm::dvec3& origin = glm::dvec3(0.0))
{
    openvdb::initialize();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {0.5f, 1.0f, 1.5f}, 0.25f);
    GridToMeshOptions options;
    options.origin = origin;
    return gridToMesh(*grid, options);
}

std::size_t filesIn(const std::filesystem::path& dir)
{
    return std::size_t(std::distance(std::filesystem::directory_iterator(dir), {}));
}

} // namespace

TEST(GltfIO, GlbRoundTripIsExact)
{
    const auto dir = strata::test::freshTestDir();
    const TriangleMesh mesh = sphereMesh({10.0, 20.0, -30.0});
    writeGlb(mesh, dir / "sphere.glb");

    // A binary glTF starts with the magic "glTF" and version 2.
    std::ifstream in(dir / "sphere.glb", std::ios::binary);
    char header[8] = {};
    in.read(header, 8);
    EXPECT_EQ(std::string(header, 4), "glTF");
    EXPECT_EQ(header[4], 2);

    const TriangleMesh back = readGltf(dir / "sphere.glb");
    EXPECT_EQ(back.indices, mesh.indices);
    ASSERT_EQ(back.positions.size(), mesh.positions.size());
    ASSERT_EQ(back.normals.size(), mesh.normals.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        EXPECT_EQ(back.positions[i], mesh.positions[i]);
        EXPECT_EQ(back.normals[i], mesh.normals[i]);
    }
    EXPECT_EQ(back.origin, mesh.origin);
    EXPECT_EQ(filesIn(dir), 1u) << "no temporary file may be left behind";
}

TEST(GltfIO, UnwritableTargetThrowsAndLeavesNothing)
{
    const auto dir = strata::test::freshTestDir();
    EXPECT_THROW(writeGlb(sphereMesh(), dir / "missing-dir" / "a.glb"), strata::Error);
    EXPECT_EQ(filesIn(dir), 0u);
}

TEST(GltfIO, BadFilesGiveErrorsNamingThePath)
{
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream(dir / "garbage.glb") << "this is not a glTF file";
    }
    try {
        readGltf(dir / "garbage.glb");
        FAIL() << "expected strata::Error";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("garbage.glb"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readGltf(dir / "does-not-exist.glb"), strata::Error);
}
