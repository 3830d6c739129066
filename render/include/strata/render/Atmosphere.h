// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The sky and aerial perspective of a Lighting (shaders/Atmosphere.h).

#include <glm/vec3.hpp>

namespace strata::render {

/// The sky and aerial perspective (shaders/Atmosphere.h), the same on both
/// renderers: a sky gradient from the horizon to the zenith with the sun's
/// glow and disc instead of the flat Lighting::skyColor, and exponential
/// height fog that fades distant terrain into the horizon colour. Off by
/// default in the library (a diorama keeps its flat background); the scene
/// file's [atmosphere] table turns it on by default.
struct Atmosphere
{
    bool enabled = false;
    glm::vec3 zenithColor{0.16f, 0.32f, 0.75f};  ///< sky radiance straight up, linear
    glm::vec3 horizonColor{0.7f, 0.8f, 0.95f};   ///< sky radiance at the horizon; the fog's colour
    float fogDensity = 1.5e-4f;     ///< extinction per metre at fogBaseHeight, 0..1 (0: no fog)
    float fogFalloff = 1.0f / 500.0f; ///< per metre of height, 0..1: density × e^(−falloff·(y − base))
    double fogBaseHeight = 0.0;     ///< world metres (double: worlds far from the origin)
    float sunGlow = 0.25f;          ///< 0..100: the forward-scattered glow around the sun, × sunColor
    float sunDiscRadius = 1.5f;     ///< degrees, 0..20 (below 0.1: no disc)
};

/// Throws strata::Error "atmosphere: KEY = VALUE outside RANGE" for a value
/// out of its documented range (NaN and infinity included). Both renderers
/// call it before drawing with the atmosphere on.
void checkAtmosphere(const Atmosphere& atmosphere);

} // namespace strata::render
