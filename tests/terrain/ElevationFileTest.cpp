// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// DEM files the test writes itself: NumPy .npy (each type, versions 1 to 3,
// C and Fortran order, non-finite values), .npz (stored members, zip64 as
// np.savez writes them, the member chosen), ESRI ASCII grids (corner and
// centre forms, NODATA, CRLF); and broken ones: each gives strata::Error
// naming the file (and the line for .asc), and no truncation or flipped
// byte of a valid file crashes the readers.

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/terrain/ElevationFile.h>

#include <zlib.h>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;

// ---------------------------------------------------------------------------
// Writers

void putLittle(std::string& out, std::uint64_t value, int size)
{
    for (int i = 0; i < size; ++i) out += char((value >> (8 * i)) & 0xFFu);
}

std::string int16s(const std::vector<int>& values)
{
    std::string out;
    for (int v : values) putLittle(out, std::uint16_t(std::int16_t(v)), 2);
    return out;
}

std::string int32s(const std::vector<int>& values)
{
    std::string out;
    for (int v : values) putLittle(out, std::uint32_t(v), 4);
    return out;
}

std::string float32s(const std::vector<float>& values)
{
    std::string out;
    for (float v : values) putLittle(out, std::bit_cast<std::uint32_t>(v), 4);
    return out;
}

std::string float64s(const std::vector<double>& values)
{
    std::string out;
    for (double v : values) putLittle(out, std::bit_cast<std::uint64_t>(v), 8);
    return out;
}

/// A .npy file as NumPy writes it: the dict padded with spaces to a multiple of 64 bytes, ending in '\n'.
std::string npy(const std::string& descr, const std::string& shape, const std::string& data, int version = 1,
                bool fortran = false)
{
    std::string dict =
        "{'descr': '" + descr + "', 'fortran_order': " + (fortran ? "True" : "False") + ", 'shape': " + shape + ", }";
    const std::size_t prefix = version == 1 ? 10 : 12;
    while ((prefix + dict.size() + 1) % 64 != 0) dict += ' ';
    dict += '\n';
    std::string out("\x93NUMPY", 6);
    out += char(version);
    out += char(0);
    putLittle(out, dict.size(), version == 1 ? 2 : 4);
    return out + dict + data;
}

struct Member
{
    std::string name;
    std::string data;
    int method = 0; ///< 0 stored, 8 deflated (with zlib), anything else written as is (raw bytes)
    bool brokenDeflate = false; ///< method 8 labelled on raw bytes
    std::uint64_t claimedSize = 0; ///< the unpacked size written in the zip64 fields (0: the real one)
};

