// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata mesh`, `strata info` and `strata bench mesh` end to end.

#include "RunStrata.h"
#include "TestDir.h"

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/MeshMetrics.h>

#include <openvdb/io/File.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numbers>

using namespace strata::meshing;

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

// A torus level set, 0.25 m voxels, written as a .vdb.
std::filesystem::path writeTorus(const std::filesystem::path& dir)
{
    const auto grid = levelSetFromShape(analyticTorus({0.1, 0.2, -0.3}, 5.0, 2.0), 0.25);
    grid->setName("surface");
    writeGrid(*grid, dir / "torus.vdb");
    return dir / "torus.vdb";
}

} // namespace

TEST(MeshCommand, EveryMesherAndFormat)
{
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    const double exact = 2.0 * std::numbers::pi * std::numbers::pi * 5.0 * 2.0 * 2.0;
    for (const std::string mesher : {"volume", "surface-nets", "dual-contouring"}) {
        for (const std::string ext : {".glb", ".ply", ".obj", ".off", ".stl"}) {
            const auto out = dir / (mesher + ext);
            const CommandResult run = runStrata("mesh " + vdb.string() + " -o " + out.string() + " --mesher " + mesher, dir);
            ASSERT_EQ(run.exitCode, 0) << run.output;
            EXPECT_TRUE(contains(run.output, "watertight")) << run.output;
            const TriangleMesh mesh = readMesh(out);
            EXPECT_GT(mesh.triangleCount(), 1000u) << out;
            EXPECT_NEAR(signedVolume(mesh) / exact, 1.0, 0.02) << out;
            if (ext != ".stl") {
                EXPECT_TRUE(analyzeTopology(mesh).watertight()) << out;
            }
        }
    }
}

TEST(MeshCommand, OptionsChangeTheMesh)
{
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    auto triangles = [&](const std::string& options) {
        const auto out = dir / "m.glb";
        const CommandResult run = runStrata("mesh " + vdb.string() + " -o " + out.string() + " " + options, dir);
        EXPECT_EQ(run.exitCode, 0) << options << "\n" << run.output;
        return readMesh(out);
    };
    const std::size_t full = triangles("--mesher volume").triangleCount();
    EXPECT_LT(triangles("--mesher volume --adaptivity 0.5").triangleCount(), full);
    EXPECT_LT(triangles("--mesher surface-nets --simplify 0.25 --max-error 0.5").triangleCount(), full / 2);
    EXPECT_LT(triangles("--mesher dual-contouring --simplify 0.25 --simplifier quadric").triangleCount(), full / 2);
    EXPECT_TRUE(triangles("--mesher surface-nets --normals none").normals.empty());
    EXPECT_EQ(triangles("--mesher surface-nets --chunk 0 --normals mesh --project 1").triangleCount(),
              triangles("--mesher surface-nets --chunk 16 --threads 1").triangleCount());
    const TriangleMesh placed = triangles("--mesher surface-nets");
    EXPECT_NE(placed.origin, glm::dvec3(0.0)); // relative to the middle of the grid
}

TEST(MeshCommand, SameBytesOnAnyThreadCount)
{
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    auto bytes = [](const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    for (const std::string mesher : {"surface-nets", "dual-contouring"}) {
        for (const char* threads : {"1", "2"}) {
            const auto out = dir / (mesher + threads + ".glb");
            const CommandResult run = runStrata("mesh " + vdb.string() + " -o " + out.string() + " --mesher " + mesher +
                                                    " --chunk 16 --threads " + threads + " -q",
                                                dir);
            ASSERT_EQ(run.exitCode, 0) << run.output;
        }
        EXPECT_EQ(bytes(dir / (mesher + "1.glb")), bytes(dir / (mesher + "2.glb"))) << mesher;
    }
}

TEST(MeshCommand, BadInputsGiveClearErrors)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    auto expectError = [&](const std::string& arguments, const std::string& reason) {
        const CommandResult run = runStrata(arguments, dir);
        EXPECT_EQ(run.exitCode, 2) << arguments << "\n" << run.output;
        EXPECT_TRUE(contains(run.output, reason)) << arguments << "\n" << run.output;
    };
    auto writeRaw = [&](const openvdb::GridBase::Ptr& grid, const std::string& name) {
        openvdb::io::File file((dir / name).string());
        file.write({grid});
        file.close();
        return (dir / name).string();
    };
    std::ofstream(dir / "corrupt.vdb") << "not an OpenVDB file";
    openvdb::FloatGrid::Ptr fog = openvdb::FloatGrid::create(0.0f);
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    fog->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
    openvdb::FloatGrid::Ptr empty = openvdb::FloatGrid::create(0.75f);
    empty->setGridClass(openvdb::GRID_LEVEL_SET);
    const std::string out = " -o " + (dir / "out.glb").string();

    expectError("mesh " + (dir / "missing.vdb").string() + out, "does not exist");
    expectError("mesh " + (dir / "corrupt.vdb").string() + out, "not a readable OpenVDB file");
    {
        // A .vdb cut short (at its header, in its tree) is refused, not read
        // on with whatever OpenVDB's variables held (which allocated GBs).
        std::ifstream in(vdb, std::ios::binary);
        const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        std::ofstream(dir / "cut-header.vdb", std::ios::binary) << bytes.substr(0, 300);
        std::ofstream(dir / "cut-tree.vdb", std::ios::binary) << bytes.substr(0, bytes.size() - 100);
    }
    expectError("mesh " + (dir / "cut-header.vdb").string() + out, "is truncated or corrupt");
    expectError("mesh " + (dir / "cut-tree.vdb").string() + out, "is truncated or corrupt");
    expectError("info " + (dir / "cut-tree.vdb").string(), "is truncated or corrupt");
    expectError("mesh " + writeRaw(openvdb::Vec3SGrid::create(), "vector.vdb") + out, "no float grid");
    expectError("mesh " + writeRaw(fog, "fog.vdb") + out, "not a level set");
    expectError("mesh " + writeRaw(empty, "empty.vdb") + out, "empty");
    expectError("mesh " + vdb.string() + " -o " + (dir / "out.fbx").string(), "unknown extension");
    // A bad output name is refused before any work, and no folder is made for it.
    expectError("mesh " + vdb.string() + " -o " + (dir / "newdir" / "out.xyz").string(),
                "cannot write mesh file '" + (dir / "newdir" / "out.xyz").string() + "': unknown extension '.xyz'");
    EXPECT_FALSE(std::filesystem::exists(dir / "newdir"));
    expectError("mesh " + (dir / "missing.vdb").string() + " -o " + (dir / "newdir" / "out.glb").string(), "does not exist");
    EXPECT_FALSE(std::filesystem::exists(dir / "newdir"));
    std::filesystem::create_directories(dir / "folder.glb");
    expectError("mesh " + vdb.string() + " -o " + (dir / "folder.glb").string(), "it is a folder");
    expectError("mesh " + vdb.string() + out + " --mesher surface-nets --adaptivity 0.5", "--adaptivity");
    expectError("mesh " + vdb.string() + out + " --mesher marching-cubes", "--mesher");
    expectError("mesh " + vdb.string() + out + " --mesher surface-nets --chunk 12", "chunk size 12");
    expectError("info " + (dir / "corrupt.vdb").string(), "not a readable OpenVDB file");
    expectError("info " + (dir / "nothing.glb").string(), "does not exist");
    EXPECT_FALSE(std::filesystem::exists(dir / "out.glb"));
}

