// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The viewer's orbit and fly cameras (apps/strata-view/ViewerCamera.h).

#include "ViewerCamera.h"

#include <glm/geometric.hpp>

#include <gtest/gtest.h>

namespace {

using strata::view::ViewerCamera;

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-9)
{
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

strata::render::Camera lookingAt(const glm::dvec3& position, const glm::dvec3& target)
{
    strata::render::Camera c;
    c.position = position;
    c.target = target;
    c.nearPlane = 0.5;
    c.farPlane = 500.0;
    c.fovYDegrees = 40.0;
    return c;
}

TEST(ViewerCamera, StartsFromARenderCameraWithTheSameView)
{
    const auto start = lookingAt({10.0, 20.0, 30.0}, {-5.0, 2.0, 4.0});
    const ViewerCamera v = ViewerCamera::from(start);
    EXPECT_EQ(v.mode, ViewerCamera::Mode::Orbit);
    const strata::render::Camera c = v.camera();
    expectNear(c.position, start.position);
    expectNear(glm::normalize(c.target - c.position), glm::normalize(start.target - start.position));
    EXPECT_DOUBLE_EQ(c.fovYDegrees, 40.0);
    EXPECT_GT(c.farPlane, glm::length(start.target - start.position));
    EXPECT_GT(c.nearPlane, 0.0);
    EXPECT_LT(c.nearPlane, c.farPlane);
    // Yaw 0 looks towards −Z; positive yaw turns left (towards −X).
    ViewerCamera w;
    w.mode = ViewerCamera::Mode::Fly;
    expectNear(w.forward(), {0.0, 0.0, -1.0});
    w.rotate(90.0, 0.0);
    expectNear(w.forward(), {-1.0, 0.0, 0.0});
}

TEST(ViewerCamera, OrbitRotatesAndZoomsAroundTheTarget)
{
    ViewerCamera v = ViewerCamera::from(lookingAt({0.0, 0.0, 50.0}, {0.0, 0.0, 0.0}));
    v.rotate(90.0, 30.0);
    expectNear(v.camera().target - v.camera().position, glm::normalize(-v.eye()), 1e-9);
    EXPECT_NEAR(glm::length(v.eye() - v.target), 50.0, 1e-9);
    v.zoom(1.0);
    EXPECT_NEAR(glm::length(v.eye() - v.target), 45.0, 1e-9);
    v.zoom(-2.0);
    EXPECT_NEAR(glm::length(v.eye() - v.target), 45.0 / 0.81, 1e-9);
    // Pitch stops short of the poles (the up vector stays defined).
    v.rotate(0.0, 500.0);
    EXPECT_DOUBLE_EQ(v.pitch, 89.0);
    v.rotate(0.0, -500.0);
    EXPECT_DOUBLE_EQ(v.pitch, -89.0);
    // Moving an orbit moves its target horizontally.
    v.pitch = -45.0;
    v.yaw = 0.0;
    v.move(0.0, 0.0, 10.0);
    expectNear(v.target, {0.0, 0.0, -10.0}, 1e-6);
}

TEST(ViewerCamera, FlyMovesAlongTheViewAndTogglingKeepsTheView)
{
    ViewerCamera v = ViewerCamera::from(lookingAt({0.0, 10.0, 40.0}, {0.0, 10.0, 0.0}));
    const glm::dvec3 eye = v.eye();
    const glm::dvec3 forward = v.forward();
    v.toggleMode();
    EXPECT_EQ(v.mode, ViewerCamera::Mode::Fly);
    expectNear(v.eye(), eye);
    expectNear(v.forward(), forward);
    v.move(0.0, 0.0, 5.0);
    expectNear(v.eye(), {0.0, 10.0, 35.0});
    v.move(2.0, 1.0, 0.0); // right is +X when looking towards −Z; up is world +Y
    expectNear(v.eye(), {2.0, 11.0, 35.0});
    v.zoom(3.0); // no zoom in fly mode
    expectNear(v.eye(), {2.0, 11.0, 35.0});
    v.toggleMode(); // back to orbit: around the point `distance` ahead
    EXPECT_EQ(v.mode, ViewerCamera::Mode::Orbit);
    expectNear(v.eye(), {2.0, 11.0, 35.0}, 1e-9);
    expectNear(v.target, glm::dvec3(2.0, 11.0, 35.0) + forward * v.distance, 1e-9);
}

} // namespace