/// Raw deflate (no zlib header), as zip members hold it.
std::string deflateRaw(const std::string& data)
{
    z_stream s{};
    deflateInit2(&s, 9, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
    std::string out(deflateBound(&s, uLong(data.size())), '\0');
    s.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    s.avail_in = uInt(data.size());
    s.next_out = reinterpret_cast<Bytef*>(out.data());
    s.avail_out = uInt(out.size());
    deflate(&s, Z_FINISH);
    out.resize(s.total_out);
    deflateEnd(&s);
    return out;
}

/// A zip archive of `members`; `zip64` writes it as np.savez does (Python's
/// zipfile with force_zip64: zip64 extra fields) plus zip64 end records.
std::string zip(const std::vector<Member>& members, bool zip64 = false)
{
    std::string out, directory;
    for (const Member& m : members) {
        const std::uint64_t offset = out.size();
        const std::uint32_t crc = std::uint32_t(::crc32(0L, reinterpret_cast<const Bytef*>(m.data.data()), uInt(m.data.size())));
        const std::string packed = m.method == 8 && !m.brokenDeflate ? deflateRaw(m.data) : m.data;
        std::string extra;
        if (zip64) {
            putLittle(extra, 1, 2);
            putLittle(extra, 16, 2);
            putLittle(extra, m.claimedSize ? m.claimedSize : m.data.size(), 8);
            putLittle(extra, packed.size(), 8);
        }
        const std::uint64_t size32 = zip64 ? 0xFFFFFFFFu : m.data.size();
        const std::uint64_t packed32 = zip64 ? 0xFFFFFFFFu : packed.size();
        out += std::string("PK\x03\x04", 4);
        putLittle(out, zip64 ? 45 : 20, 2); // version needed
        putLittle(out, 0, 2);               // flags
        putLittle(out, std::uint64_t(m.method), 2);
        putLittle(out, 0, 4); // time, date
        putLittle(out, crc, 4);
        putLittle(out, packed32, 4);
        putLittle(out, size32, 4);
        putLittle(out, m.name.size(), 2);
        putLittle(out, extra.size(), 2);
        out += m.name + extra + packed;

        std::string centralExtra;
        if (zip64) {
            putLittle(centralExtra, 1, 2);
            putLittle(centralExtra, 24, 2);
            putLittle(centralExtra, m.claimedSize ? m.claimedSize : m.data.size(), 8);
            putLittle(centralExtra, packed.size(), 8);
            putLittle(centralExtra, offset, 8);
        }
        directory += std::string("PK\x01\x02", 4);
        putLittle(directory, zip64 ? 45 : 20, 2); // made by
        putLittle(directory, zip64 ? 45 : 20, 2); // needed
        putLittle(directory, 0, 2);
        putLittle(directory, std::uint64_t(m.method), 2);
        putLittle(directory, 0, 4);
        putLittle(directory, crc, 4);
        putLittle(directory, packed32, 4);
        putLittle(directory, size32, 4);
        putLittle(directory, m.name.size(), 2);
        putLittle(directory, centralExtra.size(), 2);
        putLittle(directory, 0, 2); // comment
        putLittle(directory, 0, 2); // disk
        putLittle(directory, 0, 2); // internal attributes
        putLittle(directory, 0, 4); // external attributes
        putLittle(directory, zip64 ? 0xFFFFFFFFu : offset, 4);
        directory += m.name + centralExtra;
    }
    const std::uint64_t directoryOffset = out.size();
    out += directory;
    if (zip64) {
        const std::uint64_t record = out.size();
        out += std::string("PK\x06\x06", 4);
        putLittle(out, 44, 8);
        putLittle(out, 45, 2);
        putLittle(out, 45, 2);
        putLittle(out, 0, 4);
        putLittle(out, 0, 4);
        putLittle(out, members.size(), 8);
        putLittle(out, members.size(), 8);
        putLittle(out, directory.size(), 8);
        putLittle(out, directoryOffset, 8);
        out += std::string("PK\x06\x07", 4);
        putLittle(out, 0, 4);
        putLittle(out, record, 8);
        putLittle(out, 1, 4);
    }
    out += std::string("PK\x05\x06", 4);
    putLittle(out, 0, 2);
    putLittle(out, 0, 2);
    putLittle(out, zip64 ? 0xFFFF : members.size(), 2);
    putLittle(out, zip64 ? 0xFFFF : members.size(), 2);
    putLittle(out, zip64 ? 0xFFFFFFFFu : directory.size(), 4);
    putLittle(out, zip64 ? 0xFFFFFFFFu : directoryOffset, 4);
    putLittle(out, 0, 2);
    return out;
}

/// The error message of parsing `bytes` (empty if it parsed).
std::string errorOf(const std::string& bytes, const std::string& name = "dem.bin")
{
    try {
        parseElevationFile(bytes, name);
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << e.what();
        EXPECT_EQ(e.place().file, name);
        return e.what();
    }
    return {};
}

#define EXPECT_ERROR(bytes, expected)                                                                                  \
    do {                                                                                                               \
        const std::string message_ = errorOf(bytes);                                                                   \
        EXPECT_NE(message_.find(expected), std::string::npos) << "message: '" << message_ << "'";                      \
        EXPECT_EQ(message_.rfind("dem.bin", 0), 0u) << message_;                                                       \
    } while (0)

const std::vector<double> SIX = {101.0, -7.0, 3.0, 32767.0, -32768.0, 0.0};

// ---------------------------------------------------------------------------
// Valid files

TEST(ElevationFile, NpyOfEachType)
{
    const std::vector<int> ints = {101, -7, 3, 32767, -32768, 0};
    for (const std::string& bytes : {npy("<i2", "(2, 3)", int16s(ints)), npy("<i4", "(2, 3)", int32s(ints), 2),
                                     npy("<f4", "(2, 3)", float32s({101.f, -7.f, 3.f, 32767.f, -32768.f, 0.f}), 3),
                                     npy("<f8", "(2,3)", float64s(SIX))}) {
        const ElevationGrid grid = parseElevationFile(bytes, "dem.npy");
        EXPECT_EQ(grid.format, "npy");
        EXPECT_EQ(grid.width, 3);
        EXPECT_EQ(grid.height, 2);
        EXPECT_EQ(grid.heights, SIX);
        EXPECT_EQ(grid.cellSize, 0.0);
        EXPECT_EQ(grid.noDataCells, 0u);
        EXPECT_TRUE(grid.member.empty());
    }
    // int32 beyond the int16 range.
    EXPECT_EQ(parseElevationFile(npy("<i4", "(1, 2)", int32s({2000000000, -2000000000})), "a").heights,
              (std::vector<double>{2e9, -2e9}));
}

TEST(ElevationFile, NpyFortranOrderAndNonFiniteValues)
{
    // Fortran order stores column by column: [[1, 2, 3], [4, 5, 6]] is 1 4 2 5 3 6.
    const ElevationGrid fortran = parseElevationFile(npy("<f8", "(2, 3)", float64s({1, 4, 2, 5, 3, 6}), 1, true), "f");
    EXPECT_EQ(fortran.heights, (std::vector<double>{1, 2, 3, 4, 5, 6}));

    const ElevationGrid holes =
        parseElevationFile(npy("<f4", "(2, 2)", float32s({1.0f, NAN, INFINITY, 4.0f})), "holes.npy");
    EXPECT_EQ(holes.noDataCells, 2u);
    EXPECT_EQ(holes.heights[0], 1.0);
    EXPECT_TRUE(std::isnan(holes.heights[1]));
    EXPECT_TRUE(std::isnan(holes.heights[2]));
    EXPECT_EQ(holes.heights[3], 4.0);
}

TEST(ElevationFile, NpzPicksTheElevationMember)
{
    const std::string elevation = npy("<i2", "(2, 3)", int16s({101, -7, 3, 32767, -32768, 0}));
    const std::string mask = npy("<f8", "(2, 2)", float64s({0, 1, 1, 0}));
    const std::string dx = npy("<f8", "()", float64s({0.000833}));
    for (bool zip64 : {false, true}) {
        const ElevationGrid grid =
            parseElevationFile(zip({{"mask.npy", mask}, {"elevation.npy", elevation}, {"dx.npy", dx}}, zip64), "d.npz");
        EXPECT_EQ(grid.format, "npz");
        EXPECT_EQ(grid.member, "elevation.npy");
        EXPECT_EQ(grid.width, 3);
        EXPECT_EQ(grid.heights, SIX);
        EXPECT_EQ(grid.cellSize, 0.0);
    }
    // No 'elevation': the only 2D array (scalars and 1D arrays do not count;
    // a deflated scalar beside it does not matter).
    const std::string line = npy("<f8", "(4,)", float64s({1, 2, 3, 4}));
    const ElevationGrid only =
        parseElevationFile(zip({{"dx.npy", dx}, {"heights.npy", elevation}, {"x.npy", line}}), "only.npz");
    EXPECT_EQ(only.member, "heights.npy");
    EXPECT_EQ(only.heights, SIX);
}

TEST(ElevationFile, EsriAsciiGrid)
{
    const std::string text = "ncols 3\nNROWS 2\nxllcorner 500000.5\nyllcorner -20\ncellsize 30\n"
                             "NODATA_value -9999\n101 -7 3\n32767 -32768 -9999\n";
    const ElevationGrid grid = parseElevationFile(text, "dem.asc");
    EXPECT_EQ(grid.format, "asc");
    EXPECT_EQ(grid.width, 3);
    EXPECT_EQ(grid.height, 2);
    EXPECT_EQ(grid.cellSize, 30.0);
    EXPECT_EQ(grid.lowerLeft.x, 500000.5);
    EXPECT_EQ(grid.lowerLeft.y, -20.0);
    EXPECT_EQ(grid.noDataCells, 1u);
    EXPECT_EQ(grid.heights[0], 101.0);
    EXPECT_EQ(grid.heights[4], -32768.0);
    EXPECT_TRUE(std::isnan(grid.heights[5]));

    // Centre form, dx/dy, CRLF, values wrapped over lines, no NODATA, no final newline.
    const ElevationGrid centre = parseElevationFile(
        "NCOLS\t2\r\nnrows 2\r\nxllcenter 10\r\nyllcenter 20\r\ndx 2.5\r\ndy 2.5\r\n1.5 2e1\r\n-3\r\n+4", "c.asc");
    EXPECT_EQ(centre.cellSize, 2.5);
    EXPECT_EQ(centre.lowerLeft.x, 10.0 - 1.25);
    EXPECT_EQ(centre.lowerLeft.y, 20.0 - 1.25);
    EXPECT_EQ(centre.heights, (std::vector<double>{1.5, 20.0, -3.0, 4.0}));
    EXPECT_EQ(centre.noDataCells, 0u);
}

TEST(ElevationFile, ReadsFromDiskAndNamesMissingFiles)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path path = dir / "dem.npz";
    {
        std::ofstream out(path, std::ios::binary);
        out << zip({{"elevation.npy", npy("<f8", "(2, 3)", float64s(SIX))}});
    }
    EXPECT_EQ(readElevationFile(path).heights, SIX);
    try {
        readElevationFile(dir / "missing.asc");
        FAIL() << "no error";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing.asc"), std::string::npos) << e.what();
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
    }
    EXPECT_THROW(readElevationFile(dir), strata::Error);
}

