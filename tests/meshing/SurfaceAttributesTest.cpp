// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/meshing/GridNormals.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/SurfaceAttributes.h>

#include <openvdb/tools/Composite.h>
#include <openvdb/tools/LevelSetSphere.h>
#include <openvdb/tools/LevelSetUtil.h>
#include <openvdb/tools/MeshToVolume.h>

#include <gtest/gtest.h>

#include <iostream>

using namespace strata::meshing;

namespace {

/// A level set of an axis-aligned box [lo, hi] with `voxel` spacing.
openvdb::FloatGrid::Ptr boxLevelSet(const openvdb::Vec3s& lo, const openvdb::Vec3s& hi, float voxel)
{
    return openvdb::tools::createLevelSetBox<openvdb::FloatGrid>(openvdb::BBoxd(lo, hi),
                                                                 *openvdb::math::Transform::createLinearTransform(voxel));
}

TriangleMesh meshOf(const openvdb::FloatGrid& grid)
{
    GridToMeshOptions options;
    options.normals = NormalMethod::Grid;
    return gridToMesh(grid, options);
}

} // namespace

TEST(SurfaceAttributes, ASphereIsNeitherConcaveNorCovered)
{
    openvdb::initialize();
    const auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(5.0f, openvdb::Vec3f(0.0f), 0.25f);
    const TriangleMesh mesh = meshOf(*sphere);
    const std::vector<glm::vec2> a = computeSurfaceAttributes(*sphere, mesh);
    ASSERT_EQ(a.size(), mesh.positions.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_LT(a[i].x, 0.1f) << i;
        // Only the underside has rock above it.
        if (mesh.normals[i].y > 0.2f) {
            EXPECT_EQ(a[i].y, 0.0f) << i;
        }
        if (mesh.normals[i].y < -0.5f) {
            EXPECT_EQ(a[i].y, 1.0f) << i;
        }
    }
}

TEST(SurfaceAttributes, GroundUnderAnOverhangIsCoveredAndItsInnerCornerConcave)
{
    openvdb::initialize();
    // A floor slab, a pillar, and a roof slab over part of the floor.
    auto ground = boxLevelSet({-8, -2, -8}, {8, 0, 8}, 0.25f);
    auto pillar = boxLevelSet({-8, -1, -8}, {-6, 6, 8}, 0.25f);
    auto roof = boxLevelSet({-8, 5, -8}, {2, 6, 8}, 0.25f);
    openvdb::tools::csgUnion(*ground, *pillar);
    openvdb::tools::csgUnion(*ground, *roof);
    const TriangleMesh mesh = meshOf(*ground);
    const std::vector<glm::vec2> a = computeSurfaceAttributes(*ground, mesh);
    int coveredFloor = 0, openFloor = 0, corner = 0;
    double cornerCavity = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        const bool floor = std::abs(p.y) < 0.2f && mesh.normals[i].y > 0.9f;
        if (floor && p.x > -4.0f && p.x < 0.0f && std::abs(p.z) < 6.0f) {
            EXPECT_EQ(a[i].y, 1.0f) << p.x;
            ++coveredFloor;
        }
        if (floor && p.x > 4.0f && std::abs(p.z) < 6.0f) {
            EXPECT_EQ(a[i].y, 0.0f) << p.x;
            EXPECT_LT(a[i].x, 0.05f) << p.x; // flat, open ground
            ++openFloor;
        }
        // The floor right at the pillar's foot: an inner corner.
        if (std::abs(p.y) < 0.3f && std::abs(p.x + 6.0f) < 0.3f && std::abs(p.z) < 6.0f) {
            cornerCavity += a[i].x;
            ++corner;
        }
    }
    EXPECT_GT(coveredFloor, 50);
    EXPECT_GT(openFloor, 50);
    ASSERT_GT(corner, 5);
    std::cout << "mean cavity at the inner corner: " << cornerCavity / corner << std::endl;
    EXPECT_GT(cornerCavity / corner, 0.08); // the bevelled corner vertex; open ground stays below 0.05
}

TEST(SurfaceAttributes, NeedsNormalsAndALevelSet)
{
    openvdb::initialize();
    const auto sphere = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(2.0f, openvdb::Vec3f(0.0f), 0.25f);
    TriangleMesh mesh = meshOf(*sphere);
    mesh.normals.clear();
    EXPECT_THROW(computeSurfaceAttributes(*sphere, mesh), strata::Error);
    auto fog = sphere->deepCopy();
    fog->setGridClass(openvdb::GRID_FOG_VOLUME);
    EXPECT_THROW(computeSurfaceAttributes(*fog, meshOf(*sphere)), strata::Error);
}
