// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>

#include <openvdb/io/Stream.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <set>

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

namespace {

std::string fileBytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A level set sphere with one active root-level tile far from it (origin
/// (4096·3, 4096·5, −4096·7), value 1.25): root tiles are what the
/// preflight checks byte by byte.
openvdb::FloatGrid::Ptr sphereWithRootTile()
{
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, {0.f, 0.f, 0.f}, 0.25f);
    grid->tree().addTile(3, openvdb::Coord(4096 * 3, 4096 * 5, -4096 * 7), 1.25f, true);
    return grid;
}

/// The bytes of a root tile record (origin, value, active) as written.
template <typename T> std::string tileRecord(const openvdb::Coord& origin, T value, bool active)
{
    std::string record(reinterpret_cast<const char*>(origin.asPointer()), 3 * sizeof(std::int32_t));
    record.append(reinterpret_cast<const char*>(&value), sizeof(T));
    record.push_back(active ? '\1' : '\0');
    return record;
}

} // namespace

// The preflight follows what OpenVDB reads, as far as the root node's tiles,
// for every registered grid type, transform, half floats, instances and
// streams: every valid file still reads, with its root tiles.
TEST(GridIO, ValidFilesOfEveryKindStillRead)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    const openvdb::Coord far(4096 * 3, 4096 * 5, -4096 * 7);
    openvdb::GridPtrVec grids;
    auto add = [&](openvdb::GridBase::Ptr grid, const std::string& name, openvdb::math::Transform::Ptr transform) {
        grid->setName(name);
        grid->setTransform(transform);
        grids.push_back(grid);
    };
    auto level = sphereWithRootTile();
    add(level, "level", openvdb::math::Transform::createLinearTransform(0.5));
    auto half = sphereWithRootTile();
    half->setSaveFloatAsHalf(true);
    add(half, "half", openvdb::math::Transform::createLinearTransform(0.25));
    auto instance = level->copyGrid(); // shares the tree: written as an instance
    auto moved = openvdb::math::Transform::createLinearTransform(0.5);
    moved->postTranslate(openvdb::Vec3d(5, 6, 7)); // a uniform scale and translation
    add(instance, "instance", moved);
    auto doubles = openvdb::DoubleGrid::create(-1.0);
    doubles->tree().addTile(3, far, 2.5, true);
    doubles->tree().setValue(openvdb::Coord(1, 2, 3), 7.0);
    add(doubles, "double", std::make_shared<openvdb::math::Transform>(std::make_shared<openvdb::math::ScaleTranslateMap>(
                               openvdb::Vec3d(1, 2, 3), openvdb::Vec3d(4, 5, 6))));
    auto bools = openvdb::BoolGrid::create(false);
    bools->tree().addTile(3, far, true, false);
    bools->tree().setValue(openvdb::Coord(1, 2, 3), true);
    auto rotation = openvdb::math::Transform::createLinearTransform(1.0);
    rotation->preRotate(0.5, openvdb::math::Y_AXIS); // an affine map
    add(bools, "bool", rotation);
    auto vectors = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.f));
    vectors->tree().addTile(3, far, openvdb::Vec3s(1.f, 2.f, 3.f), true);
    add(vectors, "vec3s", openvdb::math::Transform::createFrustumTransform(
                              openvdb::BBoxd(openvdb::Vec3d(0), openvdb::Vec3d(10)), 0.5, 4.0, 1.0));
    auto ints = openvdb::Int64Grid::create(3);
    ints->tree().addTile(3, far, 9, true);
    add(ints, "int64", std::make_shared<openvdb::math::Transform>(
                           std::make_shared<openvdb::math::TranslationMap>(openvdb::Vec3d(5, 6, 7))));
    auto int32s = openvdb::Int32Grid::create(0);
    int32s->tree().addTile(3, far, 4, true);
    add(int32s, "int32", std::make_shared<openvdb::math::Transform>(
                             std::make_shared<openvdb::math::UnitaryMap>(openvdb::Vec3d(0, 0, 1), 0.5)));
    auto masks = openvdb::MaskGrid::create();
    masks->tree().addTile(3, far, true, true);
    add(masks, "mask", std::make_shared<openvdb::math::Transform>(
                              std::make_shared<openvdb::math::ScaleMap>(openvdb::Vec3d(1, 2, 3)))); // a scale map

    std::vector<std::string> transforms;
    for (const auto& grid : grids) transforms.push_back(grid->transform().mapType());
    const std::set<std::string> kinds(transforms.begin(), transforms.end());
    // Transform's constructor turns a translation into a uniform scale and
    // translation and a unitary map into an affine one: no writer stores those two.
    EXPECT_EQ(kinds, (std::set<std::string>{"AffineMap", "NonlinearFrustumMap", "ScaleMap", "ScaleTranslateMap",
                                            "UniformScaleMap", "UniformScaleTranslateMap"}));
    // Bool and mask grids are skipped unread through a file's grid offsets
    // (their trees hold bools OpenVDB reads unchecked); a stream has none.
    openvdb::GridPtrVec readable;
    std::vector<std::string> readableTransforms;
    for (std::size_t i = 0; i < grids.size(); ++i) {
        if (grids[i]->getName() == "bool" || grids[i]->getName() == "mask") continue;
        readable.push_back(grids[i]);
        readableTransforms.push_back(transforms[i]);
    }
    namespace io = openvdb::io;
    for (const std::uint32_t compression : std::vector<std::uint32_t>{
             io::COMPRESS_NONE, io::COMPRESS_ZIP, io::COMPRESS_BLOSC, io::COMPRESS_ACTIVE_MASK,
             io::COMPRESS_ZIP | io::COMPRESS_ACTIVE_MASK, io::COMPRESS_BLOSC | io::COMPRESS_ACTIVE_MASK})
    for (const bool seekable : {true, false}) {
        SCOPED_TRACE((seekable ? "file, compression " : "stream, compression ") + std::to_string(compression));
        const auto path = dir / ((seekable ? "all-" : "stream-") + std::to_string(compression) + ".vdb");
        if (seekable) {
            openvdb::io::File file(path.string());
            file.setCompression(compression);
            file.write(grids);
            file.close();
        } else {
            std::ofstream out(path, std::ios::binary);
            openvdb::io::Stream stream(out);
            stream.setCompression(compression);
            stream.write(readable);
        }
        const VdbFile back = readVdbFile(path);
        ASSERT_EQ(back.grids->size(), readable.size());
        for (std::size_t i = 0; i < readable.size(); ++i) {
            const openvdb::GridBase& read = *(*back.grids)[i];
            EXPECT_EQ(read.getName(), readable[i]->getName());
            EXPECT_EQ(read.activeVoxelCount(), readable[i]->activeVoxelCount()) << read.getName();
            EXPECT_EQ(read.transform().mapType(), readableTransforms[i]) << read.getName();
        }
        ASSERT_EQ(back.unread.size(), seekable ? 2u : 0u);
        if (seekable) {
            EXPECT_EQ(back.unread[0].name, "bool");
            EXPECT_EQ(back.unread[0].type, "Tree_bool_5_4_3");
            EXPECT_EQ(back.unread[1].name, "mask");
            EXPECT_EQ(back.unread[1].type, "Tree_mask_5_4_3");
        }
        EXPECT_EQ(readLevelSet(path)->activeVoxelCount(), level->activeVoxelCount());
    }
    {
        // A stream records no grid offsets: a mask grid there cannot be skipped.
        std::ofstream out(dir / "stream-mask.vdb", std::ios::binary);
        openvdb::io::Stream(out).write({level, masks});
    }
    expectReadError(dir / "stream-mask.vdb", "grid 1 ('mask', Tree_mask_5_4_3) is of a kind Strata does not read");
    // Only unread grids: the level-set reader says what it found.
    openvdb::io::File onlyBools((dir / "bools.vdb").string());
    onlyBools.write({bools});
    onlyBools.close();
    expectReadError(dir / "bools.vdb", "holds no float grid (found 'Tree_bool_5_4_3', not read)");
}

