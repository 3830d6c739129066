// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the sun's shadow-map projection fitted to a mesh, shared by the
// GL and the CPU renderer so that both look up the same map (shaders/Shadow.h).

#include "ShadingBridge.h"

#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace strata::render::detail {

static_assert(sizeof(shading::ShadowParams) == 96, "ShadowParams must match its std140 block (terrain.frag)");
static_assert(offsetof(shading::ShadowParams, lightViewProjection) == 0);
static_assert(offsetof(shading::ShadowParams, lightDirection) == 64);
static_assert(offsetof(shading::ShadowParams, texelSize) == 76); // a float may follow a vec3 in std140
static_assert(offsetof(shading::ShadowParams, normalBias) == 80);
static_assert(offsetof(shading::ShadowParams, depthBias) == 84);
static_assert(offsetof(shading::ShadowParams, resolution) == 88);
static_assert(offsetof(shading::ShadowParams, enabled) == 92);

/// Binding point of the shadow block and texture unit of the shadow map in
/// the terrain program (terrain.frag).
inline constexpr unsigned SHADOW_BLOCK_BINDING = 3;
inline constexpr unsigned SHADOW_MAP_UNIT = 9;

/// Axis-aligned bounds of a mesh's vertices (mesh-relative metres); empty
/// (lo > hi) without vertices. O(vertexCount).
struct MeshBounds
{
    glm::vec3 lo{std::numeric_limits<float>::infinity()};
    glm::vec3 hi{-std::numeric_limits<float>::infinity()};
    bool empty() const { return !(lo.x <= hi.x); }
};

inline MeshBounds meshBounds(const MeshView& mesh)
{
    MeshBounds b;
    if (mesh.indexCount == 0) {
        return b;
    }
    for (std::size_t i = 0; i < mesh.vertexCount; ++i) {
        b.lo = glm::min(b.lo, mesh.positions[i]);
        b.hi = glm::max(b.hi, mesh.positions[i]);
    }
    return b;
}

/// The shadow parameters for a mesh with `bounds`: an orthographic view
/// along the sun direction (towards −sunDirection) whose square footprint
/// and depth range hold the bounding box plus a margin of normalBias +
/// depthBias + 2 texels, so that the biased lookups of mesh points fall
/// inside the map. Computed in double, returned in float (the same float
/// matrix on both renderers). `enabled` is 0 when shadows are off or the
/// mesh is empty.
inline shading::ShadowParams makeShadowParams(const MeshBounds& bounds, const Lighting& lighting,
                                              const ShadowOptions& options)
{
    shading::ShadowParams sp{};
    sp.lightViewProjection = glm::mat4(1.0f);
    sp.lightDirection = toShading(lighting).lights[0].direction;
    sp.texelSize = 0.0f;
    sp.normalBias = options.normalBias;
    sp.depthBias = options.depthBias;
    sp.resolution = options.resolution;
    sp.enabled = 0;
    if (!options.enabled || bounds.empty()) {
        return sp;
    }
    constexpr double INF = std::numeric_limits<double>::infinity();
    const glm::dvec3 lo(bounds.lo), hi(bounds.hi);
    const glm::dvec3 towardsSun(sp.lightDirection);
    const glm::dvec3 up = std::abs(towardsSun.y) < 0.9 ? glm::dvec3(0.0, 1.0, 0.0) : glm::dvec3(0.0, 0.0, 1.0);
    const glm::dvec3 centre = 0.5 * (lo + hi);
    const glm::dmat4 view = glm::lookAtRH(centre + towardsSun, centre, up);
    glm::dvec3 viewLo(INF), viewHi(-INF);
    for (int i = 0; i < 8; ++i) {
        const glm::dvec3 corner(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
        const glm::dvec3 v(view * glm::dvec4(corner, 1.0));
        viewLo = glm::min(viewLo, v);
        viewHi = glm::max(viewHi, v);
    }
    const double resolution = double(options.resolution);
    const double extent = std::max({viewHi.x - viewLo.x, viewHi.y - viewLo.y, 1e-6});
    const double margin = (double(sp.normalBias) + double(sp.depthBias) + 2.0) * extent / resolution;
    const double half = 0.5 * extent + margin;
    const double cx = 0.5 * (viewLo.x + viewHi.x);
    const double cy = 0.5 * (viewLo.y + viewHi.y);
    const double depthMargin = std::max(margin, 1e-3 * extent);
    // The view looks down −Z: depths run from −viewHi.z (nearest) to −viewLo.z.
    const glm::dmat4 projection =
        glm::orthoRH_NO(cx - half, cx + half, cy - half, cy + half, -viewHi.z - depthMargin, -viewLo.z + depthMargin);
    sp.lightViewProjection = glm::mat4(projection * view);
    sp.texelSize = float(2.0 * half / resolution);
    sp.enabled = 1;
    return sp;
}

} // namespace strata::render::detail
