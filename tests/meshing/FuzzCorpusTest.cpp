// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The fuzzers' seed corpora (and any crash reproducer added to them) as
// regression inputs: each file either parses or throws strata::Error.
#include <strata/Error.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/MeshFile.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using namespace strata::meshing;
namespace fs = std::filesystem;

TEST(FuzzCorpus, EveryCorpusFileParsesOrThrowsStrataError)
{
    const fs::path root = STRATA_FUZZ_CORPUS_DIR;
    for (const char* format : {"glb", "ply", "obj", "stl", "off"}) {
        std::size_t files = 0, parsed = 0;
        for (const auto& entry : fs::directory_iterator(root / format)) {
            if (!entry.is_regular_file()) continue;
            std::ifstream in(entry.path(), std::ios::binary);
            const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
            ++files;
            try {
                const TriangleMesh mesh = parseMesh(bytes, std::string(".") + format, entry.path().string());
                for (std::uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size()) << entry.path();
                EXPECT_EQ(mesh.indices.size() % 3, 0u) << entry.path();
                ++parsed;
            } catch (const strata::Error& e) {
                EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << entry.path() << ": " << e.what();
            }
        }
        EXPECT_GT(files, 0u) << format;
        EXPECT_GT(parsed, 0u) << format; // each corpus holds at least one good file
    }
}

// The .vdb reader of `strata mesh` / `strata info` on fuzz/corpus/vdb/: a
// usable level set or strata::Error (BadInput), never a crash or another
// exception.
TEST(FuzzCorpus, EveryVdbCorpusFileReadsOrThrowsStrataError)
{
    const fs::path root = STRATA_FUZZ_CORPUS_DIR;
    std::size_t files = 0, read = 0;
    for (const auto& entry : fs::directory_iterator(root / "vdb")) {
        if (!entry.is_regular_file()) continue;
        ++files;
        try {
            const openvdb::FloatGrid::Ptr grid = readLevelSet(entry.path());
            ASSERT_TRUE(grid) << entry.path();
            EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET) << entry.path();
            EXPECT_GT(grid->activeVoxelCount(), 0u) << entry.path();
            ++read;
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << entry.path() << ": " << e.what();
        }
    }
    EXPECT_GT(files, 0u);
    EXPECT_GT(read, 0u); // at least one good file
    EXPECT_LT(read, files); // and at least one bad one
}