TEST(InfoCommand, DescribesGridsAndMeshes)
{
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    const CommandResult grid = runStrata("info " + vdb.string(), dir);
    ASSERT_EQ(grid.exitCode, 0) << grid.output;
    for (const char* part : {"grid 'surface'", "float", "level set", "0.25", "active voxels", "usable by `strata mesh`"}) {
        EXPECT_TRUE(contains(grid.output, part)) << part << "\n" << grid.output;
    }
    ASSERT_EQ(runStrata("mesh " + vdb.string() + " -o " + (dir / "t.glb").string() + " --mesher surface-nets -q", dir).exitCode, 0);
    const CommandResult mesh = runStrata("info " + (dir / "t.glb").string(), dir);
    ASSERT_EQ(mesh.exitCode, 0) << mesh.output;
    for (const char* part : {"triangles", "with normals", "watertight         yes", "signed volume", "smallest angle"}) {
        EXPECT_TRUE(contains(mesh.output, part)) << part << "\n" << mesh.output;
    }
}

TEST(BenchMeshCommand, QuickRunWritesMarkdownAndCsv)
{
    const auto dir = strata::test::freshTestDir();
    const CommandResult run = runStrata("bench mesh --quick -o " + (dir / "bench").string(), dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    std::ifstream md(dir / "bench" / "mesh-bench.md"), csv(dir / "bench" / "mesh-bench.csv");
    ASSERT_TRUE(md && csv);
    const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
    for (const char* part : {"| sphere | 16 | volume a=0 | grid |", "surface-nets", "dual-contouring", "M triangles/s",
                             "ns per voxel", "volumeToMesh"}) {
        EXPECT_TRUE(contains(table, part)) << part;
    }
    std::string header;
    std::getline(csv, header);
    EXPECT_EQ(header.rfind("shape,voxels_across,voxel_size,mesher,normals,triangles,time_ms", 0), 0u) << header;
    std::size_t rows = 0;
    for (std::string line; std::getline(csv, line) && !line.empty();) ++rows;
    EXPECT_EQ(rows, 2u * 2u * 5u * 3u); // shapes x resolutions x meshers x normal methods
}

TEST(MeshCommand, MinComponentDropsSmallClosedPiecesOnly)
{
    const auto dir = strata::test::freshTestDir();
    const auto vdb = writeTorus(dir);
    // The torus is one closed piece a few metres across: kept under a 1 m
    // limit, removed under a 100 m one (and then there is nothing to write).
    const CommandResult keep =
        runStrata("mesh " + vdb.string() + " -o " + (dir / "keep.glb").string() + " --min-component 1", dir);
    ASSERT_EQ(keep.exitCode, 0) << keep.output;
    EXPECT_NE(keep.output.find("clean    0 of 1 components removed"), std::string::npos) << keep.output;
    EXPECT_NE(keep.output.find("1 components, Euler characteristic 0"), std::string::npos) << keep.output;
    EXPECT_GT(readMesh(dir / "keep.glb").triangleCount(), 100u);
    const CommandResult drop =
        runStrata("mesh " + vdb.string() + " -o " + (dir / "drop.glb").string() + " --min-component 100", dir);
    EXPECT_NE(drop.output.find("clean    1 of 1 components removed"), std::string::npos) << drop.output;
}
