// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The shared dual mesher (DualMesh.h) behind surfaceNets(), dualContouring()
// and the World's chunk meshes: golden hashes of its outputs, so a change of
// a single bit shows, and the manifold welding of dual contouring.

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/DualMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <gtest/gtest.h>

#include "ByteHash.h"

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using namespace strata::meshing;

namespace {

using Hash = strata::test::ByteHash;

std::uint64_t meshHash(const TriangleMesh& mesh)
{
    Hash h;
    h.bytes(&mesh.origin, sizeof(mesh.origin));
    h.vec(mesh.positions);
    h.vec(mesh.normals);
    h.vec(mesh.indices);
    return h.h;
}

std::uint64_t chunkHash(const ChunkMesh& chunk)
{
    Hash h;
    const std::uint64_t mesh = meshHash(chunk.mesh);
    h.bytes(&mesh, sizeof(mesh));
    h.bytes(chunk.chunkMin.data(), 3 * sizeof(int));
    h.vec(chunk.cells);
    h.vec(chunk.components);
    return h.h;
}

std::string hex(std::uint64_t v)
{
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "0x%016llxull", static_cast<unsigned long long>(v));
    return buffer;
}

// The hash of a few chunks of `grid` (the first, the middle and the last of
// listChunks) and of the assembled mesh, for one mesher and its options.
template <typename Options, typename Whole, typename Chunk>
std::uint64_t outputHash(const openvdb::FloatGrid& grid, const Options& options, Whole whole, Chunk chunk)
{
    Hash h;
    const std::uint64_t all = meshHash(whole(grid, options));
    h.bytes(&all, sizeof(all));
    const std::vector<openvdb::Coord> chunks = listChunks(grid, options.chunkSize == 0 ? 32 : options.chunkSize);
    for (std::size_t i : {std::size_t(0), chunks.size() / 2, chunks.size() - 1}) {
        const std::uint64_t one = chunkHash(chunk(grid, chunks[i], options));
        h.bytes(&one, sizeof(one));
    }
    return h.h;
}

std::uint64_t netsHash(const openvdb::FloatGrid& grid, const ChunkMeshOptions& options)
{
    return outputHash(grid, options, [](auto& g, auto& o) { return surfaceNets(g, o); },
                      [](auto& g, auto& c, auto& o) { return surfaceNetsChunk(g, c, o); });
}

std::uint64_t contouringHash(const openvdb::FloatGrid& grid, const DualContouringOptions& options)
{
    return outputHash(grid, options, [](auto& g, auto& o) { return dualContouring(g, o); },
                      [](auto& g, auto& c, auto& o) { return dualContouringChunk(g, c, o); });
}

} // namespace

// Expected values computed on the meshers before they shared DualMesh.cpp:
// the refactoring changes no bit of surface nets.
TEST(DualMesh, SurfaceNetsBytesAreUnchanged)
{
    openvdb::initialize();
    const auto torus = levelSetFromShape(analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5), 0.25);
    const auto gyroid = levelSetFromShape(analyticGyroid(6.0, 1.2, 7.0), 0.25);
    const AnalyticShape box = analyticBox({-3.13, -2.41, -2.77}, {2.94, 2.58, 3.06});
    const auto boxGrid = levelSetFromShape(box, 0.25);

    ChunkMeshOptions plain;
    plain.chunkSize = 16;
    ChunkMeshOptions projected = plain;
    projected.projectionSteps = 2;
    projected.normals = NormalMethod::Gradient;
    projected.gradient = box.gradient;
    ChunkMeshOptions face;
    face.chunkSize = 32;
    face.normals = NormalMethod::Face;
    face.isovalue = 0.1;
    face.origin = {1.0, -2.0, 3.0};

    const std::uint64_t got[] = {netsHash(*torus, plain), netsHash(*gyroid, plain), netsHash(*boxGrid, projected),
                                 netsHash(*torus, face)};
    const std::uint64_t expected[] = {0x61b845610cf7b553ull, 0x03bebc8a10749ca7ull, 0x2d3e534215e0842cull,
                                      0xa46fd6c0e8f16ebaull};
    for (std::size_t i = 0; i < std::size(got); ++i) EXPECT_EQ(got[i], expected[i]) << i << ": " << hex(got[i]);
}

// Dual contouring, the same way. The box values are those of the code before
// DualMesh.cpp; the torus ones changed once, with the deliberate fix that
// keeps DC vertices DUAL_CONTOURING_MARGIN inside their cells (before it:
// 0xfcf20a0516105c33, 0x4ee05c08acea670b): a few of its QEF minima were
// clamped onto cell faces.
TEST(DualMesh, DualContouringBytesAreUnchanged)
{
    openvdb::initialize();
    const auto torus = levelSetFromShape(analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5), 0.25);
    const AnalyticShape box = analyticBox({-3.13, -2.41, -2.77}, {2.94, 2.58, 3.06});
    const auto boxGrid = levelSetFromShape(box, 0.25);

    DualContouringOptions plain;
    plain.chunkSize = 16;
    DualContouringOptions exact = plain;
    exact.gradient = box.gradient;
    exact.normals = NormalMethod::Gradient;
    DualContouringOptions projected = plain;
    projected.projectionSteps = 3;
    projected.singularThreshold = 0.05;

    const std::uint64_t got[] = {contouringHash(*torus, plain), contouringHash(*boxGrid, plain),
                                 contouringHash(*boxGrid, exact), contouringHash(*torus, projected)};
    const std::uint64_t expected[] = {0x44061edf8b7c8475ull, 0xaa8d09439a1b4762ull, 0xd4a9459683b5862aull,
                                      0x4f43e8b59f5953a3ull};
    for (std::size_t i = 0; i < std::size(got); ++i) EXPECT_EQ(got[i], expected[i]) << i << ": " << hex(got[i]);
}

