// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <openvdb/tools/Interpolation.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <map>

using namespace strata::meshing;

namespace {

// A level set of background 1 whose voxels in [lo, hi] are -0.5 (inside).
openvdb::FloatGrid::Ptr voxelBlock(const openvdb::Coord& lo, const openvdb::Coord& hi)
{
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.0f);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    for (int x = lo.x() - 1; x <= hi.x() + 1; ++x)
        for (int y = lo.y() - 1; y <= hi.y() + 1; ++y)
            for (int z = lo.z() - 1; z <= hi.z() + 1; ++z) {
                const bool inside = openvdb::CoordBBox(lo, hi).isInside(openvdb::Coord(x, y, z));
                grid->tree().setValue(openvdb::Coord(x, y, z), inside ? -0.5f : 1.0f);
            }
    return grid;
}

bool sameBytes(const TriangleMesh& a, const TriangleMesh& b)
{
    return a.indices == b.indices && a.positions.size() == b.positions.size() &&
           a.normals.size() == b.normals.size() &&
           std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)) == 0 &&
           std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(glm::vec3)) == 0;
}

} // namespace

TEST(SurfaceNets, OneInsideVoxelGivesASmallCube)
{
    const TriangleMesh mesh = surfaceNets(*voxelBlock(openvdb::Coord(0), openvdb::Coord(0)));
    ASSERT_EQ(mesh.vertexCount(), 8u);
    ASSERT_EQ(mesh.triangleCount(), 12u);
    EXPECT_TRUE(analyzeTopology(mesh).watertight());
    // Crossings a third of the way from the inside voxel: vertices at ±1/9.
    for (const glm::vec3& p : mesh.positions) {
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(std::abs(p[a]), 1.0f / 9.0f, 1e-4f);
    }
    EXPECT_NEAR(signedVolume(mesh), std::pow(2.0 / 9.0, 3.0), 1e-4);
}

TEST(SurfaceNets, CubeOfInsideVoxelsHasTheExpectedCounts)
{
    // k^3 inside voxels: (k+1)^3 - (k-1)^3 crossing cells, 6 k^2 crossing edges.
    for (int k : {2, 3, 5}) {
        for (int chunk : {0, 8}) {
            ChunkMeshOptions options;
            options.chunkSize = chunk;
            const TriangleMesh mesh = surfaceNets(*voxelBlock(openvdb::Coord(5), openvdb::Coord(5 + k - 1)), options);
            EXPECT_EQ(mesh.vertexCount(), std::size_t((k + 1) * (k + 1) * (k + 1) - (k - 1) * (k - 1) * (k - 1)))
                << "k " << k << " chunk " << chunk;
            EXPECT_EQ(mesh.triangleCount(), std::size_t(12 * k * k));
            EXPECT_TRUE(analyzeTopology(mesh).watertight());
            EXPECT_GT(signedVolume(mesh), 0.0);
        }
    }
}

TEST(SurfaceNets, AmbiguousCellsStayManifold)
{
    // Inside voxels touching along a face diagonal, then only at a corner:
    // the cells between them hold two sheets, one vertex each, and the mesh
    // is two closed cubes with no non-manifold edge or vertex.
    for (const openvdb::Coord& other : {openvdb::Coord(0, 1, 1), openvdb::Coord(1, 1, 1)}) {
        openvdb::initialize();
        openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.0f);
        grid->setGridClass(openvdb::GRID_LEVEL_SET);
        grid->tree().setValue(openvdb::Coord(0), -0.5f);
        grid->tree().setValue(other, -0.5f);
        for (int chunk : {0, 8}) {
            ChunkMeshOptions options;
            options.chunkSize = chunk;
            const TriangleMesh mesh = surfaceNets(*grid, options);
            EXPECT_EQ(mesh.vertexCount(), 16u) << other;
            EXPECT_EQ(mesh.triangleCount(), 24u);
            const MeshTopology topology = analyzeTopology(mesh);
            EXPECT_TRUE(topology.watertight());
            EXPECT_EQ(topology.nonManifoldVertices, 0u);
            EXPECT_NEAR(signedVolume(mesh), 2.0 * std::pow(2.0 / 9.0, 3.0), 1e-4);
        }
    }
}

TEST(SurfaceNets, TunnelCellsFacingEachOtherStayManifold)
{
    // A clipped gyroid sheet at 0.25 m voxels has cells whose sheet crosses
    // one face twice, facing a neighbour that does the same (12 non-manifold
    // edges before the complement grouping of OpenVDB's correctCellSigns).
    const auto grid = levelSetFromShape(analyticGyroid(6.0, 1.2, 7.0), 0.25);
    for (int chunk : {0, 32}) {
        ChunkMeshOptions options;
        options.chunkSize = chunk;
        const MeshTopology nets = analyzeTopology(surfaceNets(*grid, options));
        EXPECT_TRUE(nets.watertight()) << "chunk " << chunk << ": " << nets.nonManifoldEdges << " non-manifold edges";
        EXPECT_EQ(nets.nonManifoldVertices, 0u);
    }
}