// ---------------------------------------------------------------------------
// Broken files

TEST(ElevationFile, BrokenNpyNamesTheProblem)
{
    const std::string good = npy("<i2", "(2, 3)", int16s({1, 2, 3, 4, 5, 6}));
    EXPECT_ERROR("", "empty");
    EXPECT_ERROR(std::string("\x93NUMPY\x01", 7), "not a NumPy");
    std::string version = good;
    version[6] = 9;
    EXPECT_ERROR(version, "version 9");
    std::string length = good;
    length[8] = char(0xFF), length[9] = char(0xFF);
    EXPECT_ERROR(length, "more than the file holds");
    EXPECT_ERROR(npy(">i2", "(2, 3)", int16s({1, 2, 3, 4, 5, 6})), "'>i2' is not supported");
    EXPECT_ERROR(npy("<c16", "(1, 1)", std::string(16, '\0')), "'<c16' is not supported");
    EXPECT_ERROR(npy("<i2", "(1, 2, 3)", int16s({1, 2, 3, 4, 5, 6})), "shape (1, 2, 3)");
    EXPECT_ERROR(npy("<i2", "(6,)", int16s({1, 2, 3, 4, 5, 6})), "shape (6,)");
    EXPECT_ERROR(npy("<i2", "(0, 5)", ""), "empty");
    EXPECT_ERROR(good.substr(0, good.size() - 1), "needs 6 x 2 bytes");
    EXPECT_ERROR(good + "x", "needs 6 x 2 bytes");
    // A huge shape over a few bytes: refused before anything is allocated.
    EXPECT_ERROR(npy("<f8", "(2147483647, 2147483647)", float64s({1.0})), "4611686014132420609 cells, more than the");
    EXPECT_ERROR(npy("<f8", "(4, 4)", float64s({1.0})), "needs 16 x 8 bytes");
    EXPECT_ERROR(npy("<f8", "(2147483648, 1)", ""), "larger than 2147483647");
    EXPECT_ERROR(npy("<f8", "(99999999999999999999999, 1)", ""), "larger than 2147483647");
    EXPECT_ERROR(npy("<f8", "[2, 3]", ""), "'shape' must be a tuple");
    EXPECT_ERROR(npy("<f8", "(two, 3)", ""), "must hold integers");

    // Header dicts NumPy would not write.
    auto header = [](const std::string& dict) {
        std::string out("\x93NUMPY\x01\x00", 8);
        putLittle(out, dict.size(), 2);
        return out + dict;
    };
    EXPECT_ERROR(header("{'descr': '<i2', 'shape': (1, 1), }"), "lacks 'fortran_order'");
    EXPECT_ERROR(header("{'descr': '<i2', 'fortran_order': Maybe, 'shape': (1, 1)}"), "True or False");
    EXPECT_ERROR(header("{'descr': '<i2', 'fortran_order': False, 'shape': (1, 1), 'x': 1}"), "unknown key 'x'");
    EXPECT_ERROR(header("{'descr: '<i2'"), "expected ':'");
    EXPECT_ERROR(header("{'descr': '<i2"), "unterminated");
    EXPECT_ERROR(header("['descr']"), "expected '{'");
    EXPECT_ERROR(header("{'descr': '<i2' 'x'}"), "expected ',' or '}'");
}

