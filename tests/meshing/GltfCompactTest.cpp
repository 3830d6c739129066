// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfCompact.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridToMesh.h>

#include <openvdb/tools/LevelSetSphere.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <set>

using namespace strata::meshing;

namespace {

constexpr double STEP = 1.0 / 256.0;

/// A sphere of radius 3 m (about 2000 vertices) with normals and made-up
/// surface, landform and rock attributes, relative to `origin`.
TriangleMesh sphereMesh(const glm::dvec3& origin)
{
    openvdb::initialize();
    auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(3.0f, {0.5f, 1.0f, 1.5f}, 0.25f);
    GridToMeshOptions options;
    options.origin = origin;
    TriangleMesh mesh = gridToMesh(*grid, options);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        mesh.surface.emplace_back(0.5f + 0.1f * p.x, 0.25f * p.y);
        mesh.landform.emplace_back(3.0f + p.x, 0.01f * p.y, 1e-3f * p.z, float(i % 7) / 6.0f);
        mesh.rock.emplace_back(0.25f + 0.01f * p.y, float(i % 5));
    }
    return mesh;
}

nlohmann::json glbJson(const std::string& bytes)
{
    std::uint32_t length;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, length));
}

/// A triangle as its three corners' world grid points, rotated so the
/// smallest comes first (the index codec may rotate a triangle; the winding stays).
using Corner = std::array<long long, 3>;
long long gridRound(double x) { return (long long)std::floor(x + 0.5); }
using Triangle = std::array<Corner, 3>;

std::multiset<Triangle> gridTriangles(const TriangleMesh& mesh, double step)
{
    std::multiset<Triangle> out;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        Triangle tri;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 w = mesh.origin + glm::dvec3(mesh.positions[mesh.indices[3 * t + std::size_t(k)]]);
            tri[std::size_t(k)] = {gridRound(w.x / step), gridRound(w.y / step), gridRound(w.z / step)};
        }
        std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
        out.insert(tri);
    }
    return out;
}

} // namespace

TEST(GltfCompact, RoundTripKeepsTrianglesWithinTheBounds)
{
    const glm::dvec3 origin(64.0, -32.0, 128.0); // a multiple of the step, as a tile corner
    const TriangleMesh mesh = sphereMesh(origin);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    for (const bool reorder : {false, true}) {
        SCOPED_TRACE(reorder ? "reordered" : "in order");
        CompactGlbOptions options;
        options.positionStep = STEP;
        options.optimizeOrder = reorder;
        CompactGlbStats stats;
        const std::string bytes = encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "sphere", options, &stats);
        EXPECT_EQ(stats.positionStep, STEP);
        EXPECT_LE(stats.maxPositionError, 0.5 * STEP + 1e-9);
        EXPECT_LT(stats.maxNormalAngle, glm::radians(1.0)); // 8-bit octahedral

        const TriangleMesh back = parseGlb(bytes, "sphere.glb");
        ASSERT_EQ(back.triangleCount(), mesh.triangleCount());
        ASSERT_EQ(back.vertexCount(), mesh.vertexCount()); // gridToMesh leaves no unused vertex
        ASSERT_EQ(back.normals.size(), back.vertexCount());
        ASSERT_EQ(back.surface.size(), back.vertexCount());
        ASSERT_EQ(back.landform.size(), back.vertexCount());
        ASSERT_EQ(back.rock.size(), back.vertexCount());
        // The same triangles, corner for corner on the grid, wound alike.
        EXPECT_EQ(gridTriangles(back, STEP), gridTriangles(mesh, STEP));

        // Per vertex: each decoded vertex is an input vertex within half a
        // step (found through the triangles' first corners when reordered).
        std::vector<std::size_t> source(back.vertexCount(), SIZE_MAX);
        if (!reorder) {
            for (std::size_t i = 0; i < source.size(); ++i) source[i] = i;
        } else {
            // Match each decoded vertex to the input vertex at the same grid point.
            std::map<Corner, std::size_t> at;
            for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
                const glm::dvec3 w = mesh.origin + glm::dvec3(mesh.positions[i]);
                at[{gridRound(w.x / STEP), gridRound(w.y / STEP), gridRound(w.z / STEP)}] = i;
            }
            for (std::size_t i = 0; i < back.vertexCount(); ++i) {
                const glm::dvec3 w = back.origin + glm::dvec3(back.positions[i]);
                const auto found = at.find({gridRound(w.x / STEP), gridRound(w.y / STEP), gridRound(w.z / STEP)});
                ASSERT_NE(found, at.end()) << "decoded vertex " << i << " is no input vertex";
                source[i] = found->second;
            }
        }
        double worstPosition = 0.0, worstAngle = 0.0;
        for (std::size_t i = 0; i < back.vertexCount(); ++i) {
            const std::size_t j = source[i];
            const glm::dvec3 d = (back.origin + glm::dvec3(back.positions[i])) - (mesh.origin + glm::dvec3(mesh.positions[j]));
            worstPosition = std::max({worstPosition, std::abs(d.x), std::abs(d.y), std::abs(d.z)});
            EXPECT_NEAR(glm::length(back.normals[i]), 1.0f, 1e-5f);
            worstAngle = std::max(worstAngle, double(std::acos(std::clamp(glm::dot(back.normals[i], mesh.normals[j]), -1.0f, 1.0f))));
            // Float attributes are lossless.
            EXPECT_EQ(back.surface[i], mesh.surface[j]);
            EXPECT_EQ(back.landform[i], mesh.landform[j]);
            EXPECT_EQ(back.rock[i], mesh.rock[j]);
        }
        EXPECT_LE(worstPosition, 0.5 * STEP + 1e-9);
        EXPECT_LT(worstAngle, glm::radians(1.0));
        std::cout << "[ compact ] " << (reorder ? "reordered" : "in order") << ": " << bytes.size() << " bytes ("
                  << encodeGlb({GlbPart{&mesh}}, mesh.origin, "sphere").size() << " plain), worst position error "
                  << worstPosition / STEP << " steps, worst normal " << glm::degrees(worstAngle) << " deg\n";
    }
}