// An instance of a skipped grid is skipped with it (it shares that tree).
TEST(GridIO, AnInstanceOfASkippedGridIsSkipped)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    auto bools = openvdb::BoolGrid::create(false);
    bools->setName("bools");
    bools->tree().setValue(openvdb::Coord(1, 2, 3), true);
    auto copy = bools->copyGrid(); // shares the tree: written as an instance
    copy->setName("copy");
    auto level = sphereWithRootTile();
    level->setName("level");
    openvdb::io::File file((dir / "instance.vdb").string());
    file.write({bools, copy, level});
    file.close();
    const VdbFile back = readVdbFile(dir / "instance.vdb");
    ASSERT_EQ(back.grids->size(), 1u);
    EXPECT_EQ((*back.grids)[0]->getName(), "level");
    ASSERT_EQ(back.unread.size(), 2u);
    EXPECT_EQ(back.unread[0].name, "bools");
    EXPECT_EQ(back.unread[1].name, "copy");
}

// OpenVDB's RootNode::readTopology reads a root tile's active byte (and a bool
// grid's tile value) straight into a bool: a byte other than 0 or 1 is
// undefined behaviour (UBSan: "load of value 2, which is not a valid value for
// type 'bool'"), so the preflight refuses it, naming the file and the byte.
TEST(GridIO, ARootTileWhoseBoolIsNotZeroOrOneIsRefused)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    const openvdb::Coord far(4096 * 3, 4096 * 5, -4096 * 7);
    {
        writeRaw(sphereWithRootTile(), dir / "tile.vdb");
        std::string bytes = fileBytes(dir / "tile.vdb");
        const std::string record = tileRecord(far, 1.25f, true);
        const std::size_t at = bytes.find(record);
        ASSERT_NE(at, std::string::npos);
        ASSERT_EQ(bytes.find(record, at + 1), std::string::npos);
        EXPECT_NO_THROW(readLevelSet(dir / "tile.vdb"));
        bytes[at + record.size() - 1] = '\2';
        std::ofstream(dir / "active-2.vdb", std::ios::binary) << bytes;
        expectReadError(dir / "active-2.vdb", "grid 0's root tile 0 active flag at byte " +
                                                  std::to_string(at + record.size() - 1) + " is 2, not a bool");
    }
    {
        // A grid after the first one; a bool grid, checked to its root
        // tiles, then skipped unread.
        auto bools = openvdb::BoolGrid::create(false);
        bools->tree().addTile(3, far, true, false);
        openvdb::io::File file((dir / "two.vdb").string());
        file.write({sphereWithRootTile(), bools});
        file.close();
    }
    std::string bytes = fileBytes(dir / "two.vdb");
    const std::string record = tileRecord(far, true, false);
    const std::size_t at = bytes.find(record, bytes.find(tileRecord(far, 1.25f, true)) + 1);
    ASSERT_NE(at, std::string::npos);
    EXPECT_EQ(readVdbFile(dir / "two.vdb").unread.size(), 1u);
    bytes[at + record.size() - 2] = '\x7f'; // the tile's value
    std::ofstream(dir / "value-127.vdb", std::ios::binary) << bytes;
    expectReadError(dir / "value-127.vdb", "grid 1's root tile 0 value at byte " +
                                                std::to_string(at + record.size() - 2) + " is 127, not a bool");
}

