// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The sky and aerial perspective of shaders/Atmosphere.h, compiled as C++
// through the shading prelude, and the host side that fills its parameters
// (render/src/AtmosphereSetup.h): fog against a numerical integral, the sky
// meeting the fog at the horizon, the view rays of the sky pass, and the
// extremes (zero and huge densities, heights 1e9 m away, degenerate rays).
// GL against CPU with the atmosphere on is in ExtremesTest.cpp and
// RenderParityTest.cpp.

#include <strata/Error.h>
#include <strata/render/Atmosphere.h>
#include <strata/render/Camera.h>
#include <strata/render/Material.h>

#include "AtmosphereSetup.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <limits>
#include <string>

namespace {

using namespace strata::render;
namespace shading = strata::shading;

shading::AtmosphereParams fogParams(float density, float falloff, float baseHeight)
{
    shading::AtmosphereParams a{};
    a.enabled = 1;
    a.fogDensity = density;
    a.fogFalloff = falloff;
    a.fogBaseHeight = baseHeight;
    a.horizonColor = glm::vec3(0.7f, 0.8f, 0.95f);
    a.zenithColor = glm::vec3(0.1f, 0.2f, 0.6f);
    a.sunDirection = glm::normalize(glm::vec3(0.3f, 0.5f, -0.8f));
    a.sunColor = glm::vec3(2.0f);
    a.sunGlow = 0.5f;
    a.sunDiscCos = 2.0f; // no disc
    a.skyRayMatrix = glm::mat4(1.0f);
    return a;
}

/// The optical depth of the same fog by the midpoint rule in double.
double integratedDepth(double density, double falloff, double base, glm::dvec3 from, glm::dvec3 to)
{
    const int steps = 20000;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const glm::dvec3 p = from + (to - from) * ((i + 0.5) / steps);
        sum += std::exp(-falloff * (p.y - base));
    }
    return density * glm::length(to - from) * sum / steps;
}

TEST(Atmosphere, FogDepthMatchesTheIntegralOfTheDensity)
{
    const float base = 12.0f;
    const glm::vec3 camera(0.0f, 40.0f, 0.0f);
    // Level, rising, falling, nearly level (the series) and steep rays.
    const glm::vec3 targets[] = {{500.0f, 40.0f, 0.0f},  {300.0f, 90.0f, 40.0f}, {-200.0f, 0.0f, 300.0f},
                                 {800.0f, 40.001f, 0.0f}, {10.0f, -300.0f, 5.0f}, {0.0f, 600.0f, 1.0f}};
    for (const float falloff : {0.0f, 0.002f, 0.05f}) {
        const shading::AtmosphereParams a = fogParams(0.003f, falloff, base);
        for (const glm::vec3& target : targets) {
            const double expected = integratedDepth(0.003, falloff, base, camera, target);
            const double got = shading::fogOpticalDepth(a, camera, target);
            EXPECT_NEAR(got, expected, 1e-4 * expected + 1e-7)
                << "falloff " << falloff << " to (" << target.x << ", " << target.y << ", " << target.z << ")";
        }
    }
}

TEST(Atmosphere, FogIsSymmetricAndZeroForNoDistanceOrNoDensity)
{
    const shading::AtmosphereParams a = fogParams(0.01f, 0.02f, 0.0f);
    const glm::vec3 p(10.0f, 5.0f, -3.0f);
    const glm::vec3 q(-250.0f, 80.0f, 120.0f);
    EXPECT_NEAR(shading::fogOpticalDepth(a, p, q), shading::fogOpticalDepth(a, q, p),
                1e-5f * shading::fogOpticalDepth(a, p, q));
    EXPECT_EQ(shading::fogOpticalDepth(a, p, p), 0.0f);
    EXPECT_EQ(shading::fogOpticalDepth(fogParams(0.0f, 0.02f, 0.0f), p, q), 0.0f);

    // No fog: the surface's radiance passes unchanged, also with the atmosphere on.
    const glm::vec3 radiance(0.3f, 0.5f, 0.7f);
    EXPECT_EQ(shading::applyAerialPerspective(fogParams(0.0f, 0.02f, 0.0f), radiance, p, q), radiance);
    shading::AtmosphereParams off = fogParams(1.0f, 0.0f, 0.0f);
    off.enabled = 0;
    EXPECT_EQ(shading::applyAerialPerspective(off, radiance, p, q), radiance);
}