TEST(ElevationFile, BrokenNpzNamesTheProblem)
{
    const std::string elevation = npy("<i2", "(2, 3)", int16s({1, 2, 3, 4, 5, 6}));
    const std::string good = zip({{"elevation.npy", elevation}});

    // np.savez_compressed and the matplotlib sample DEM: deflated members
    // are inflated (and the same grid comes out); a broken stream is named.
    for (bool zip64 : {false, true}) {
        const ElevationGrid inflated = parseElevationFile(zip({{"elevation.npy", elevation, 8}}, zip64), "z.npz");
        EXPECT_EQ(inflated.heights, parseElevationFile(good, "g.npz").heights);
    }
    Member broken{"elevation.npy", elevation, 8, true};
    EXPECT_ERROR(zip({broken}), "not valid deflate data");
    EXPECT_ERROR(zip({{"elevation.npy", elevation, 12}}), "compression method 12");

    EXPECT_ERROR(zip({{"a.npy", elevation}, {"b.npy", elevation}}), "several 2D arrays (a.npy, b.npy)");
    EXPECT_ERROR(zip({{"dx.npy", npy("<f8", "()", float64s({1.0}))}}), "no 2D array (arrays: dx.npy)");
    EXPECT_ERROR(zip({{"readme.txt", "hello"}}), "no .npy member");
    EXPECT_ERROR(zip({}), "no .npy member");

    std::string corrupt = good;
    corrupt[30 + 13 + 20] ^= 0x01; // a byte of the member's header text
    EXPECT_ERROR(corrupt, "CRC-32");
    EXPECT_ERROR(good.substr(0, good.size() - 1), "no end of central directory");
    std::string outside = good;
    outside[good.size() - 3] = char(0x7F); // the directory offset's high byte: far past the end
    EXPECT_ERROR(outside, "outside the file");
    std::string encrypted = good;
    encrypted[6] = 1; // local flags do not matter; the central directory's do
    encrypted[good.size() - 22 - (46 + 13) + 8] = 1;
    EXPECT_ERROR(encrypted, "encrypted");
}