TEST(SurfaceNets, ClosedShapesAreWatertightOutwardWithTheRightVolume)
{
    // 64 voxels across, chunked (two sizes) and unchunked.
    const double voxel = 0.25;
    const AnalyticShape shapes[] = {analyticSphere({0.3, -0.2, 0.1}, 8.0),
                                          analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5)};
    for (const auto& shape : shapes) {
        const auto grid = levelSetFromShape(shape, voxel);
        for (int chunk : {0, 16, 32}) {
            ChunkMeshOptions options;
            options.chunkSize = chunk;
            const TriangleMesh mesh = surfaceNets(*grid, options);
            const MeshTopology topology = analyzeTopology(mesh);
            EXPECT_TRUE(topology.watertight()) << "chunk " << chunk << " boundary " << topology.boundaryEdges
                                               << " non-manifold " << topology.nonManifoldEdges;
            EXPECT_EQ(topology.degenerateTriangles, 0u);
            EXPECT_EQ(topology.nonManifoldVertices, 0u);
            EXPECT_NEAR(signedVolume(mesh) / shape.volume, 1.0, 0.01) << "chunk " << chunk;
        }
    }
}

TEST(SurfaceNets, ChunkedAndUnchunkedGiveTheSameSurface)
{
    const auto grid = levelSetFromShape(analyticSphere({0.1, 0.2, 0.3}, 5.0), 0.25);
    ChunkMeshOptions whole;
    whole.chunkSize = 0;
    ChunkMeshOptions chunked;
    chunked.chunkSize = 8;
    const TriangleMesh a = surfaceNets(*grid, whole), b = surfaceNets(*grid, chunked);
    ASSERT_EQ(a.vertexCount(), b.vertexCount());
    ASSERT_EQ(a.triangleCount(), b.triangleCount());
    auto sorted = [](std::vector<glm::vec3> v) {
        std::sort(v.begin(), v.end(), [](const glm::vec3& p, const glm::vec3& q) {
            return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z);
        });
        return v;
    };
    EXPECT_EQ(sorted(a.positions), sorted(b.positions));
    EXPECT_DOUBLE_EQ(signedVolume(a), signedVolume(b));
}

TEST(SurfaceNets, AdjacentChunksShareIdenticalBorderVertices)
{
    // Power-of-two voxel size: world positions are exact in both chunks.
    const auto grid = levelSetFromShape(analyticSphere({0.3, 0.1, -0.2}, 6.0), 0.25);
    ChunkMeshOptions options;
    options.chunkSize = 16;
    const std::vector<openvdb::Coord> chunks = listChunks(*grid, 16);
    ASSERT_GT(chunks.size(), 8u);
    using Key = std::pair<openvdb::Coord, int>; // (cell, component) names a vertex
    std::map<Key, glm::dvec3> firstSeen;        // world position
    std::map<Key, glm::vec3> firstNormal;
    std::size_t shared = 0;
    TriangleMesh all; // the union, welded by cell
    std::map<Key, std::uint32_t> welded;
    for (const openvdb::Coord& c : chunks) {
        const ChunkMesh chunk = surfaceNetsChunk(*grid, c, options);
        EXPECT_EQ(chunk.chunkMin, c);
        ASSERT_EQ(chunk.cells.size(), chunk.mesh.vertexCount());
        ASSERT_EQ(chunk.components.size(), chunk.mesh.vertexCount());
        std::vector<std::uint32_t> remap(chunk.mesh.vertexCount());
        for (std::size_t v = 0; v < chunk.cells.size(); ++v) {
            const glm::dvec3 world = chunk.mesh.origin + glm::dvec3(chunk.mesh.positions[v]);
            const Key key(chunk.cells[v], chunk.components[v]);
            const auto [it, inserted] = firstSeen.emplace(key, world);
            if (!inserted) {
                ++shared;
                EXPECT_EQ(it->second, world) << "cell " << chunk.cells[v];
                EXPECT_EQ(firstNormal[key], chunk.mesh.normals[v]);
                remap[v] = welded[key];
            } else {
                firstNormal[key] = chunk.mesh.normals[v];
                remap[v] = welded[key] = std::uint32_t(all.positions.size());
                all.positions.emplace_back(world);
            }
        }
        for (std::uint32_t i : chunk.mesh.indices) all.indices.push_back(remap[i]);
    }
    EXPECT_GT(shared, 100u);
    EXPECT_TRUE(analyzeTopology(all).watertight());
    EXPECT_EQ(all.triangleCount(), surfaceNets(*grid, options).triangleCount());
}

