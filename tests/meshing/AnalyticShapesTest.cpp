// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/meshing/AnalyticShapes.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

using namespace strata::meshing;

TEST(AnalyticShapes, DistancesAndGradientsAreExact)
{
    const AnalyticShape sphere = analyticSphere({1, 2, 3}, 2.0);
    EXPECT_DOUBLE_EQ(sphere.distance({1, 2, 3}), -2.0);
    EXPECT_DOUBLE_EQ(sphere.distance({4, 2, 3}), 1.0);
    EXPECT_EQ(sphere.gradient({1, 5, 3}), glm::dvec3(0, 1, 0));

    const AnalyticShape box = analyticBox({0, 0, 0}, {2, 4, 6});
    EXPECT_DOUBLE_EQ(box.volume, 48.0);
    EXPECT_DOUBLE_EQ(box.distance({1, 1, 1}), -1.0);           // nearest faces x = 0, x = 2, y = 0, z = 0
    EXPECT_DOUBLE_EQ(box.distance({3, 2, 3}), 1.0);            // beside the +x face
    EXPECT_DOUBLE_EQ(box.distance({3, 5, 3}), std::sqrt(2.0)); // beyond the edge x = 2, y = 4
    EXPECT_EQ(box.gradient({3, 2, 3}), glm::dvec3(1, 0, 0));

    const AnalyticShape torus = analyticTorus({0, 0, 0}, 3.0, 1.0);
    EXPECT_DOUBLE_EQ(torus.distance({3, 0, 0}), -1.0);
    EXPECT_DOUBLE_EQ(torus.distance({0, 0, 0}), 2.0);
    EXPECT_NEAR(glm::length(torus.gradient({4.5, 0.3, 0.2})), 1.0, 1e-12);
    EXPECT_FALSE(analyticGyroid(6.0, 1.0, 5.0).exact);
}

TEST(AnalyticShapes, LevelSetHasTheBandAndTheSigns)
{
    const AnalyticShape sphere = analyticSphere({0, 0, 0}, 2.0);
    const openvdb::FloatGrid::Ptr grid = levelSetFromShape(sphere, 0.25, 3.0);
    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 0.25);
    EXPECT_FLOAT_EQ(grid->background(), 0.75f);
    const auto accessor = grid->getConstAccessor();
    EXPECT_FLOAT_EQ(accessor.getValue(openvdb::Coord(8, 0, 0)), 0.0f);   // on the surface
    EXPECT_FLOAT_EQ(accessor.getValue(openvdb::Coord(9, 0, 0)), 0.25f);  // one voxel out
    EXPECT_FLOAT_EQ(accessor.getValue(openvdb::Coord(0, 0, 0)), -0.75f); // deep inside: -background
    EXPECT_FLOAT_EQ(accessor.getValue(openvdb::Coord(20, 0, 0)), 0.75f);
    for (auto it = grid->cbeginValueOn(); it; ++it) EXPECT_LT(std::abs(*it), 0.75f);
    EXPECT_THROW(levelSetFromShape(sphere, 0.0), strata::Error);
}