TEST(ElevationFile, NpzMembersThatClaimMoreThanTheyHoldAreRefusedBeforeInflating)
{
    // Seen in a review: a member of exactly 2^32 bytes passed the size check
    // and its CRC was taken over 0 bytes (zlib counts in 32 bits).
    const std::string elevation = npy("<i2", "(2, 3)", int16s({1, 2, 3, 4, 5, 6}));
    Member four{"elevation.npy", elevation, 8};
    four.claimedSize = std::uint64_t(1) << 32;
    EXPECT_ERROR(zip({four}, true), "claims 4294967296 bytes");
    four.claimedSize = (std::uint64_t(1) << 32) - 1; // more than 1032 times its packed bytes
    EXPECT_ERROR(zip({four}, true), "claims 4294967295 bytes, more than it can hold");
    four.claimedSize = 20000; // possible, but its stream ends long before
    EXPECT_ERROR(zip({four}, true), "not valid deflate data of 20000 bytes");

    // A header claiming a grid over the cap, or a size its member does not
    // have, is refused from the header alone (the member is not inflated).
    // These name the member after the file.
    const auto refusal = [](const std::string& bytes) {
        try {
            parseElevationFile(bytes, "dem.npz");
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << e.what();
            return std::string(e.what());
        }
        return std::string("(read)");
    };
    const std::string big = npy("<f8", "(16384, 16385)", float64s({1.0}));
    for (const char* member : {"elevation.npy", "heights.npy"}) {
        const std::string message = refusal(zip({{member, big, 8}}));
        EXPECT_EQ(message.rfind("dem.npz member '" + std::string(member) + "'", 0), 0u) << message;
        EXPECT_NE(message.find("268451840 cells, more than the 268435456"), std::string::npos) << message;
    }
    Member lying{"elevation.npy", npy("<f8", "(1000, 1000)", float64s({1.0, 2.0})), 8};
    EXPECT_NE(refusal(zip({lying})).find("needs 1000000 x 8 bytes, the file holds 16 after the header"),
              std::string::npos)
        << refusal(zip({lying}));
    // Several deflated members: each is looked into by its header only, and
    // the chosen one is read whole (its CRC checked).
    const ElevationGrid grid =
        parseElevationFile(zip({{"x.npy", npy("<f8", "(3,)", float64s({1.0, 2.0, 3.0})), 8}, {"h.npy", elevation, 8}}),
                           "two.npz");
    EXPECT_EQ(grid.member, "h.npy");
    EXPECT_EQ(grid.heights.size(), 6u);
}