TEST(Atmosphere, DistantTerrainFadesIntoTheHorizonItStandsAgainst)
{
    const shading::AtmosphereParams a = fogParams(0.002f, 0.0f, 0.0f);
    const glm::vec3 camera(0.0f, 0.0f, 0.0f);
    const glm::vec3 radiance(0.05f, 0.3f, 0.02f);
    // At the horizon the sky is the fog's in-scatter colour, sun glow included.
    for (const glm::vec3 dir : {glm::vec3(1.0f, 0.0f, 0.0f), glm::normalize(glm::vec3(0.3f, 0.0f, -0.8f)),
                                glm::vec3(0.0f, 0.0f, 1.0f)}) {
        const glm::vec3 sky = shading::skyRadiance(a, dir);
        EXPECT_EQ(sky, shading::inscatterRadiance(a, dir));
        // Terrain 20 km away along that ray (transmittance e^-40) shows the sky.
        const glm::vec3 far = shading::applyAerialPerspective(a, radiance, camera, dir * 20000.0f);
        EXPECT_NEAR(glm::length(far - sky), 0.0f, 1e-5f);
        // Near terrain keeps nearly its own colour; in between it is a mix.
        const glm::vec3 near = shading::applyAerialPerspective(a, radiance, camera, dir * 1.0f);
        EXPECT_NEAR(glm::length(near - radiance), 0.0f, 0.01f);
        const glm::vec3 mid = shading::applyAerialPerspective(a, radiance, camera, dir * 350.0f); // e^-0.7
        const float t = std::exp(-0.7f);
        EXPECT_NEAR(glm::length(mid - (radiance * t + sky * (1.0f - t))), 0.0f, 1e-4f);
    }
    // Straight up the sky is the zenith colour plus the sun's glow there.
    const glm::vec3 up(0.0f, 1.0f, 0.0f);
    EXPECT_NEAR(glm::length(shading::skyRadiance(a, up) - (a.zenithColor + shading::sunGlowRadiance(a, up))), 0.0f,
                1e-6f);
    // The glow peaks towards the sun; nothing of it on the far side.
    EXPECT_NEAR(glm::length(shading::sunGlowRadiance(a, a.sunDirection) - a.sunColor * a.sunGlow), 0.0f, 1e-5f);
    EXPECT_EQ(shading::sunGlowRadiance(a, -a.sunDirection), glm::vec3(0.0f));
}

TEST(Atmosphere, SunDiscOnlyWhereAsked)
{
    shading::AtmosphereParams a = fogParams(0.0f, 0.0f, 0.0f);
    const glm::vec3 without = shading::skyRadiance(a, a.sunDirection);
    a.sunDiscCos = std::cos(2.0f * 3.14159265f / 180.0f);
    const glm::vec3 with = shading::skyRadiance(a, a.sunDirection);
    EXPECT_NEAR(glm::length(with - without - a.sunColor * 16.0f), 0.0f, 1e-4f);
    // 5° away: no disc.
    const glm::vec3 aside = glm::normalize(a.sunDirection + glm::vec3(0.09f, 0.0f, 0.0f));
    a.sunDiscCos = std::cos(2.0f * 3.14159265f / 180.0f);
    const glm::vec3 withAside = shading::skyRadiance(a, aside);
    a.sunDiscCos = 2.0f;
    EXPECT_EQ(withAside, shading::skyRadiance(a, aside));
}

// Nothing is NaN or infinite at the extremes: fog 1e9 m below or above the
// camera, the densest fog allowed, the steepest falloff, zero-length and
// degenerate rays.
TEST(Atmosphere, FiniteAtTheExtremes)
{
    const glm::vec3 radiance(0.4f, 0.4f, 0.4f);
    const glm::vec3 positions[] = {{0.0f, 0.0f, 0.0f}, {1e6f, 0.0f, 0.0f}, {0.0f, 1e6f, 0.0f}, {0.0f, -1e6f, 1.0f}};
    for (const float base : {-1e9f, -1e4f, 0.0f, 1e4f, 1e9f}) {
        for (const float falloff : {0.0f, 1e-6f, 1.0f}) {
            for (const float density : {0.0f, 1e-6f, 1.0f}) {
                const shading::AtmosphereParams a = fogParams(density, falloff, base);
                for (const glm::vec3& from : positions) {
                    for (const glm::vec3& to : positions) {
                        const float depth = shading::fogOpticalDepth(a, from, to);
                        EXPECT_TRUE(std::isfinite(depth) && depth >= 0.0f) << depth;
                        const glm::vec3 c = shading::applyAerialPerspective(a, radiance, from, to);
                        EXPECT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
                        EXPECT_GE(glm::min(c.x, glm::min(c.y, c.z)), 0.0f);
                    }
                }
            }
        }
    }
    const shading::AtmosphereParams a = fogParams(0.01f, 0.01f, 0.0f);
    const glm::vec3 sky = shading::skyRadiance(a, glm::vec3(0.0f));
    EXPECT_TRUE(std::isfinite(sky.x) && std::isfinite(sky.y) && std::isfinite(sky.z));
}

