// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Each terrain layer's share of a surface point as the terrain shader
/// paints the layers before its height blend (shaders/TerrainLayers.h,
/// steps 1 and 2): the rule's coverage c_i (bands on altitude, slope,
/// cavity, cover, the landform masks, the noise mask, times the opacity),
/// then painter's order a_i = c_i · Π_{j>i} (1 − c_j), layer 0 the base
/// with c_0 = 1. The a_i sum to 1. Evaluated by the shared header itself,
/// so weight maps exported for an engine's terrain follow the same rules
/// as Strata's own renderers.

#include <strata/render/Material.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <memory>
#include <vector>

namespace strata::render {

class LayerCoverage
{
public:
    /// Layer 0 (the base) plus one layer per rule, in painter's order, for
    /// points given relative to `origin` (metres; kept in double, so the
    /// bands and the noise hold far from the world origin). The rules must
    /// have passed checkMaterial() (at most MAX_MATERIAL_LAYERS − 1).
    LayerCoverage(const std::vector<LayerRule>& rules, const glm::dvec3& origin);
    ~LayerCoverage();
    LayerCoverage(LayerCoverage&&) noexcept;
    LayerCoverage& operator=(LayerCoverage&&) noexcept;

    int layerCount() const;

    /// Writes layerCount() shares a_i to `out`. `position` is relative to
    /// the origin, `normal` the unit surface normal, `surface` the cavity
    /// and cover (0..1), `landform` (flow, wear, deposition, water),
    /// `rock` (hardness, bed).
    void shares(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& surface,
                const glm::vec4& landform, const glm::vec2& rock, float* out) const;

private:
    struct Params;
    std::unique_ptr<Params> mParams;
};

} // namespace strata::render
