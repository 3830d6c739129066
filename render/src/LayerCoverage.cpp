// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/LayerCoverage.h>

#include "LayerSetup.h"

#include <algorithm>

namespace strata::render {

struct LayerCoverage::Params
{
    std::vector<shading::LayerParams> layers;
};

LayerCoverage::LayerCoverage(const std::vector<LayerRule>& rules, const glm::dvec3& origin)
    : mParams(std::make_unique<Params>())
{
    const std::size_t count = std::min<std::size_t>(rules.size(), STRATA_MAX_LAYERS - 1);
    mParams->layers.push_back(detail::ruleParams(nullptr, origin));
    for (std::size_t i = 0; i < count; ++i) mParams->layers.push_back(detail::ruleParams(&rules[i], origin));
}

LayerCoverage::~LayerCoverage() = default;
LayerCoverage::LayerCoverage(LayerCoverage&&) noexcept = default;
LayerCoverage& LayerCoverage::operator=(LayerCoverage&&) noexcept = default;

int LayerCoverage::layerCount() const { return int(mParams->layers.size()); }

void LayerCoverage::shares(const glm::vec3& position, const glm::vec3& normal, const glm::vec2& surface,
                           const glm::vec4& landform, const glm::vec2& rock, float* out) const
{
    // Painter's order from the top layer down: what lies above hides.
    float above = 1.0f;
    for (int i = layerCount() - 1; i >= 0; --i) {
        const float c = i == 0 ? 1.0f
                               : shading::layerCoverage(mParams->layers[std::size_t(i)], normal, position, surface,
                                                        landform, rock);
        out[i] = c * above;
        above *= 1.0f - c;
    }
}

} // namespace strata::render