TEST(GltfCompact, TheFileFollowsBothExtensions)
{
    const TriangleMesh mesh = sphereMesh(glm::dvec3(8.0, 0.0, -8.0));
    CompactGlbOptions options;
    options.positionStep = STEP;
    const std::string bytes = encodeCompactGlb({GlbPart{&mesh}, GlbPart{&mesh, "skirt", true}}, mesh.origin, "t", options);
    const nlohmann::json gltf = glbJson(bytes);
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        const auto& names = gltf[list];
        EXPECT_NE(std::find(names.begin(), names.end(), "EXT_meshopt_compression"), names.end()) << list;
        EXPECT_NE(std::find(names.begin(), names.end(), "KHR_mesh_quantization"), names.end()) << list;
    }
    // Buffer 1 is the fallback, with no data; every view decodes into it.
    ASSERT_EQ(gltf["buffers"].size(), 2u);
    EXPECT_FALSE(gltf["buffers"][1].contains("uri"));
    EXPECT_TRUE(gltf["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"].get<bool>());
    std::uint32_t jsonLength;
    std::memcpy(&jsonLength, bytes.data() + 12, 4);
    const std::size_t bin = 20 + jsonLength + 8;
    for (const auto& view : gltf["bufferViews"]) {
        EXPECT_EQ(view["buffer"], 1);
        const auto& ext = view["extensions"]["EXT_meshopt_compression"];
        EXPECT_EQ(ext["buffer"], 0);
        EXPECT_EQ(ext["byteOffset"].get<std::size_t>() % 4, 0u);
        const auto first = std::uint8_t(bytes[bin + ext["byteOffset"].get<std::size_t>()]);
        // The extension allows vertex codec version 0 (header 0xa0) and index codec version 0 or 1 (0xe0, 0xe1).
        if (ext["mode"] == "ATTRIBUTES") {
            EXPECT_EQ(first, 0xa0);
            EXPECT_EQ(view["byteStride"], ext["byteStride"]);
        } else {
            EXPECT_EQ(ext["mode"], "TRIANGLES");
            EXPECT_TRUE(first == 0xe0 || first == 0xe1) << int(first);
            EXPECT_FALSE(view.contains("byteStride")) << "index views have none";
        }
        EXPECT_EQ(view["byteLength"].get<std::size_t>(), ext["count"].get<std::size_t>() * ext["byteStride"].get<std::size_t>());
    }
    // Positions: unsigned short, not normalized, dequantized by the node's scale.
    const auto& position = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
    EXPECT_EQ(position["componentType"], 5123);
    EXPECT_FALSE(position.value("normalized", false));
    const auto& normal = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>()];
    EXPECT_EQ(normal["componentType"], 5120);
    EXPECT_TRUE(normal["normalized"].get<bool>());
    EXPECT_EQ(gltf["nodes"][0]["scale"], nlohmann::json({STEP, STEP, STEP}));
    // Same materials as the plain form: the skirt part double-sided.
    ASSERT_EQ(gltf["materials"].size(), 2u);
    EXPECT_TRUE(gltf["materials"][1]["doubleSided"].get<bool>());
}

