// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the public Atmosphere as the shared header's AtmosphereParams for
// one frame (shaders/Atmosphere.h), shared by the GL and the CPU renderer so
// that both draw the same sky and fog.

#include "ShadingBridge.h"

#include <strata/render/Camera.h>
#include <strata/render/Material.h>

#include <glm/vec3.hpp>

#include <cstddef>

namespace strata::render::detail {

static_assert(sizeof(shading::AtmosphereParams) == 160, "AtmosphereParams must match its std140 block");
static_assert(offsetof(shading::AtmosphereParams, skyRayMatrix) == 0);
static_assert(offsetof(shading::AtmosphereParams, zenithColor) == 64);
static_assert(offsetof(shading::AtmosphereParams, fogDensity) == 76); // a float may follow a vec3 in std140
static_assert(offsetof(shading::AtmosphereParams, horizonColor) == 80);
static_assert(offsetof(shading::AtmosphereParams, fogFalloff) == 92);
static_assert(offsetof(shading::AtmosphereParams, sunDirection) == 96);
static_assert(offsetof(shading::AtmosphereParams, fogBaseHeight) == 108);
static_assert(offsetof(shading::AtmosphereParams, sunColor) == 112);
static_assert(offsetof(shading::AtmosphereParams, sunGlow) == 124);
static_assert(offsetof(shading::AtmosphereParams, viewportSize) == 128); // vec2: aligned to 8
static_assert(offsetof(shading::AtmosphereParams, sunDiscCos) == 136);
static_assert(offsetof(shading::AtmosphereParams, enabled) == 140);
static_assert(offsetof(shading::AtmosphereParams, exposure) == 144);

/// Binding point of the atmosphere block in the terrain and sky programs.
inline constexpr unsigned ATMOSPHERE_BLOCK_BINDING = 4;

/// The frame's atmosphere: `lighting.atmosphere` (checked when enabled)
/// for `camera` over a `width` × `height` viewport, with heights relative
/// to the mesh `origin` (subtracted in double). enabled = 0 when it is off.
/// Throws strata::Error for an atmosphere out of range.
shading::AtmosphereParams makeAtmosphereParams(const Lighting& lighting, const Camera& camera,
                                               const glm::dvec3& origin, int width, int height);

} // namespace strata::render::detail
