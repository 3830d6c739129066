// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// One test per reader defect of issue 17: each malformed file must give a
// BadInput strata::Error naming the file (and the element), never a hang, a
// crash, an allocation failure or a silently shortened mesh.
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/PlyIO.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <string>

#include <sys/stat.h>

using namespace strata::meshing;

namespace {

/// Writes `bytes` to dir/name and reads it with readMesh; returns the error
/// message, or "" if it read. Checks the error is BadInput naming the file.
std::string readError(const std::string& name, const std::string& bytes)
{
    const auto dir = strata::test::freshTestDir();
    const auto path = dir / name;
    std::ofstream(path, std::ios::binary) << bytes;
    try {
        readMesh(path);
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << e.what();
        EXPECT_EQ(e.place().file, path.string()) << e.what();
        EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
        return e.what();
    }
    return "";
}

bool contains(const std::string& text, const std::string& piece)
{
    return text.find(piece) != std::string::npos;
}

const std::string ASCII_PLY_HEADER = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                                     "end_header\n";

template <typename T>
void append(std::string& bytes, T value)
{
    bytes.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// A .glb from its JSON and binary chunk.
std::string makeGlb(std::string json, std::string bin)
{
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string glb = "glTF";
    append<std::uint32_t>(glb, 2);
    append<std::uint32_t>(glb, std::uint32_t(12 + 8 + json.size() + 8 + bin.size()));
    append<std::uint32_t>(glb, std::uint32_t(json.size()));
    glb += "JSON" + json;
    append<std::uint32_t>(glb, std::uint32_t(bin.size()));
    glb += std::string("BIN\0", 4) + bin;
    return glb;
}

/// A triangle: 3 float positions (36 bytes) then 3 uint32 indices (12 bytes);
/// `positionCount` and the views are the caller's.
std::string triangleGlb(int positionCount, int positionViewLength)
{
    std::string bin;
    for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(bin, v);
    for (std::uint32_t i : {0u, 1u, 2u}) append(bin, i);
    const std::string json =
        R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":48}],)"
        R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" + std::to_string(positionViewLength) +
        R"(},{"buffer":0,"byteOffset":36,"byteLength":12}],)"
        R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" + std::to_string(positionCount) +
        R"(,"type":"VEC3"},{"bufferView":1,"componentType":5125,"count":3,"type":"SCALAR"}],)"
        R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"nodes":[{"mesh":0}],)"
        R"("scenes":[{"nodes":[0]}],"scene":0})";
    return makeGlb(json, bin);
}

} // namespace

TEST(MeshReadErrors, AsciiPlyWithANonNumericTokenFailsAtOnce)
{
    // This hung `strata info` with growing memory through OpenMesh.
    const std::string message = readError("m.ply", ASCII_PLY_HEADER + "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n");
    EXPECT_TRUE(contains(message, "vertex 1: coordinate 'abc' is not a number")) << message;
    EXPECT_TRUE(contains(message, ":11:")) << message; // the line
}

