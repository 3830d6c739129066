// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// C++ prelude of the shared shading headers: GLSL's vocabulary in terms of
/// GLM, inside namespace strata::shading, then the shared headers themselves.
/// The CPU side of Strata (tests, the CPU sampler) includes this file and
/// calls e.g. strata::shading::triplanarWeights(); the GPU side compiles the
/// very same text as GLSL after ShadingPrelude.glsl.
///
/// Not installed: the shared headers are an implementation detail of
/// strata::render.

#include <glm/common.hpp>
#include <glm/exponential.hpp>
#include <glm/trigonometric.hpp>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define STRATA_CPP 1
#define STRATA_INLINE inline
#define INOUT(T) T&
// Feature-set functions (TriplanarMaterial.h): templates on the feature bits
// and the map sampler, whose feature tests are `if constexpr`.
#define STRATA_FEATURE_FUNCTION template <unsigned STRATA_FEATURES, class Maps> inline
#define STRATA_FEATURE_ARGS <STRATA_FEATURES, Maps>
#define STRATA_MAPS_PARAM const Maps &maps,
#define STRATA_MAPS_ARG maps,
// The compile-time set is ANDed with the sampler's run-time `features`: an
// instantiation for one exact set folds every test to a constant, the
// catch-all instantiation (all bits) tests at run time. Either way a
// disabled feature is never evaluated.
#define STRATA_IF_FEATURE(f) if (((STRATA_FEATURES) & (f)) != 0u && (maps.features & (f)) != 0u)
#define STRATA_FEATURE_BITS (STRATA_FEATURES & maps.features)
#define SAMPLE_MAP(map, uv, dUVdx, dUVdy) maps.sample(map, uv, dUVdx, dUVdy)
// Terrain layers (TerrainLayers.h): the sampler switches to layer i and its
// feature set; the layer set is a parameter (a uniform block in GLSL).
#define STRATA_SELECT_LAYER(i, f) maps.select((i), (f))
#define STRATA_LAYERS_PARAM const LayerSetParams &layerSet,
#define LAYER_SET layerSet

namespace strata::shading {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using uint = unsigned;

// GLSL's built-in functions: abs, min, max, clamp, mix, pow, dot, normalize...
using namespace glm;

/// HLSL's saturate, which GLSL lacks: clamp to [0, 1] per component.
inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
inline vec2 saturate(vec2 x) { return glm::clamp(x, vec2(0.0f), vec2(1.0f)); }
inline vec3 saturate(vec3 x) { return glm::clamp(x, vec3(0.0f), vec3(1.0f)); }
inline vec4 saturate(vec4 x) { return glm::clamp(x, vec4(0.0f), vec4(1.0f)); }

#include "TriplanarShading.h"
#include "TriplanarMaterial.h"
#include "Shadow.h"
#include "Atmosphere.h"
#include "TerrainLayers.h"

} // namespace strata::shading

#undef STRATA_INLINE
#undef INOUT
#undef STRATA_FEATURE_FUNCTION
#undef STRATA_FEATURE_ARGS
#undef STRATA_MAPS_PARAM
#undef STRATA_MAPS_ARG
#undef STRATA_IF_FEATURE
#undef STRATA_FEATURE_BITS
#undef SAMPLE_MAP
#undef STRATA_SELECT_LAYER
#undef STRATA_LAYERS_PARAM
#undef LAYER_SET