// The fuzz_vdb findings in fuzz/corpus/vdb/, refused before OpenVDB reads
// the bytes: root tiles whose active byte is 49 (UBSan in
// RootNode::readTopology), and a blosc block whose byte count says 2^44
// (ASan: bloscFromStream allocates it).
TEST(GridIO, TheFuzzersFindingsAreRefused)
{
    const std::filesystem::path corpus = std::filesystem::path(STRATA_FUZZ_CORPUS_DIR) / "vdb";
    expectReadError(corpus / "root-tile-active-not-a-bool.vdb", "grid 0's root node at byte 567 claims 13874 tiles");
    expectReadError(corpus / "blosc-block-size-allocation.vdb", "claims 17592186044416 compressed bytes");
    // DelayedLoadMetadata::readValue allocates its blocks' byte counts (here
    // 2^32 − 1) whatever the metadata's size says (libFuzzer: out-of-memory).
    expectReadError(corpus / "delayed-load-block-size-allocation.vdb", "reads past its");
    // Made by hand: a leaf's blosc block stored raw with a byte count of
    // -4096 for a 32-byte buffer (ASan: heap-buffer-overflow, a 4096-byte
    // write in bloscFromStream).
    expectReadError(corpus / "blosc-raw-overflow.vdb", "grid 0's leaf 0 values at byte 9971 holds 4096 uncompressed bytes, not 32");
}

// A leaf's values stored uncompressed in a compressed file: a negative byte
// count that is not the leaf's size. OpenVDB 10 reads that many bytes into
// the leaf's buffer before it compares the two (blosc) or allocates nothing
// and fails (zip): refused first either way.
TEST(GridIO, ABlockLargerThanItsNodeIsRefused)
{
    openvdb::initialize();
    const auto dir = strata::test::freshTestDir();
    auto grid = openvdb::FloatGrid::create(0.5f); // not a level set: OpenVDB zips no level set
    // 8 active values of 512, all different: zlib cannot shrink their 32 bytes.
    const float values[8] = {-0.031f, -0.117f, -0.229f, -0.303f, -0.389f, -0.421f, -0.457f, -0.499f};
    for (int i = 0; i < 8; ++i) grid->tree().setValue(openvdb::Coord(i, 0, 0), values[i]);
    {
        openvdb::io::File file((dir / "leaf.vdb").string());
        file.setCompression(openvdb::io::COMPRESS_ZIP | openvdb::io::COMPRESS_ACTIVE_MASK);
        file.write({grid});
        file.close();
    }
    std::string bytes = fileBytes(dir / "leaf.vdb");
    EXPECT_NO_THROW(readVdbFile(dir / "leaf.vdb"));
    // The leaf's eight active floats, stored raw: -32, then 32 bytes.
    const std::int64_t raw = -32;
    const std::string count(reinterpret_cast<const char*>(&raw), sizeof(raw));
    const std::size_t at = bytes.rfind(count);
    ASSERT_NE(at, std::string::npos);
    const std::int64_t larger = -4096;
    bytes.replace(at, sizeof(larger), reinterpret_cast<const char*>(&larger), sizeof(larger));
    std::ofstream(dir / "overflow.vdb", std::ios::binary) << bytes;
    expectReadError(dir / "overflow.vdb", "holds 4096 uncompressed bytes, not 32");
}
