// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/Simplify.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/meshing/SurfaceNets.h>

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <tuple>

using namespace strata::meshing;

namespace {

// Boundary edges as pairs of positions (order-free), for comparing borders.
std::set<std::tuple<float, float, float, float, float, float>> borderOf(const TriangleMesh& mesh)
{
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        for (int e = 0; e < 3; ++e) {
            std::uint32_t a = mesh.indices[t + e], b = mesh.indices[t + (e + 1) % 3];
            uses[{std::min(a, b), std::max(a, b)}]++;
        }
    }
    std::set<std::tuple<float, float, float, float, float, float>> border;
    for (const auto& [edge, count] : uses) {
        if (count != 1) continue;
        glm::vec3 p = mesh.positions[edge.first], q = mesh.positions[edge.second];
        if (std::tie(q.x, q.y, q.z) < std::tie(p.x, p.y, p.z)) std::swap(p, q);
        border.emplace(p.x, p.y, p.z, q.x, q.y, q.z);
    }
    return border;
}

} // namespace

TEST(Simplify, BothMethodsKeepTheErrorBoundAndStayClosed)
{
    const double voxel = 0.25;
    const auto shape = analyticSphere({0.1, 0.2, 0.3}, 6.0);
    const auto grid = levelSetFromShape(shape, voxel);
    const TriangleMesh mesh = surfaceNets(*grid);
    SurfaceErrorOptions measure;
    measure.voxelSize = voxel;
    const double before = measureSurfaceError(mesh, shape.distance, measure).meshToSurfaceMax;
    for (Simplifier method : {Simplifier::MeshOptimizer, Simplifier::Quadric}) {
        SimplifyOptions options;
        options.method = method;
        options.ratio = 0.1;
        options.maxError = 0.25 * voxel;
        const TriangleMesh simple = simplify(mesh, options);
        EXPECT_LT(simple.triangleCount(), mesh.triangleCount() / 2) << toString(method);
        EXPECT_EQ(simple.normals.size(), simple.positions.size());
        EXPECT_TRUE(analyzeTopology(simple).watertight()) << toString(method);
        // Distance to the true surface grows by no more than the bound.
        const double after = measureSurfaceError(simple, shape.distance, measure).meshToSurfaceMax;
        EXPECT_LE(after, before + 0.25 + 0.02) << toString(method) << " " << before << " -> " << after;
        EXPECT_NEAR(signedVolume(simple), signedVolume(mesh), 0.01 * signedVolume(mesh));
    }
}

TEST(Simplify, TighterBoundKeepsMoreTriangles)
{
    const auto grid = levelSetFromShape(analyticSphere({0, 0, 0}, 5.0), 0.25);
    const TriangleMesh mesh = surfaceNets(*grid);
    for (Simplifier method : {Simplifier::MeshOptimizer, Simplifier::Quadric}) {
        SimplifyOptions loose, tight;
        loose.method = tight.method = method;
        loose.ratio = tight.ratio = 0.01;
        loose.maxError = 0.1;
        tight.maxError = 0.001;
        EXPECT_GT(simplify(mesh, tight).triangleCount(), simplify(mesh, loose).triangleCount()) << toString(method);
    }
}

TEST(Simplify, ChunkBordersStayFixed)
{
    const auto grid = levelSetFromShape(analyticSphere({0.3, 0.1, -0.2}, 6.0), 0.25);
    ChunkMeshOptions chunkOptions;
    chunkOptions.chunkSize = 16;
    for (const openvdb::Coord& c : listChunks(*grid, 16)) {
        const ChunkMesh chunk = surfaceNetsChunk(*grid, c, chunkOptions);
        if (chunk.mesh.triangleCount() < 100) continue;
        for (Simplifier method : {Simplifier::MeshOptimizer, Simplifier::Quadric}) {
            SimplifyOptions options;
            options.method = method;
            options.ratio = 0.2;
            options.maxError = 0.1;
            const TriangleMesh simple = simplify(chunk.mesh, options);
            EXPECT_LT(simple.triangleCount(), chunk.mesh.triangleCount());
            EXPECT_EQ(borderOf(simple), borderOf(chunk.mesh)) << toString(method) << " chunk " << c;
        }
    }
}

TEST(Simplify, RejectsBadOptions)
{
    TriangleMesh mesh;
    SimplifyOptions options;
    options.ratio = 0.0;
    EXPECT_THROW(simplify(mesh, options), strata::Error);
    options.ratio = 0.5;
    options.maxError = -1.0;
    EXPECT_THROW(simplify(mesh, options), strata::Error);
}