TEST(GltfCompact, MeshesWithOriginsOnTheGridDecodeSharedPointsIdentically)
{
    // Two "tiles" hold the same world points (a seam at x = 100), each
    // relative to its own corner, one corner above and one below them in z,
    // so the same point is positive relative to one and negative to the
    // other. The points lie on a 1/1024 m lattice (the bake's seam points
    // lie on 1/4096 of a cell), a quarter of them exactly half-way between
    // two grid steps (the rounding ties). Both decode every point to the
    // same world point, bit for bit.
    const glm::dvec3 cornerA(0.0, -20.0, 0.0), cornerB(100.0, -20.0, 100.0);
    TriangleMesh a, b;
    a.origin = cornerA;
    b.origin = cornerB;
    std::uint32_t seed = 12345;
    auto next = [&] { return (seed = seed * 1664525u + 1013904223u) >> 8; };
    auto lattice = [&](double lo, double span) { return lo + double(next() % std::uint32_t(span * 1024.0)) / 1024.0; };
    for (int i = 0; i < 3000; ++i) {
        glm::dvec3 w(100.0, lattice(-20.0, 40.0), lattice(0.0, 100.0));
        if (i % 4 == 0) w.z = std::floor(w.z * 256.0) / 256.0 + 0.5 / 256.0; // a tie
        a.positions.push_back(glm::vec3(w - cornerA));
        b.positions.push_back(glm::vec3(w - cornerB));
        ASSERT_EQ(cornerA + glm::dvec3(a.positions.back()), w);
        ASSERT_EQ(cornerB + glm::dvec3(b.positions.back()), w);
        // Two more corners per triangle, so the meshes span differently.
        a.positions.push_back(glm::vec3(100.0 * lattice(0.0, 1.0), 10.0f, 50.0f));
        b.positions.push_back(glm::vec3(1.0 + 30.0 * lattice(0.0, 1.0), -10.0f, -50.0f));
        a.positions.push_back(glm::vec3(5.0f, 10.0 * lattice(0.0, 1.0), 5.0f));
        b.positions.push_back(glm::vec3(5.0f, 3.0 * lattice(0.0, 1.0), -5.0f));
        for (std::uint32_t k = 0; k < 3; ++k) {
            a.indices.push_back(std::uint32_t(3 * i) + k);
            b.indices.push_back(std::uint32_t(3 * i) + k);
        }
    }
    CompactGlbOptions options;
    options.positionStep = 1.0 / 256.0;
    const TriangleMesh backA = parseGlb(encodeCompactGlb({GlbPart{&a}}, a.origin, "a", options), "a.glb");
    const TriangleMesh backB = parseGlb(encodeCompactGlb({GlbPart{&b}}, b.origin, "b", options), "b.glb");
    auto seam = [](const TriangleMesh& m) {
        std::set<std::array<double, 3>> points;
        for (const glm::vec3& p : m.positions) {
            const glm::dvec3 w = m.origin + glm::dvec3(p);
            if (w.x == 100.0) points.insert({w.x, w.y, w.z});
        }
        return points;
    };
    const auto seamA = seam(backA), seamB = seam(backB);
    EXPECT_GT(seamA.size(), 2900u);
    EXPECT_EQ(seamA, seamB);
}

TEST(GltfCompact, TheStepDoublesWhereAMeshIsWiderThan16Bits)
{
    TriangleMesh mesh;
    mesh.positions = {{0.0f, 0.0f, 0.0f}, {300.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    mesh.indices = {0, 1, 2};
    CompactGlbOptions options;
    options.positionStep = 1.0 / 256.0; // 300 m would need 76800 steps
    CompactGlbStats stats;
    const TriangleMesh back = parseGlb(encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "w", options, &stats), "w.glb");
    EXPECT_EQ(stats.positionStep, 1.0 / 128.0);
    EXPECT_EQ(back.positions[1].x, 300.0f);

    EXPECT_EQ(compactPositionStep(256.0 + 32.0, 1.0), 1.0 / 128.0); // 288 m in 36864 steps
    EXPECT_EQ(compactPositionStep(1024.0 + 64.0, 1.0), 1.0 / 32.0);
    EXPECT_EQ(compactPositionStep(100000.0, 0.5), 2.0);
    EXPECT_THROW(compactPositionStep(1.0, 0.0), strata::Error);
    options.positionStep = 0.0;
    EXPECT_THROW(encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "w", options), strata::Error);
}

