#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

using namespace strata::meshing;

namespace {

// Expects readLevelSet(path) to throw a strata::Error whose message names the
// file and contains `reason`.
void expectReadError(const std::filesystem::path& path, const std::string& reason)
{
    try {
        readLevelSet(path);
        FAIL() << "expected an error for " << path;
    } catch (const strata::Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.filename().string()), std::string::npos) << message;
        EXPECT_NE(message.find(reason), std::string::npos) << message;
    }
}

void writeRaw(const openvdb::GridBase::Ptr& grid, const std::filesystem::path& path)
{
    openvdb::io::File file(path.string());
    file.write({grid});
    file.close();
}

} // namespace

TEST(GridIO, LevelSetRoundTrip)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, {0.f, 0.f, 0.f}, 0.25f);
    grid->setName("surface");
    writeGrid(*grid, dir / "sphere.vdb");
    const openvdb::FloatGrid::Ptr back = readLevelSet(dir / "sphere.vdb");
    EXPECT_EQ(back->getName(), "surface");
    EXPECT_EQ(back->activeVoxelCount(), grid->activeVoxelCount());
    EXPECT_EQ(back->voxelSize(), grid->voxelSize());
    EXPECT_EQ(back->tree().getValue(openvdb::Coord(0, 0, 0)), grid->tree().getValue(openvdb::Coord(0, 0, 0)));
}

TEST(GridIO, EachBadFileHasItsOwnError)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();

    expectReadError(dir / "missing.vdb", "does not exist");

    std::ofstream(dir / "corrupt.vdb") << "definitely not an OpenVDB file";
    expectReadError(dir / "corrupt.vdb", "not a readable OpenVDB file");

    writeRaw(openvdb::Vec3SGrid::create(), dir / "vector.vdb");
    expectReadError(dir / "vector.vdb", "no float grid");

    openvdb::FloatGrid::Ptr fog = openvdb::FloatGrid::create(0.0f);
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    fog->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
    writeRaw(fog, dir / "fog.vdb");
    expectReadError(dir / "fog.vdb", "not a level set");

    openvdb::FloatGrid::Ptr empty = openvdb::FloatGrid::create(0.75f);
    empty->setGridClass(openvdb::GRID_LEVEL_SET);
    writeRaw(empty, dir / "empty.vdb");
    expectReadError(dir / "empty.vdb", "empty");
}

// Lengths and counts OpenVDB would trust are checked against the file first:
// a few changed bytes must not make the reader allocate gigabytes.
TEST(GridIO, LengthsAndCountsBeyondTheFileAreRefused)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, openvdb::Vec3f(0.0f), 0.5f);
    writeGrid(*sphere, dir / "good.vdb");
    std::ifstream in(dir / "good.vdb", std::ios::binary);
    const std::string good{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    ASSERT_NO_THROW(readLevelSet(dir / "good.vdb"));
    auto withBytes = [&](std::size_t offset, const std::string& bytes, const std::string& name) {
        std::string changed = good;
        changed.replace(offset, bytes.size(), bytes);
        std::ofstream(dir / name, std::ios::binary) << changed;
        return dir / name;
    };
    const std::size_t name = good.find("class");
    ASSERT_NE(name, std::string::npos);
    // The grid metadata's first name claims 0x7fffffff characters.
    expectReadError(withBytes(name - 4, std::string("\xff\xff\xff\x7f", 4), "long-name.vdb"),
                    "claims 2147483647 characters");
    // The grid metadata count (just before that name) claims 2^32 - 1 entries.
    expectReadError(withBytes(name - 8, std::string("\xff\xff\xff\xff", 4), "many-entries.vdb"),
                    "claims 4294967295 entries");
    // The file format version (bytes 8..11).
    expectReadError(withBytes(8, std::string("\x10\x00\x00\x00", 4), "old.vdb"), "has format version 16");
    // A string metadata value longer than the file.
    const std::size_t value = good.find("level set");
    ASSERT_NE(value, std::string::npos);
    expectReadError(withBytes(value - 4, std::string("\x00\x00\x00\x40", 4), "long-value.vdb"),
                    "is truncated or corrupt");
    // Cut anywhere in the tree.
    {
        std::ofstream(dir / "cut.vdb", std::ios::binary) << good.substr(0, good.size() * 2 / 3);
    }
    expectReadError(dir / "cut.vdb", "is truncated or corrupt");
}

TEST(GridIO, SameGridGivesSameBytes)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, {0.f, 0.f, 0.f}, 0.25f);
    writeGrid(*grid, dir / "a.vdb");
    writeGrid(*grid, dir / "b.vdb");
    auto bytes = [](const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    EXPECT_EQ(bytes(dir / "a.vdb"), bytes(dir / "b.vdb"));
    // Still a valid OpenVDB file with a well-formed UUID.
    openvdb::io::File file((dir / "a.vdb").string());
    file.open();
    const std::string uuid = file.getUniqueTag();
    EXPECT_EQ(uuid.size(), 36u);
    EXPECT_EQ(uuid[8], '-');
    EXPECT_EQ(readLevelSet(dir / "a.vdb")->activeVoxelCount(), grid->activeVoxelCount());

    auto other = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.5f, {0.f, 0.f, 0.f}, 0.25f);
    writeGrid(*other, dir / "c.vdb");
    openvdb::io::File otherFile((dir / "c.vdb").string());
    otherFile.open();
    EXPECT_NE(otherFile.getUniqueTag(), uuid);
}
