// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/meshing/SurfaceNets.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

using namespace strata::meshing;

TEST(SurfaceError, ExactForAKnownOffset)
{
    // A sphere meshed at radius 5 measured against radius 5.1: every mesh
    // sample is about 0.1 m (0.4 voxel at 0.25 m) from the surface.
    const auto grid = levelSetFromShape(analyticSphere({0, 0, 0}, 5.0), 0.25);
    const TriangleMesh mesh = surfaceNets(*grid);
    const auto bigger = analyticSphere({0, 0, 0}, 5.1);
    SurfaceErrorOptions options;
    options.voxelSize = 0.25;
    options.surfacePoints = sampleSurface(bigger.distance, bigger.gradient, bigger.min - 0.5, bigger.max + 0.5, 0.25);
    options.gradient = bigger.gradient;
    const SurfaceError e = measureSurfaceError(mesh, bigger.distance, options);
    EXPECT_GT(e.surfaceSamples, 1000u);
    EXPECT_EQ(e.meshSamples, mesh.vertexCount() + mesh.triangleCount());
    EXPECT_NEAR(e.meshToSurfaceMean, 0.4, 0.05);
    EXPECT_NEAR(e.surfaceToMeshMean, 0.4, 0.05);
    EXPECT_GE(e.hausdorff, e.rms);
    EXPECT_GE(e.rms, e.mean);
    EXPECT_LT(e.normalMeanDegrees, 2.0);
    EXPECT_LT(e.normalOver5Percent, 1.0);
}

TEST(SurfaceError, SamplesLieOnTheSurface)
{
    const auto torus = analyticTorus({0.5, 0, 0}, 3.0, 1.0);
    const auto points = sampleSurface(torus.distance, torus.gradient, torus.min - 0.5, torus.max + 0.5, 0.2);
    ASSERT_GT(points.size(), 500u);
    for (const glm::dvec3& p : points) EXPECT_LT(std::abs(torus.distance(p)), 1e-6);
}

TEST(SurfaceError, FindsAMissingPiece)
{
    // Drop a patch of triangles: the surface-to-mesh direction sees the hole.
    const auto shape = analyticSphere({0, 0, 0}, 4.0);
    const auto grid = levelSetFromShape(shape, 0.25);
    TriangleMesh mesh = surfaceNets(*grid);
    std::vector<std::uint32_t> kept;
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        if (mesh.positions[mesh.indices[t]].y > 3.5f) continue;
        kept.insert(kept.end(), mesh.indices.begin() + t, mesh.indices.begin() + t + 3);
    }
    mesh.indices = kept;
    SurfaceErrorOptions options;
    options.voxelSize = 0.25;
    options.surfacePoints = sampleSurface(shape.distance, shape.gradient, shape.min - 0.5, shape.max + 0.5, 0.25);
    const SurfaceError e = measureSurfaceError(mesh, shape.distance, options);
    EXPECT_LT(e.meshToSurfaceMax, 0.2);
    EXPECT_GT(e.surfaceToMeshMax, 2.0);
    EXPECT_EQ(e.hausdorff, e.surfaceToMeshMax);
    EXPECT_THROW(measureSurfaceError(mesh, shape.distance, SurfaceErrorOptions{0.0, {}, {}}), strata::Error);
}

namespace {

// Distance from p to triangle abc by brute force: the plane when the
// projection falls inside, else the nearest of the three edges.
double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
    const auto segment = [&](const glm::dvec3& u, const glm::dvec3& v) {
        const glm::dvec3 d = v - u;
        const double t = std::clamp(glm::dot(p - u, d) / glm::dot(d, d), 0.0, 1.0);
        return glm::length(p - (u + t * d));
    };
    const glm::dvec3 n = glm::cross(b - a, c - a);
    const glm::dvec3 q = p - n * (glm::dot(p - a, n) / glm::dot(n, n));
    const bool inside = glm::dot(glm::cross(b - a, q - a), n) >= 0 && glm::dot(glm::cross(c - b, q - b), n) >= 0 &&
                        glm::dot(glm::cross(a - c, q - c), n) >= 0;
    if (inside) return glm::length(p - q);
    return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

} // namespace

TEST(SurfaceError, PointToMeshDistancesAreExactNearAndFarAndAwayFromTheOrigin)
{
    // The bucket search prunes cells and stops at the scanned cube's faces:
    // every distance must still be the nearest triangle's, for points on the
    // mesh, near it, on bucket faces, and far outside it (beyond the shells).
    for (const double offset : {0.0, 1.0e6}) {
        const auto grid = levelSetFromShape(analyticTorus({0.5, 0, 0}, 3.0, 1.0), 0.5);
        TriangleMesh mesh = surfaceNets(*grid);
        mesh.origin += glm::dvec3(offset, -offset, 0.5 * offset);
        // A large triangle across many buckets, too.
        const auto base = std::uint32_t(mesh.positions.size());
        mesh.positions.insert(mesh.positions.end(), {{-9.0f, -4.0f, -9.0f}, {9.0f, -4.5f, -8.0f}, {0.0f, -3.0f, 9.0f}});
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2});

        std::vector<glm::dvec3> points;
        std::uint64_t s = 12345;
        const auto next = [&s] {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            return double(s >> 11) * 0x1.0p-53;
        };
        for (std::size_t i = 0; i < mesh.positions.size(); i += 7) points.push_back(mesh.origin + glm::dvec3(mesh.positions[i]));
        for (int i = 0; i < 400; ++i) {
            const double scale = i < 300 ? 6.0 : 400.0; // the last 100: far beyond 64 buckets of 1 m
            points.push_back(mesh.origin + scale * glm::dvec3(2 * next() - 1, 2 * next() - 1, 2 * next() - 1));
        }
        for (int i = 0; i < 50; ++i) points.push_back(mesh.origin + glm::dvec3(std::floor(8 * next() - 4), 0.5, 1.0)); // on bucket faces

        SurfaceErrorOptions options;
        options.voxelSize = 0.5; // buckets 1 m wide
        options.meshToSurface = false; // mesh against points: no distance function
        for (const glm::dvec3& p : points) {
            options.surfacePoints = {p};
            const SurfaceError e = measureSurfaceError(mesh, {}, options);
            ASSERT_EQ(e.meshSamples, 0u);
            const double found = e.surfaceToMeshMax * 0.5;
            double expected = std::numeric_limits<double>::infinity();
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
                const auto v = [&](std::size_t k) { return mesh.origin + glm::dvec3(mesh.positions[mesh.indices[t + k]]); };
                expected = std::min(expected, pointTriangleDistance(p, v(0), v(1), v(2)));
            }
            ASSERT_NEAR(found, expected, 1e-9 * (1.0 + expected) + 1e-12 * offset) << "point " << p.x << " " << p.y << " " << p.z;
        }
    }
}
