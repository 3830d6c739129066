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
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#define STRATA_CPP 1
#define STRATA_INLINE inline
#define INOUT(T) T&

namespace strata::shading {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;

// GLSL's built-in functions: abs, min, max, clamp, mix, pow, dot, normalize...
using namespace glm;

/// HLSL's saturate, which GLSL lacks: clamp to [0, 1] per component.
inline float saturate(float x) { return glm::clamp(x, 0.0f, 1.0f); }
inline vec2 saturate(vec2 x) { return glm::clamp(x, vec2(0.0f), vec2(1.0f)); }
inline vec3 saturate(vec3 x) { return glm::clamp(x, vec3(0.0f), vec3(1.0f)); }
inline vec4 saturate(vec4 x) { return glm::clamp(x, vec4(0.0f), vec4(1.0f)); }

#include "TriplanarShading.h"

} // namespace strata::shading

#undef STRATA_INLINE
#undef INOUT
