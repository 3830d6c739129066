// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/GridNormals.h>
#include <strata/meshing/GridToMesh.h>

#include <openvdb/tools/Interpolation.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

using namespace strata::meshing;

namespace {

// Area-weighted sums of the face normals around each vertex.
std::vector<glm::vec3> faceSums(const TriangleMesh& mesh)
{
    std::vector<glm::vec3> sums(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        sums[a] += n;
        sums[b] += n;
        sums[c] += n;
    }
    return sums;
}

// Vertices whose normal points against their faces.
std::size_t againstFaces(const TriangleMesh& mesh, const std::vector<glm::vec3>& normals)
{
    const std::vector<glm::vec3> sums = faceSums(mesh);
    std::size_t count = 0;
    for (std::size_t i = 0; i < normals.size(); ++i) count += glm::dot(normals[i], sums[i]) < 0.0f ? 1 : 0;
    return count;
}

// The raw central differences computeGridNormals() starts from.
std::vector<glm::vec3> rawGridGradients(const openvdb::FloatGrid& grid, const TriangleMesh& mesh)
{
    using Sampler = openvdb::tools::GridSampler<openvdb::FloatGrid::ConstAccessor, openvdb::tools::BoxSampler>;
    const openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const Sampler sampler(accessor, grid.transform());
    const double h = grid.voxelSize()[0];
    std::vector<glm::vec3> gradients;
    for (const glm::vec3& p : mesh.positions) {
        const openvdb::Vec3d w(mesh.origin.x + p.x, mesh.origin.y + p.y, mesh.origin.z + p.z);
        gradients.emplace_back(sampler.wsSample(w + openvdb::Vec3d(h, 0, 0)) - sampler.wsSample(w - openvdb::Vec3d(h, 0, 0)),
                               sampler.wsSample(w + openvdb::Vec3d(0, h, 0)) - sampler.wsSample(w - openvdb::Vec3d(0, h, 0)),
                               sampler.wsSample(w + openvdb::Vec3d(0, 0, h)) - sampler.wsSample(w - openvdb::Vec3d(0, 0, h)));
    }
    return gradients;
}

} // namespace

// Features thinner than two voxels: the central differences straddle both
// sides and some point against the faces (a tube 0.6 voxel in radius, a
// gyroid sheet 0.4 voxel thick). computeGridNormals() orients them.
TEST(GridNormals, ThinFeaturesGetNormalsOnTheirFacesSide)
{
    for (const AnalyticShape& shape : {analyticTorus({0.1, 0.2, -0.3}, 3.0, 0.15), analyticGyroid(2.0, 0.1, 3.0)}) {
        const auto grid = levelSetFromShape(shape, 0.25);
        GridToMeshOptions options;
        options.computeNormals = false;
        TriangleMesh mesh = gridToMesh(*grid, options);
        ASSERT_GT(mesh.vertexCount(), 300u) << shape.name;
        const std::size_t against = againstFaces(mesh, rawGridGradients(*grid, mesh));
        EXPECT_GT(against, 10u) << shape.name << ": the case no longer reproduces";

        computeGridNormals(*grid, mesh);
        EXPECT_EQ(againstFaces(mesh, mesh.normals), 0u) << shape.name;
        for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-5f) << shape.name;
        EXPECT_EQ(orientNormalsToFaces(mesh), 0u) << shape.name; // already oriented
    }
}

// On a feature several voxels thick nothing is replaced: the normals are the
// normalised central differences.
TEST(GridNormals, ThickFeaturesKeepTheirGradientNormals)
{
    const auto grid = levelSetFromShape(analyticSphere({0.1, 0.2, 0.3}, 3.0), 0.25);
    GridToMeshOptions options;
    options.computeNormals = false;
    TriangleMesh mesh = gridToMesh(*grid, options);
    const std::vector<glm::vec3> raw = rawGridGradients(*grid, mesh);
    computeGridNormals(*grid, mesh);
    for (std::size_t i = 0; i < raw.size(); ++i) {
        ASSERT_NEAR(glm::dot(mesh.normals[i], glm::normalize(raw[i])), 1.0f, 1e-5f);
    }
}

TEST(GridNormals, OrientReplacesNormalsAgainstTheirFacesByTheFaceNormal)
{
    // Two triangles in the z = 0 plane, counter-clockwise seen from +z.
    TriangleMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {5, 5, 5}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    const glm::vec3 tilted = glm::normalize(glm::vec3(1.0f, 0.0f, -0.1f)); // 95.7° from +z
    mesh.normals = {{0, 0, 1}, glm::normalize(glm::vec3(1, 0, 1)), {0, 0, -1}, tilted, {0, 0, -1}};
    EXPECT_EQ(orientNormalsToFaces(mesh), 2u);
    EXPECT_EQ(mesh.normals[0], glm::vec3(0, 0, 1));
    EXPECT_EQ(mesh.normals[1], glm::normalize(glm::vec3(1, 0, 1))); // on the faces' side: kept
    EXPECT_EQ(mesh.normals[2], glm::vec3(0, 0, 1));
    EXPECT_EQ(mesh.normals[3], glm::vec3(0, 0, 1)); // not the nearly tangent flip
    EXPECT_EQ(mesh.normals[4], glm::vec3(0, 0, -1)); // no faces: left alone

    TriangleMesh without = mesh;
    without.normals.clear();
    EXPECT_EQ(orientNormalsToFaces(without), 0u);
    EXPECT_TRUE(without.normals.empty());
}