TEST(GltfCompact, ABrokenCompressedViewIsAnErrorNamingIt)
{
    const TriangleMesh mesh = sphereMesh(glm::dvec3(0.0));
    CompactGlbOptions options;
    options.positionStep = STEP;
    const std::string good = encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "s", options);
    const nlohmann::json gltf = glbJson(good);
    std::uint32_t jsonLength;
    std::memcpy(&jsonLength, good.data() + 12, 4);
    const std::size_t bin = 20 + jsonLength + 8;

    // Corrupt the vertex codec's header byte of view 0: the decoder refuses it.
    std::string bad = good;
    bad[bin + gltf["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteOffset"].get<std::size_t>()] = 0x11;
    try {
        parseGlb(bad, "bad.glb");
        FAIL() << "a corrupt compressed view was read";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.glb"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("buffer view 0"), std::string::npos) << e.what();
    }
    // A mode the extension does not have, written over "ATTRIBUTES" in place.
    std::string mode = good;
    const std::size_t at = mode.find("\"ATTRIBUTES\"");
    ASSERT_NE(at, std::string::npos);
    mode.replace(at, 12, "\"SOMETHINGS\"");
    EXPECT_THROW(parseGlb(mode, "mode.glb"), strata::Error);
    // A stride the attribute codec does not allow (a multiple of 4 is required).
    std::string stride = good;
    const std::size_t st = stride.find("\"byteStride\":8,\"count\"");
    ASSERT_NE(st, std::string::npos);
    stride[st + 13] = '7';
    EXPECT_THROW(parseGlb(stride, "stride.glb"), strata::Error);
}

namespace {

/// The same .glb with another JSON chunk (the binary chunk kept).
std::string withJson(const std::string& glb, const nlohmann::json& gltf)
{
    std::uint32_t jsonLength;
    std::memcpy(&jsonLength, glb.data() + 12, 4);
    std::string text = gltf.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    const std::string bin = glb.substr(20 + jsonLength);
    std::string out = glb.substr(0, 8);
    const auto u32 = [&out](std::size_t v) {
        const auto w = std::uint32_t(v);
        out.append(reinterpret_cast<const char*>(&w), 4);
    };
    u32(20 + text.size() + bin.size());
    u32(text.size());
    out += "JSON" + text + bin;
    return out;
}

} // namespace

TEST(GltfCompact, AViewClaimingMoreThanItsElementsIsRefusedBeforeAllocating)
{
    // Seen in a review: one view's byteLength set to 4,000,000,000 in a
    // 141 KB tile made the reader allocate 4 GB and succeed.
    const TriangleMesh mesh = sphereMesh(glm::dvec3(0.0));
    CompactGlbOptions options;
    options.positionStep = STEP;
    const std::string good = encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "s", options);
    ASSERT_NO_THROW(parseGlb(withJson(good, glbJson(good)), "same.glb"));
    for (const std::uint64_t claim : {std::uint64_t(4000000000u), std::uint64_t(1) << 20}) {
        nlohmann::json gltf = glbJson(good);
        gltf["bufferViews"][0]["byteLength"] = claim;
        try {
            parseGlb(withJson(good, gltf), "huge.glb");
            FAIL() << "a view of " << claim << " bytes was read";
        } catch (const strata::Error& e) {
            const std::string what = e.what();
            EXPECT_NE(what.find("huge.glb"), std::string::npos) << what;
            EXPECT_NE(what.find("byteLength " + std::to_string(claim)), std::string::npos) << what;
        }
    }
    // A count that claims more decoded bytes than 64 times the compressed
    // ones (the most the attribute codec yields) is refused too.
    nlohmann::json gltf = glbJson(good);
    auto& ext = gltf["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    const std::uint64_t stride = ext["byteStride"].get<std::uint64_t>();
    const std::uint64_t count = 64 * ext["byteLength"].get<std::uint64_t>() / stride + 4096;
    ext["count"] = count;
    gltf["bufferViews"][0]["byteLength"] = count * stride;
    EXPECT_THROW(parseGlb(withJson(good, gltf), "ratio.glb"), strata::Error);
}

TEST(GltfCompact, WiderNormalsAreShortsAndCloser)
{
    const TriangleMesh mesh = sphereMesh(glm::dvec3(0.0));
    CompactGlbOptions options;
    options.positionStep = STEP;
    options.optimizeOrder = false;
    options.normalBits = 12; // 8 bytes a normal (SHORT)
    CompactGlbStats stats;
    const std::string bytes = encodeCompactGlb({GlbPart{&mesh}}, mesh.origin, "s", options, &stats);
    const nlohmann::json gltf = glbJson(bytes);
    const auto& normal = gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["NORMAL"].get<int>()];
    EXPECT_EQ(normal["componentType"], 5122);
    const TriangleMesh back = parseGlb(bytes, "s.glb");
    ASSERT_EQ(back.normals.size(), mesh.normals.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < mesh.normals.size(); ++i)
        worst = std::max(worst, double(std::acos(std::clamp(glm::dot(back.normals[i], mesh.normals[i]), -1.0f, 1.0f))));
    EXPECT_LT(worst, glm::radians(0.1));
    EXPECT_LT(stats.maxNormalAngle, glm::radians(0.1));
}