TEST(SurfaceNets, SameBytesOnOneOrManyThreads)
{
    const auto grid = levelSetFromShape(analyticTorus({0.0, 0.0, 0.0}, 5.0, 2.0), 0.25);
    ChunkMeshOptions options;
    options.chunkSize = 16;
    TriangleMesh single;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        single = surfaceNets(*grid, options);
    }
    const TriangleMesh many = surfaceNets(*grid, options);
    EXPECT_TRUE(sameBytes(single, many));
}

TEST(SurfaceNets, ProjectionMovesVerticesOntoTheSurface)
{
    // A box: surface nets leaves vertices off its rounded edges; Newton
    // steps bring them onto the trilinear surface of the grid.
    const double voxel = 0.25;
    const auto shape = analyticBox({-3.13, -2.41, -2.77}, {2.94, 2.58, 3.06});
    const auto grid = levelSetFromShape(shape, voxel);
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
    auto residual = [&](const TriangleMesh& mesh) { // mean |interpolated value|, voxels
        double sum = 0.0;
        for (const glm::vec3& p : mesh.positions) {
            const glm::dvec3 w = mesh.origin + glm::dvec3(p);
            sum += std::abs(sampler.wsSample(openvdb::Vec3d(w.x, w.y, w.z)));
        }
        return sum / double(mesh.vertexCount()) / voxel;
    };
    ChunkMeshOptions options;
    const double before = residual(surfaceNets(*grid, options));
    options.projectionSteps = 2;
    const TriangleMesh projected = surfaceNets(*grid, options);
    const double after = residual(projected);
    EXPECT_LT(after, 0.25 * before) << before << " -> " << after;
    EXPECT_LT(after, 1e-3);
    EXPECT_TRUE(analyzeTopology(projected).watertight());
}

TEST(SurfaceNets, NormalMethods)
{
    const auto shape = analyticSphere({0.1, 0.2, 0.3}, 5.0);
    const auto grid = levelSetFromShape(shape, 0.25);
    for (NormalMethod method : {NormalMethod::Grid, NormalMethod::Gradient, NormalMethod::Face}) {
        ChunkMeshOptions options;
        options.normals = method;
        options.gradient = shape.gradient;
        const TriangleMesh mesh = surfaceNets(*grid, options);
        ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
        double worst = 0.0;
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f);
            const glm::dvec3 exact = shape.gradient(mesh.origin + glm::dvec3(mesh.positions[i]));
            worst = std::max(worst, std::acos(std::clamp(glm::dot(exact, glm::dvec3(mesh.normals[i])), -1.0, 1.0)));
        }
        EXPECT_LT(worst * 180.0 / 3.14159265, method == NormalMethod::Gradient ? 0.05 : 10.0) << toString(method);
    }
    ChunkMeshOptions none;
    none.normals = NormalMethod::None;
    EXPECT_TRUE(surfaceNets(*grid, none).normals.empty());
}

TEST(SurfaceNets, FarOriginKeepsPrecision)
{
    const auto grid = levelSetFromShape(analyticSphere({4096.0, 0.0, -4096.0}, 3.0), 0.25);
    ChunkMeshOptions options;
    options.origin = {4096.0, 0.0, -4096.0};
    const TriangleMesh mesh = surfaceNets(*grid, options);
    ASSERT_GT(mesh.vertexCount(), 100u);
    for (const glm::vec3& p : mesh.positions) EXPECT_NEAR(glm::length(p), 3.0f, 0.1f);
}

TEST(SurfaceNets, RejectsBadOptions)
{
    const auto grid = voxelBlock(openvdb::Coord(0), openvdb::Coord(0));
    ChunkMeshOptions options;
    options.chunkSize = 12;
    EXPECT_THROW(surfaceNets(*grid, options), strata::Error);
    options.chunkSize = 32;
    options.isovalue = std::nan("");
    EXPECT_THROW(surfaceNets(*grid, options), strata::Error);
    options.isovalue = 0.0;
    options.normals = NormalMethod::Gradient;
    EXPECT_THROW(surfaceNets(*grid, options), strata::Error);
    options.normals = NormalMethod::Grid;
    options.projectionSteps = -1;
    EXPECT_THROW(surfaceNets(*grid, options), strata::Error);
    EXPECT_THROW(listChunks(*grid, 0), strata::Error);
    options.projectionSteps = 0;
    EXPECT_THROW(surfaceNetsChunk(*grid, openvdb::Coord(3, 0, 0), options), strata::Error);
}

TEST(SurfaceNets, EmptyGridGivesEmptyMesh)
{
    openvdb::initialize();
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(1.5f);
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    for (int chunk : {0, 32}) {
        ChunkMeshOptions options;
        options.chunkSize = chunk;
        EXPECT_EQ(surfaceNets(*grid, options).triangleCount(), 0u);
    }
}