TEST(ElevationFile, BrokenAsciiGridNamesFileAndLine)
{
    const std::string head = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n";
    EXPECT_ERROR("nrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2\n", "lacks 'ncols'");
    EXPECT_ERROR("ncols 2\nnrows 1\nyllcorner 0\ncellsize 10\n1 2\n", "lacks 'xllcorner' (or 'xllcenter')");
    EXPECT_ERROR("ncols 2\nnrows 1\nxllcorner 0\nyllcorner 0\n1 2\n", "lacks 'dx'");
    EXPECT_ERROR("ncols 0\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n",
                 "dem.bin:1: 'ncols' must be a whole number");
    EXPECT_ERROR("ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n", "dem.bin:1:");
    EXPECT_ERROR("ncols 3\nnrows 3e9\n", "dem.bin:2: 'nrows' must be a whole number");
    EXPECT_ERROR("ncols 3\nnrows 2\ncolour red\n", "dem.bin:3: 'colour' is not an ESRI ASCII grid header key");
    EXPECT_ERROR("ncols 3\nnrows 2\nNCOLS 3\n", "dem.bin:3: 'ncols' is given twice");
    EXPECT_ERROR("ncols 3\nnrows\n2\n", "dem.bin:2: 'nrows' needs a finite number");
    EXPECT_ERROR("ncols 3\nnrows nan\n", "dem.bin:2: 'nrows' needs a finite number on its line, not 'nan'");
    EXPECT_ERROR("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -10\n1 2 3 4 5 6",
                 "dem.bin:5: the cell size must be > 0");
    EXPECT_ERROR("ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ndx 1\ndy 2\n1", "dem.bin:6: 'dx' 1 and 'dy' 2 differ");
    EXPECT_ERROR("ncols 1\nnrows 1\nxllcorner 0\nxllcenter 0\nyllcorner 0\ncellsize 1\n1",
                 "either 'xllcorner' or 'xllcenter'");
    EXPECT_ERROR(head + "1 2 3\n4 five 6\n", "dem.bin:7: 'five' is not a number (value 5 of 6)");
    EXPECT_ERROR(head + "1 2 3\n4 1e999 6\n", "dem.bin:7: '1e999' is not a number");
    EXPECT_ERROR(head + "1 2 3\n4 5\n", "the grid ends after 5 values");
    EXPECT_ERROR(head + "1 2 3\n4 5 6\n\n7\n", "dem.bin:9: more values than");
    // A huge grid in a small file: refused before anything is allocated.
    EXPECT_ERROR("ncols 2147483647\nnrows 2147483647\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
                 "4611686014132420609 cells, more than the 268435456");
    EXPECT_ERROR("ncols 16384\nnrows 16384\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n", "cannot fit");
    EXPECT_ERROR(std::string("ncols 1\0", 8), "not a DEM file");
    EXPECT_ERROR("just text", "'just' is not an ESRI ASCII grid header key");
}

