// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

/// \file
/// Sun shadows: the shadow-map lookup with normal-offset bias and a fixed
/// 4×4-texel PCF kernel, written ONCE in the common subset of GLSL 4.50 and
/// C++20 (the editing rules of TriplanarShading.h apply) and compiled as both:
///  - GLSL: embedded after TriplanarMaterial.h in the terrain fragment stage;
///    the fragment shader defines shadowMapDepth(x, y) with texelFetch;
///  - C++:  #include "ShadingPrelude.h" (strata::shading::sunVisibility),
///    with a `shadowMap` object whose depth(x, y) reads the CPU shadow map.
///
/// The algorithm, identical on both renderers:
///  1. Each renderer rasterizes the mesh, seen from the sun, into its own
///     depth map with its own rasterizer: an orthographic projection fitted
///     to the mesh bounds (render/src/ShadowSetup.h), no face culling,
///     GL_LESS, cleared to 1; stored depth = window depth 0.5·z_ndc + 0.5.
///  2. A fragment looks the map up from its position moved along the
///     INTERPOLATED surface normal (never the normal-mapped one, whose bumps
///     would make the bias wobble: complex-maps §4.3) by normalBias texels
///     scaled by sin(normal, sun), and towards the sun by depthBias texels.
///  3. PCF: the 3×3 bilinearly filtered depth comparisons around the lookup
///     point, which is a 4×4-texel kernel with separable tent weights
///     (1 − f, 1, 1, f) / 3 per axis: the visibility varies continuously
///     with the lookup point, so a one-ulp difference between GL and the CPU
///     moves it by a tiny amount, never by a whole step.
///  4. The result (0 = fully shadowed, 1 = lit) scales the sun's colour, the
///     first directional light, only; other lights and ambient are unshadowed.

#ifndef STRATA_SHADOW_H
#define STRATA_SHADOW_H

#ifdef STRATA_CPP
#define STRATA_SHADOW_FUNCTION template <class ShadowMap> inline
#define STRATA_SHADOW_PARAM const ShadowMap &shadowMap,
#define SHADOW_FETCH(x, y) shadowMap.depth(x, y)
#else
#define STRATA_SHADOW_FUNCTION
#define STRATA_SHADOW_PARAM
#define SHADOW_FETCH(x, y) shadowMapDepth(x, y)
/// Stored window depth (0..1) of shadow-map texel (x, y), 0 <= x, y <
/// resolution, y = 0 the bottom row (GL's texel order). Defined by the
/// fragment shader that uses sunVisibility().
float shadowMapDepth(int x, int y);
#endif

/// The sun's shadow map and how to look it up. All lengths in metres,
/// positions relative to the mesh origin (as the fragment's vPosition).
struct ShadowParams
{
    mat4 lightViewProjection; ///< mesh-relative position → light clip space (orthographic, w = 1)
    vec3 lightDirection;      ///< unit, towards the sun
    float texelSize;          ///< metres covered by one texel (the larger side)
    float normalBias;         ///< texels along the interpolated normal
    float depthBias;          ///< texels towards the sun
    int resolution;           ///< texels per side
    int enabled;              ///< 0: every fragment is lit (the map is never read)
};

/// Where the shadow map is read for a fragment at `position` with
/// interpolated normal `n` (unit): moved normalBias · sin(n, L) texels
/// along n and depthBias texels towards the sun L. Moving along the
/// geometric normal gets the lookup out of the surface's own depth texels
/// at grazing angles (no shadow acne) without the light leaks of a large
/// depth bias. Why sin(n, L): a plane at angle θ to the light changes depth
/// by cot θ texels per texel across the map, so the PCF kernel's outer taps
/// (2 texels out) lie 2·cot θ deeper; an offset of b texels along the
/// normal puts the lookup b / sin θ in front of the plane along the ray, so
/// b >= 2·cos θ = 2·sin(n, L) clears them at every angle (the default 2.5
/// adds half a texel for the map's sampling at texel centres).
STRATA_INLINE vec3 shadowLookupPosition(ShadowParams sp, vec3 position, vec3 n)
{
    float nDotL = dot(n, sp.lightDirection);
    float sinNL = sqrt(saturate(1.0f - nDotL * nDotL));
    return position + n * (sp.normalBias * sinNL * sp.texelSize) + sp.lightDirection * (sp.depthBias * sp.texelSize);
}

/// PCF tent weights of the four texel columns (or rows) for fraction f.
STRATA_INLINE vec4 shadowTentWeights(float f)
{
    return vec4(1.0f - f, 1.0f, 1.0f, f) * (1.0f / 3.0f);
}

/// Visibility of the sun, 0 (in shadow) .. 1 (lit), for a fragment at
/// `position` (metres, mesh-relative) with interpolated surface normal
/// `interpolatedNormal` (any length; the lookup uses it normalised). Lookups
/// outside the map (x, y or depth) count as lit. 16 texel fetches.
STRATA_SHADOW_FUNCTION float sunVisibility(STRATA_SHADOW_PARAM ShadowParams sp, vec3 position,
                                           vec3 interpolatedNormal)
{
    if (sp.enabled == 0) {
        return 1.0f;
    }
    vec3 n = safeNormalize(interpolatedNormal, sp.lightDirection);
    vec4 c = sp.lightViewProjection * vec4(shadowLookupPosition(sp, position, n), 1.0f);
    float depth = c.z * 0.5f + 0.5f;
    float size = float(sp.resolution);
    // Texel coordinates with texel centres on integers.
    float tx = (c.x * 0.5f + 0.5f) * size - 0.5f;
    float ty = (c.y * 0.5f + 0.5f) * size - 0.5f;
    if (!(depth < 1.0f) || !(tx > -1.0f) || !(ty > -1.0f) || !(tx < size) || !(ty < size)) {
        return 1.0f;
    }
    float bx = floor(tx);
    float by = floor(ty);
    vec4 wx = shadowTentWeights(tx - bx);
    vec4 wy = shadowTentWeights(ty - by);
    int x0 = int(bx) - 1;
    int y0 = int(by) - 1;
    int last = sp.resolution - 1;
    float visible = 0.0f;
    for (int j = 0; j < 4; ++j) {
        int y = clamp(y0 + j, 0, last);
        for (int i = 0; i < 4; ++i) {
            int x = clamp(x0 + i, 0, last);
            if (depth <= SHADOW_FETCH(x, y)) {
                visible += wx[i] * wy[j];
            }
        }
    }
    return saturate(visible);
}

/// The lighting with the sun (light 0) scaled by `visibility`: shadows
/// darken the sun's direct light only.
STRATA_INLINE LightingParams shadowedLighting(LightingParams l, float visibility)
{
    l.lights[0].color = l.lights[0].color * visibility;
    return l;
}

#undef STRATA_SHADOW_FUNCTION
#undef STRATA_SHADOW_PARAM
#undef SHADOW_FETCH

#endif // STRATA_SHADOW_H
