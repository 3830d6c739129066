// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The `cave` camera preset on synthetic level sets: an enclosed cavity, the
// same cavity with a tunnel to the region's side, and solid rock.

#include <strata/scene/CaveView.h>

#include <strata/Error.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <functional>

namespace {

using strata::scene::CaveView;
using strata::scene::findCaveView;

const glm::dvec3 REGION_MIN(-10.0, -5.0, -10.0);
const glm::dvec3 REGION_MAX(10.0, 15.0, 10.0);
const glm::dvec3 CAVITY(-3.0, 4.0, 1.0);

/// A level set (0.5 m voxels, negative in rock) of `sdf` over the region.
openvdb::FloatGrid::Ptr levelSet(const std::function<double(const glm::dvec3&)>& sdf)
{
    const double voxel = 0.5;
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(float(3.0 * voxel));
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxel));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    auto accessor = grid->getAccessor();
    for (int k = -22; k <= 22; ++k) {
        for (int j = -12; j <= 32; ++j) {
            for (int i = -22; i <= 22; ++i) {
                const double value = sdf(glm::dvec3(i, j, k) * voxel);
                accessor.setValue(openvdb::Coord(i, j, k), float(std::clamp(value, -3.0 * voxel, 3.0 * voxel)));
            }
        }
    }
    return grid;
}

/// Rock below y = 10 (the surface), open air above.
double ground(const glm::dvec3& p)
{
    return p.y - 10.0;
}
/// A spherical cavity of radius 3.5 m.
double cavity(const glm::dvec3& p)
{
    return glm::length(p - CAVITY) - 3.5;
}
/// A tunnel of radius 1.5 m from the cavity along +X to the region's side.
double tunnel(const glm::dvec3& p)
{
    const double along = std::max(CAVITY.x - p.x, 0.0);
    return std::sqrt(along * along + (p.y - CAVITY.y) * (p.y - CAVITY.y) + (p.z - CAVITY.z) * (p.z - CAVITY.z)) - 1.5;
}

double valueAt(const openvdb::FloatGrid& grid, const glm::dvec3& p)
{
    return grid.getConstAccessor().getValue(grid.transform().worldToIndexCellCentered(openvdb::Vec3d(p.x, p.y, p.z)));
}

} // namespace

TEST(CaveView, EnclosedCavityIsViewedFromItsCentreAlongItsAxis)
{
    const auto grid = levelSet([](const glm::dvec3& p) { return std::max(ground(p), -cavity(p)); });
    const CaveView view = findCaveView(*grid, REGION_MIN, REGION_MAX);
    EXPECT_EQ(view.caveCount, 1u);
    EXPECT_FALSE(view.looksOut);
    // The most interior cell of a sphere is its centre (within a cell).
    EXPECT_LE(glm::length(view.camera.position - CAVITY), 1.0 + 1e-9) << view.camera.position.x;
    EXPECT_GT(valueAt(*grid, view.camera.position), 0.0); // in air
    EXPECT_GE(view.clearance, 2.0);
    EXPECT_GT(glm::length(view.camera.target - view.camera.position), 0.5);
    EXPECT_GT(view.camera.nearPlane, 0.0);
    EXPECT_GT(view.camera.farPlane, view.camera.nearPlane);
    // Deterministic.
    const CaveView again = findCaveView(*grid, REGION_MIN, REGION_MAX);
    EXPECT_EQ(again.camera.position, view.camera.position);
    EXPECT_EQ(again.camera.target, view.camera.target);
}

TEST(CaveView, LooksThroughTheTunnelOutOfTheCave)
{
    const auto grid =
        levelSet([](const glm::dvec3& p) { return std::max(ground(p), -std::min(cavity(p), tunnel(p))); });
    const CaveView view = findCaveView(*grid, REGION_MIN, REGION_MAX);
    EXPECT_EQ(view.caveCount, 1u);
    EXPECT_TRUE(view.looksOut);
    EXPECT_GT(valueAt(*grid, view.camera.position), 0.0);
    // Towards +X, where the tunnel opens at the region's side.
    const glm::dvec3 forward = glm::normalize(view.camera.target - view.camera.position);
    EXPECT_GT(forward.x, 0.9) << forward.x << " " << forward.y << " " << forward.z;
    EXPECT_GT(view.camera.target.x, REGION_MAX.x - 0.5);
}

TEST(CaveView, LargestOfTwoCavesWins)
{
    const glm::dvec3 small(5.0, 2.0, -5.0);
    const auto grid = levelSet([&](const glm::dvec3& p) {
        const double second = glm::length(p - small) - 2.0;
        return std::max(ground(p), -std::min(cavity(p), second));
    });
    const CaveView view = findCaveView(*grid, REGION_MIN, REGION_MAX);
    EXPECT_EQ(view.caveCount, 2u);
    EXPECT_LE(glm::length(view.camera.position - CAVITY), 1.0 + 1e-9);
}

TEST(CaveView, SolidRockHasNoCave)
{
    const auto grid = levelSet(ground);
    EXPECT_THROW(findCaveView(*grid, REGION_MIN, REGION_MAX), strata::Error);
    try {
        findCaveView(*grid, REGION_MIN, REGION_MAX);
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("--view cave: the terrain has no cave"), std::string::npos) << e.what();
    }
    EXPECT_THROW(findCaveView(*grid, REGION_MIN, REGION_MIN), strata::Error);
}