/// Every truncation and every single flipped byte of a valid file either
/// parses or throws strata::Error: nothing else (no crash, no other exception).
void expectRobust(const std::string& good, const char* what)
{
    std::size_t parsed = 0, refused = 0;
    auto attempt = [&](const std::string& bytes) {
        try {
            const ElevationGrid grid = parseElevationFile(bytes, "fuzz");
            EXPECT_EQ(grid.heights.size(), std::size_t(grid.width) * std::size_t(grid.height));
            ++parsed;
        } catch (const strata::Error&) {
            ++refused;
        }
    };
    for (std::size_t n = 0; n < good.size(); ++n) attempt(good.substr(0, n));
    for (std::size_t i = 0; i < good.size(); ++i) {
        for (int bit : {0x01, 0x80, 0xFF}) {
            std::string bytes = good;
            bytes[i] = char(bytes[i] ^ bit);
            attempt(bytes);
        }
    }
    EXPECT_GT(refused, 0u) << what;
    EXPECT_GT(parsed, 0u) << what;
}

TEST(ElevationFile, TruncatedOrFlippedBytesNeverCrash)
{
    const std::string elevation = npy("<f4", "(3, 4)", float32s({1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}));
    expectRobust(elevation, "npy");
    expectRobust(npy("<i2", "(2, 2)", int16s({1, 2, 3, 4}), 3, true), "npy v3");
    expectRobust(zip({{"dx.npy", npy("<f8", "()", float64s({1.0}))}, {"elevation.npy", elevation}}), "npz");
    expectRobust(zip({{"elevation.npy", elevation}}, true), "npz zip64");
    expectRobust("ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -1\n1 2 3\n4 -1 6\n", "asc");
}

} // namespace

TEST(ElevationFile, EveryFuzzCorpusFileReadsOrThrowsStrataError)
{
    // fuzz/corpus/elevation/: the fuzzer's seeds (each format, stored and
    // deflated) and any crash reproducer added to it, replayed in every build.
    std::size_t files = 0, read = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(STRATA_FUZZ_CORPUS_DIR) / "elevation")) {
        if (!entry.is_regular_file()) continue;
        ++files;
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        try {
            const ElevationGrid grid = parseElevationFile(bytes, entry.path().string());
            EXPECT_EQ(grid.heights.size(), std::size_t(grid.width) * std::size_t(grid.height)) << entry.path();
            ++read;
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << entry.path() << ": " << e.what();
        }
    }
    EXPECT_GE(files, 5u);
    EXPECT_GE(read, 5u); // the seeds are all valid
}
