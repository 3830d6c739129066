// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/Camera.h>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <cmath>

namespace {

using namespace strata::render;

glm::vec4 toClip(const Camera& camera, double aspect, const glm::dvec3& point, const glm::dvec3& origin)
{
    const glm::vec3 local(point - origin);
    return projectionMatrix(camera, aspect) * viewMatrix(camera, origin) * glm::vec4(local, 1.0f);
}

TEST(Camera, OrbitAtAzimuthZeroLooksTowardsMinusZ)
{
    const Camera camera = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 0.0, 0.0);
    EXPECT_NEAR(camera.position.x, 0.0, 1e-12);
    EXPECT_NEAR(camera.position.y, 0.0, 1e-12);
    EXPECT_GT(camera.position.z, 1.0);
    EXPECT_EQ(camera.target, glm::dvec3(0.0));
    EXPECT_NEAR(camera.up.y, 1.0, 1e-12);

    const Camera turned = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 90.0, 0.0);
    EXPECT_GT(turned.position.x, 1.0); // looking towards −X
    const Camera above = orbitCamera(glm::dvec3(-1.0), glm::dvec3(1.0), 0.0, 30.0);
    EXPECT_GT(above.position.y, 0.5);
}

TEST(Camera, OrbitFitsTheBoxInsideTheFrustum)
{
    const glm::dvec3 lo{-3.0, 0.0, -2.0};
    const glm::dvec3 hi{5.0, 4.0, 6.0};
    for (double azimuth : {0.0, 37.0, 135.0, 250.0}) {
        for (double elevation : {-60.0, 0.0, 30.0, 89.0, 90.0}) {
            const Camera camera = orbitCamera(lo, hi, azimuth, elevation, 45.0);
            EXPECT_GT(camera.nearPlane, 0.0);
            EXPECT_GT(camera.farPlane, camera.nearPlane);
            for (int corner = 0; corner < 8; ++corner) {
                const glm::dvec3 p{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
                const glm::vec4 clip = toClip(camera, 1.0, p, glm::dvec3(0.0));
                SCOPED_TRACE(::testing::Message() << "azimuth " << azimuth << " elevation " << elevation);
                ASSERT_TRUE(std::isfinite(clip.x) && std::isfinite(clip.w));
                EXPECT_GT(clip.w, 0.0f);
                EXPECT_LE(std::abs(clip.x), clip.w * 1.0001f);
                EXPECT_LE(std::abs(clip.y), clip.w * 1.0001f);
                EXPECT_LE(std::abs(clip.z), clip.w * 1.0001f);
            }
        }
    }
}

TEST(Camera, ViewRelativeToAFarOriginKeepsPrecision)
{
    const glm::dvec3 origin{1.0e7, 250.0, -3.0e6};
    Camera camera;
    camera.position = origin + glm::dvec3(0.0, 10.0, 20.0);
    camera.target = origin + glm::dvec3(1.0, 0.0, 0.0);
    Camera local = camera;
    local.position -= origin;
    local.target -= origin;
    const glm::dvec3 point = origin + glm::dvec3(0.25, 0.5, -0.125);
    const glm::vec4 far = toClip(camera, 1.5, point, origin);
    const glm::vec4 ref = toClip(local, 1.5, point - origin, glm::dvec3(0.0));
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(far[i], ref[i], 1e-5f);
    }
}

TEST(Camera, ProjectionMapsNearAndFarToMinusOneAndOne)
{
    Camera camera;
    camera.position = glm::dvec3(0.0);
    camera.target = glm::dvec3(0.0, 0.0, -1.0);
    camera.nearPlane = 0.5;
    camera.farPlane = 100.0;
    const glm::vec4 n = toClip(camera, 1.0, glm::dvec3(0.0, 0.0, -0.5), glm::dvec3(0.0));
    const glm::vec4 f = toClip(camera, 1.0, glm::dvec3(0.0, 0.0, -100.0), glm::dvec3(0.0));
    EXPECT_NEAR(n.z / n.w, -1.0f, 1e-5f);
    EXPECT_NEAR(f.z / f.w, 1.0f, 1e-4f);
}

} // namespace