Camera lookingAlong(glm::dvec3 position, glm::dvec3 forward)
{
    Camera camera;
    camera.position = position;
    camera.target = position + forward;
    camera.fovYDegrees = 60.0;
    camera.nearPlane = 0.5;
    camera.farPlane = 5000.0;
    return camera;
}

// The sky pass's rays: the centre of the view looks along the camera's
// axis, the top edge fovY / 2 above it, wherever the camera is (1e7 m out
// included: the ray matrix has no translation).
TEST(Atmosphere, SkyRaysFollowTheCamera)
{
    Lighting lighting;
    lighting.atmosphere.enabled = true;
    for (const glm::dvec3 position : {glm::dvec3(0.0), glm::dvec3(1e7, 3e3, -1e7)}) {
        const glm::dvec3 forward = glm::normalize(glm::dvec3(0.6, -0.3, -0.74));
        const Camera camera = lookingAlong(position, forward);
        const shading::AtmosphereParams a = detail::makeAtmosphereParams(lighting, camera, position, 1600, 900);
        const glm::vec3 centre = shading::skyRayDirection(a, glm::vec2(0.0f));
        EXPECT_NEAR(glm::length(centre - glm::vec3(forward)), 0.0f, 1e-5f);
        const glm::vec3 top = shading::skyRayDirection(a, glm::vec2(0.0f, 1.0f));
        EXPECT_NEAR(std::acos(double(glm::dot(top, glm::vec3(forward)))) * 180.0 / 3.14159265358979, 30.0, 1e-3);
        EXPECT_GT(top.y, centre.y); // y up in device coordinates
        const glm::vec3 right = shading::skyRayDirection(a, glm::vec2(1.0f, 0.0f));
        EXPECT_GT(glm::dot(glm::cross(right, glm::vec3(forward)), glm::vec3(0.0f, 1.0f, 0.0f)), 0.0f)
            << "+x in device coordinates is to the camera's right";
    }
}

// Heights reach the shader relative to the mesh origin, subtracted in
// double: the same scene 1e7 m up gives the same parameters.
TEST(Atmosphere, BaseHeightIsRelativeToTheMeshOrigin)
{
    Lighting lighting;
    lighting.atmosphere.enabled = true;
    lighting.atmosphere.fogBaseHeight = 25.25;
    const Camera camera = lookingAlong(glm::dvec3(0.0, 50.0, 0.0), glm::dvec3(1.0, -0.2, 0.0));
    const shading::AtmosphereParams nearParams =
        detail::makeAtmosphereParams(lighting, camera, glm::dvec3(3.0, 10.0, 4.0), 64, 64);
    lighting.atmosphere.fogBaseHeight += 1e7;
    Camera farCamera = camera;
    farCamera.position.y += 1e7;
    farCamera.target.y += 1e7;
    const shading::AtmosphereParams farParams =
        detail::makeAtmosphereParams(lighting, farCamera, glm::dvec3(3.0, 10.0 + 1e7, 4.0), 64, 64);
    EXPECT_EQ(nearParams.fogBaseHeight, 15.25f);
    EXPECT_EQ(farParams.fogBaseHeight, 15.25f);
    EXPECT_EQ(nearParams.enabled, 1);

    lighting.atmosphere.enabled = false;
    EXPECT_EQ(detail::makeAtmosphereParams(lighting, camera, glm::dvec3(0.0), 64, 64).enabled, 0);
    lighting.atmosphere.sunDiscRadius = 0.0f;
    lighting.atmosphere.enabled = true;
    EXPECT_GE(detail::makeAtmosphereParams(lighting, camera, glm::dvec3(0.0), 64, 64).sunDiscCos, 1.0f);
}

TEST(Atmosphere, OutOfRangeValuesNameTheKey)
{
    auto message = [](const Atmosphere& a) {
        try {
            checkAtmosphere(a);
        } catch (const strata::Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    Atmosphere a;
    EXPECT_EQ(message(a), "");
    a.fogDensity = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(message(a).find("fogDensity"), std::string::npos) << message(a);
    a = Atmosphere{};
    a.horizonColor.g = -0.5f;
    EXPECT_NE(message(a).find("horizonColor = -0.5"), std::string::npos) << message(a);
    a = Atmosphere{};
    a.sunDiscRadius = 45.0f;
    EXPECT_NE(message(a).find("sunDiscRadius"), std::string::npos) << message(a);
    a = Atmosphere{};
    a.fogBaseHeight = std::numeric_limits<double>::infinity();
    EXPECT_NE(message(a).find("fogBaseHeight"), std::string::npos) << message(a);
}

} // namespace
