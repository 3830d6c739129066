// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/Atmosphere.h>

#include "AtmosphereSetup.h"

#include <strata/Error.h>

#include "RangeCheck.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <sstream>

namespace strata::render {

void checkAtmosphere(const Atmosphere& a)
{
    auto range = [](const char* key, double value, double lo, double hi) {
        detail::checkRange("atmosphere", key, value, lo, hi);
    };
    for (int c = 0; c < 3; ++c) {
        range("zenithColor", a.zenithColor[c], 0.0, 1e3);
        range("horizonColor", a.horizonColor[c], 0.0, 1e3);
    }
    range("fogDensity", a.fogDensity, 0.0, 1.0);
    range("fogFalloff", a.fogFalloff, 0.0, 1.0);
    range("fogBaseHeight", a.fogBaseHeight, -1e9, 1e9);
    range("sunGlow", a.sunGlow, 0.0, 100.0);
    range("sunDiscRadius", a.sunDiscRadius, 0.0, 20.0);
}

namespace detail {

shading::AtmosphereParams makeAtmosphereParams(const Lighting& lighting, const Camera& camera,
                                               const glm::dvec3& origin, int width, int height)
{
    shading::AtmosphereParams p{};
    p.enabled = lighting.atmosphere.enabled ? 1 : 0;
    p.viewportSize = glm::vec2(float(width), float(height));
    p.sunDiscCos = 2.0f;
    p.skyRayMatrix = glm::mat4(1.0f);
    p.exposure = lighting.exposure;
    if (p.enabled == 0) {
        return p;
    }
    const Atmosphere& a = lighting.atmosphere;
    checkAtmosphere(a);
    // The view without its translation: device coordinates map to a ray's
    // direction, whatever the camera's distance from the origin.
    const glm::mat4 rotation(glm::mat3(viewMatrix(camera, camera.position)));
    const glm::dmat4 rayToClip(projectionMatrix(camera, double(width) / double(height)) * rotation);
    p.skyRayMatrix = glm::mat4(glm::inverse(rayToClip));
    p.zenithColor = a.zenithColor;
    p.horizonColor = a.horizonColor;
    p.fogDensity = a.fogDensity;
    p.fogFalloff = a.fogFalloff;
    p.fogBaseHeight = float(a.fogBaseHeight - origin.y);
    p.sunDirection = unitOr(lighting.sunDirection, glm::vec3(0.0f, 1.0f, 0.0f));
    p.sunColor = lighting.sunColor;
    p.sunGlow = a.sunGlow;
    if (a.sunDiscRadius >= 0.1f) {
        p.sunDiscCos = float(std::cos(double(a.sunDiscRadius) * (3.14159265358979323846 / 180.0)));
    }
    return p;
}

} // namespace detail

} // namespace strata::render
