#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <fstream>

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