TEST(MeshReadErrors, AsciiPlyWithNanOrInfCoordinateIsRejected)
{
    EXPECT_TRUE(contains(readError("m.ply", ASCII_PLY_HEADER + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n"), "vertex 2"));
    EXPECT_TRUE(contains(readError("m.ply", ASCII_PLY_HEADER + "0 0 0\n1 0 inf\n0 1 0\n3 0 1 2\n"), "not a finite"));
}

TEST(MeshReadErrors, BinaryPlyClaimingTwoBillionVerticesIsRejectedBeforeAllocating)
{
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                        "property float y\nproperty float z\nend_header\n";
    for (int i = 0; i < 9; ++i) append(bytes, 0.5f);
    const std::string message = readError("m.ply", bytes);
    EXPECT_TRUE(contains(message, "claims 2000000000")) << message;
}

TEST(MeshReadErrors, PlyFaceIndexOutOfRangeIsRejected)
{
    const std::string ascii = readError("m.ply", ASCII_PLY_HEADER + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    EXPECT_TRUE(contains(ascii, "face 0: vertex index 7 is out of range (3 vertices)")) << ascii;

    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 9; ++i) append(bytes, float(i));
    bytes += char(3);
    for (std::int32_t i : {0, -1, 2}) append(bytes, i);
    const std::string binary = readError("m.ply", bytes);
    EXPECT_TRUE(contains(binary, "face 0: vertex index -1 is out of range")) << binary;
}

TEST(MeshReadErrors, BinaryPlyThatEndsEarlyIsRejected)
{
    std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    for (int i = 0; i < 9; ++i) append(bytes, float(i));
    bytes += char(200); // a face with 200 indices, 3 present
    for (std::int32_t i : {0, 1, 2}) append(bytes, i);
    const std::string message = readError("m.ply", bytes);
    EXPECT_TRUE(contains(message, "face 0")) << message;
}

TEST(MeshReadErrors, PlyReaderReadsAsciiQuadsAndBigEndian)
{
    const TriangleMesh quad = parsePly("ply\nformat ascii 1.0\ncomment hi\nelement vertex 4\nproperty double x\n"
                                       "property double y\nproperty double z\nproperty uchar red\nelement face 1\n"
                                       "property list uchar uint vertex_indices\nend_header\n"
                                       "0 0 0 255\n1 0 0 0\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n",
                                       "q.ply");
    EXPECT_EQ(quad.vertexCount(), 4u);
    EXPECT_EQ(quad.triangleCount(), 2u);

    std::string bytes = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    auto appendBig = [&](auto value) {
        char raw[sizeof(value)];
        std::memcpy(raw, &value, sizeof(value));
        for (std::size_t i = sizeof(value); i-- > 0;) bytes += raw[i];
    };
    for (float v : {0.f, 0.f, 0.f, 2.f, 0.f, 0.f, 0.f, 3.f, 0.f}) appendBig(v);
    bytes += char(3);
    for (std::int32_t i : {0, 1, 2}) appendBig(i);
    const TriangleMesh big = parsePly(bytes, "b.ply");
    ASSERT_EQ(big.vertexCount(), 3u);
    EXPECT_EQ(big.positions[1].x, 2.0f);
    EXPECT_EQ(big.positions[2].y, 3.0f);
    EXPECT_EQ(big.indices, (std::vector<std::uint32_t>{0, 1, 2}));
}

TEST(MeshReadErrors, ObjWithBadTokensOrIndicesIsRejected)
{
    const std::string base = "# c\nv 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const std::string nonNumeric = readError("m.obj", "v 0 0 0\nv 1 abc 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_TRUE(contains(nonNumeric, ":2: vertex 2: coordinate 'abc'")) << nonNumeric;
    EXPECT_TRUE(contains(readError("m.obj", "v 0 0 nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "'nan' is not a finite number"));
    const std::string range = readError("m.obj", base + "f 1 2 4\n");
    EXPECT_TRUE(contains(range, "face 1: vertex index 4 is out of range")) << range;
    EXPECT_TRUE(contains(readError("m.obj", base + "f 1 2 0\n"), "vertex index 0"));
    EXPECT_TRUE(contains(readError("m.obj", base + "f 1 2\n"), "at least 3"));
    EXPECT_TRUE(contains(readError("m.obj", base + "f 1//5 2 3\n"), "normal index 5"));
    const TriangleMesh ok = parseObj(base + "vn 0 0 1\nf -3//1 -2//1 -1//1\n", "ok.obj");
    EXPECT_EQ(ok.triangleCount(), 1u);
    EXPECT_EQ(ok.normals.size(), 3u);
}

TEST(MeshReadErrors, OffWithBadCountsTokensOrIndicesIsRejected)
{
    EXPECT_TRUE(contains(readError("m.off", "OFF\n2000000000 1 0\n0 0 0\n"), "2000000000 vertices"));
    const std::string token = readError("m.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n");
    EXPECT_TRUE(contains(token, "vertex 1: coordinate 'x'")) << token;
    EXPECT_TRUE(contains(readError("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"), "vertex index 3 is out of range"));
    EXPECT_TRUE(contains(readError("m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n# padding\n"), "ends before face 0"));
    const TriangleMesh ok = parseOff("OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n", "ok.off");
    EXPECT_EQ(ok.triangleCount(), 1u);
}

TEST(MeshReadErrors, StlWithWrongCountNanOrGarbageIsRejected)
{
    std::string binary(80, ' ');
    append<std::uint32_t>(binary, 1000000); // claims a million triangles
    binary += std::string(50, '\0');
    EXPECT_TRUE(contains(readError("m.stl", binary), "claims 1000000 triangles"));

    std::string nan(80, ' ');
    append<std::uint32_t>(nan, 1);
    for (int i = 0; i < 3; ++i) append(nan, 0.0f);
    for (int i = 0; i < 9; ++i) append(nan, i == 4 ? std::numeric_limits<float>::quiet_NaN() : float(i));
    nan += std::string(2, '\0');
    EXPECT_TRUE(contains(readError("m.stl", nan), "triangle 0"));

    const std::string ascii = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                              "vertex 0 1 abc\nendloop\nendfacet\nendsolid t\n";
    EXPECT_TRUE(contains(readError("m.stl", ascii), "facet 0: coordinate 'abc'"));
    EXPECT_TRUE(contains(readError("m.stl", "solid t\nfacet normal 0 0 1\n"), "endsolid"));
    // Shared corners become one vertex.
    const TriangleMesh ok = parseStl("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                     "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 1 0 0\nvertex 1 1 0\n"
                                     "vertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
                                     "ok.stl");
    EXPECT_EQ(ok.triangleCount(), 2u);
    EXPECT_EQ(ok.vertexCount(), 4u);
}

TEST(MeshReadErrors, GlbAccessorOverrunningItsBufferViewIsRejected)
{
    // The sound file reads.
    EXPECT_EQ(parseGlb(triangleGlb(3, 36), "ok.glb").triangleCount(), 1u);
    // POSITION claims 4 elements in a 36-byte view: the 4th would be the index bytes next to it.
    const std::string message = readError("m.glb", triangleGlb(4, 36));
    EXPECT_TRUE(contains(message, "POSITION accessor (4 elements from offset 0) runs past its buffer view (36 bytes)"))
        << message;
    // A view that runs past the buffer.
    EXPECT_FALSE(readError("m.glb", triangleGlb(3, 4000)).empty());
}

// The GLB container is checked before tinygltf reads it: tinygltf copies a
// BIN chunk by its stated length (fuzz_glb: a heap overflow when the chunk
// claims more bytes than the file has; fuzz/corpus/glb/bin-chunk-overruns-file.glb).
TEST(MeshReadErrors, GlbChunksThatDoNotFitTheFileAreRejected)
{
    const std::string glb = triangleGlb(3, 36);
    std::string overrun = glb.substr(0, glb.size() - 8); // the BIN chunk now claims 8 bytes more than are left
    const std::uint32_t size = std::uint32_t(overrun.size());
    std::memcpy(overrun.data() + 8, &size, 4);
    const std::string binAt = std::to_string(12 + 8 + (glb.size() - 12 - 8 - 8 - 48));
    EXPECT_TRUE(contains(readError("m.glb", overrun), "m.glb: not a valid GLB file: chunk 1 at byte " + binAt +
                                                          " claims 48 bytes, the file has 40 left"))
        << readError("m.glb", overrun);
    EXPECT_TRUE(contains(readError("m.glb", glb.substr(0, glb.size() - 4)), "its header says"));
    std::string version = glb;
    version[4] = 1;
    EXPECT_TRUE(contains(readError("m.glb", version), "version 1, not 2"));
    EXPECT_TRUE(contains(readError("m.glb", "glTF"), "less than a header and one chunk"));
}

TEST(MeshReadErrors, GlbWithNanPositionOrBadIndexIsRejected)
{
    std::string glb = triangleGlb(3, 36);
    const std::size_t binStart = glb.size() - 48;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::string withNan = glb;
    std::memcpy(withNan.data() + binStart + 16, &nan, 4);
    EXPECT_TRUE(contains(readError("m.glb", withNan), "POSITION 1 is not finite"));
    std::string badIndex = glb;
    const std::uint32_t nine = 9;
    std::memcpy(badIndex.data() + binStart + 40, &nine, 4);
    EXPECT_TRUE(contains(readError("m.glb", badIndex), "index 9 is out of range"));
}

TEST(MeshReadErrors, NotARegularFileIsRejectedInsteadOfBlocking)
{
    const auto dir = strata::test::freshTestDir();
    ASSERT_EQ(::mkfifo((dir / "pipe.ply").c_str(), 0600), 0);
    try {
        readMesh(dir / "pipe.ply");
        FAIL();
    } catch (const strata::Error& e) {
        EXPECT_TRUE(contains(e.what(), "not a regular file")) << e.what();
    }
    EXPECT_THROW(readMesh(dir / "missing.ply"), strata::Error);
    EXPECT_THROW(readMesh(dir / "mesh.fbx"), strata::Error);
}
