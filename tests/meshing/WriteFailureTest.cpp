// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Every mesh and grid writer under a file size limit (a full disk, as far as
// the writer can tell): the write must fail with an I/O error naming the
// file, the file that was there must be byte-identical afterwards, and no
// temporary may be left.
#include "ChildProcess.h"
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshFile.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <iterator>

#include <sys/resource.h>

using namespace strata::meshing;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Runs `write` in a child limited to `bytes` per file; 0 if it threw an Io
/// strata::Error naming `target`.
template <typename WriteFn>
int writeUnderSizeLimit(const fs::path& target, WriteFn write, rlim_t bytes = 4096)
{
    const int status = strata::test::runInChild([&] {
        std::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{bytes, bytes};
        if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) return 2;
        try {
            write();
        } catch (const strata::Error& e) {
            const bool named = std::string(e.what()).find(target.string()) != std::string::npos;
            return e.kind() == strata::ErrorKind::Io && named ? 0 : 4;
        }
        return 3; // the write claimed success
    });
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

} // namespace

TEST(WriteFailure, FullDiskNeverLeavesATruncatedMeshOrGrid)
{
    const auto dir = strata::test::freshTestDir();
    openvdb::initialize();
    const auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {0.f, 0.f, 0.f}, 0.1f);
    const TriangleMesh mesh = gridToMesh(*grid); // computed before fork: thread pools stay in the parent
    const TriangleMesh small = [] {
        TriangleMesh m;
        m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
        m.indices = {0, 1, 2};
        return m;
    }();

    for (const char* name : {"m.glb", "m.ply", "m.obj", "m.stl", "m.off"}) {
        const fs::path target = dir / name;
        writeMeshFile(small, target); // the good file, well under the limit
        const std::string good = slurp(target);
        ASSERT_FALSE(good.empty());
        EXPECT_EQ(writeUnderSizeLimit(target, [&] { writeMeshFile(mesh, target); }), 0) << name;
        EXPECT_EQ(slurp(target), good) << name;
        EXPECT_EQ(readMesh(target).triangleCount(), 1u) << name;
    }
    const fs::path vdb = dir / "g.vdb";
    const auto tiny = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(1.0f, {0.f, 0.f, 0.f}, 0.5f);
    writeGrid(*tiny, vdb);
    const std::string good = slurp(vdb);
    const rlim_t limit = good.size() + 4096;
    EXPECT_EQ(writeUnderSizeLimit(vdb, [&] { writeGrid(*grid, vdb); }, limit), 0);
    EXPECT_EQ(slurp(vdb), good);

    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().find(".partial"), std::string::npos) << entry.path();
        ++files;
    }
    EXPECT_EQ(files, 6u);
}