namespace {

// `mesh` with vertices of equal position merged (as a reader that welds by
// position does); `duplicates` counts the vertices merged away.
TriangleMesh weldByPosition(const TriangleMesh& mesh, std::size_t& duplicates)
{
    TriangleMesh out;
    out.origin = mesh.origin;
    std::map<std::array<float, 3>, std::uint32_t> ids;
    std::vector<std::uint32_t> remap(mesh.positions.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3& p = mesh.positions[i];
        const auto [it, inserted] = ids.emplace(std::array<float, 3>{p.x, p.y, p.z}, std::uint32_t(out.positions.size()));
        if (inserted) out.positions.push_back(p);
        remap[i] = it->second;
    }
    duplicates = mesh.positions.size() - out.positions.size();
    for (std::uint32_t index : mesh.indices) out.indices.push_back(remap[index]);
    return out;
}

} // namespace

// Thin gyroid sheets with a low singular threshold put QEF minima far
// outside their cells: before the fix, 48 to 1833 vertices shared a position
// with another (clamped onto the same corner, by neighbouring cells or by two
// sheets of one cell), and welding by position made non-manifold edges. Dual
// contouring now keeps every vertex strictly inside its cell and separates
// the sheets of a cell, so the mesh welded by position is as manifold as the
// one welded by cell.
TEST(DualMesh, DualContouringVerticesAreDistinctAfterWeldingByPosition)
{
    openvdb::initialize();
    const AnalyticShape shapes[] = {analyticGyroid(6.0, 1.2, 7.0), analyticGyroid(3.0, 0.4, 5.0),
                                    analyticGyroid(2.0, 0.3, 4.0)};
    for (const AnalyticShape& shape : shapes) {
        const auto grid = levelSetFromShape(shape, 0.25);
        for (const bool exact : {false, true}) {
            DualContouringOptions options;
            options.chunkSize = 16;
            options.singularThreshold = 0.01;
            if (exact) options.gradient = shape.gradient;
            const TriangleMesh mesh = dualContouring(*grid, options);
            const std::string what = shape.name + (exact ? " exact planes" : " grid planes");
            ASSERT_EQ(analyzeTopology(mesh).nonManifoldEdges, 0u) << what;
            std::size_t duplicates = 0;
            const TriangleMesh welded = weldByPosition(mesh, duplicates);
            EXPECT_EQ(duplicates, 0u) << what;
            EXPECT_EQ(analyzeTopology(welded).nonManifoldEdges, 0u) << what;
        }
    }
}

// dualMesh() into a reused result (the chunk meshers' per-thread buffers)
// gives the same vertices, positions, gradients and indices as a fresh call,
// whatever the result held before, for each layout and setting.
TEST(DualMesh, ReusedResultEqualsFreshResult)
{
    auto field = [](int x, int y, int z, int seed) {
        const std::uint32_t k = std::uint32_t(x * 73856093) ^ std::uint32_t(y * 19349663) ^ std::uint32_t(z * 83492791) ^
                                std::uint32_t(seed * 2654435761u);
        return 0.3f * float(z - 6) + float((k * 2246822519u) >> 20) / 2048.0f - 1.0f;
    };
    DualMeshResult reused;
    for (int seed = 0; seed < 4; ++seed) {
        const int cells = seed % 2 ? 8 : 13, apron = 3, n = cells + 2 * apron + 1;
        std::vector<float> values(std::size_t(n) * n * n);
        for (int x = 0; x < n; ++x)
            for (int y = 0; y < n; ++y)
                for (int z = 0; z < n; ++z) values[(std::size_t(x) * n + y) * n + z] = field(x, y, z, seed);
        DualSamples samples;
        samples.values = values.data();
        samples.apron = apron;
        samples.cells = {cells, cells, cells};
        samples.size = {n, n, n};
        // Seeds 2 and 3 store z slowest (the general walk), 0 and 1 x slowest.
        samples.stride = seed < 2 ? std::array<std::ptrdiff_t, 3>{std::ptrdiff_t(n) * n, n, 1}
                                  : std::array<std::ptrdiff_t, 3>{1, n, std::ptrdiff_t(n) * n};
        DualMeshSettings settings;
        settings.sheets = seed % 2 ? DualSheets::Separate : DualSheets::One;
        settings.split = DualQuadSplit::ShorterDiagonal;
        settings.gradients = seed % 2 ? DualGradient::Central : DualGradient::Cell;
        settings.quantum = 65536.0;
        const DualMeshResult fresh = dualMesh(samples, settings);
        dualMesh(samples, settings, reused);
        ASSERT_FALSE(fresh.indices.empty()) << seed;
        EXPECT_EQ(fresh.indices, reused.indices) << seed;
        EXPECT_EQ(fresh.positions, reused.positions) << seed;
        EXPECT_EQ(fresh.gradients, reused.gradients) << seed;
        ASSERT_EQ(fresh.vertices.size(), reused.vertices.size()) << seed;
        for (std::size_t i = 0; i < fresh.vertices.size(); ++i) {
            EXPECT_EQ(fresh.vertices[i].cell, reused.vertices[i].cell) << seed;
            EXPECT_EQ(fresh.vertices[i].sheet, reused.vertices[i].sheet) << seed;
        }
    }
}
