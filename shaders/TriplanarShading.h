/// \file
/// Triplanar mapping and lighting math, written ONCE in the common subset of
/// GLSL 4.50 and C++20 with GLM, and compiled as both (see DESIGN.md, "The
/// shared shading header"). It is never included directly:
///  - GLSL: the build embeds it after ShadingPrelude.glsl (shaders/CMakeLists.txt);
///  - C++:  #include "ShadingPrelude.h", which puts it in strata::shading.
///
/// Rules for editing (both compilers must accept every line):
///  - no swizzles (write vec2(p.z, p.y)), no `in`/`out` qualifiers (use INOUT(T)),
///  - float literals with an f suffix (1.0f), explicit vecN(...) constructors
///    where GLSL would not convert (pow(vec3, vec3(e))),
///  - every function starts with STRATA_INLINE (inline in C++, nothing in GLSL),
///  - saturate(), STRATA_INLINE and INOUT() come from the prelude,
///  - texture fetches stay outside: each side samples its own maps.
///
/// Conventions: world space is right-handed with +Y up (OpenGL). Positions
/// passed here are texture-space positions (world metres × mapScale, plus a
/// per-mesh offset), so one texture repeat is one unit.

#ifndef STRATA_TRIPLANAR_SHADING_H
#define STRATA_TRIPLANAR_SHADING_H

/// Texture coordinates of the three planar projections.
struct TriplanarUV
{
    vec2 x; ///< projection along X (onto the YZ plane): (±p.z, p.y + 0.5)
    vec2 y; ///< projection along Y (onto the XZ plane): (±p.x, p.z)
    vec2 z; ///< projection along Z (onto the XY plane): (±p.x + 0.5, p.y)
};

/// The three projections of texture-space position `p` for a surface with
/// normal `n` (need not be unit length; only the signs of its components are
/// used).
///
/// Mirroring fix: U is negated on the faces where the projection would
/// otherwise show the texture mirrored when seen from outside, so that for
/// every face, seen from outside with +Y (or, for the Y projection, +Z) up,
/// U increases to the right and V upwards. In a right-handed world this is
/// n.x >= 0, n.y >= 0 and n.z < 0. (The Catlike Coding text negates for
/// n.x < 0, n.y < 0, n.z >= 0 because Unity is left-handed; in a right-handed
/// world that rule would mirror all six faces.)
///
/// The X projection is then shifted by 1/2 in V and the Z projection by 1/2
/// in U, so the projections do not repeat in lockstep where they meet.
///
/// Exact values, for p = (1, 2, 3):
///   n = +X: x = (-3, 2.5)   n = -X: x = (3, 2.5)
///   n = +Y: y = (-1, 3)     n = -Y: y = (1, 3)
///   n = +Z: z = (1.5, 2)    n = -Z: z = (-0.5, 2)
STRATA_INLINE TriplanarUV triplanarUV(vec3 p, vec3 n)
{
    TriplanarUV uv;
    uv.x = vec2(p.z, p.y);
    uv.y = vec2(p.x, p.z);
    uv.z = vec2(p.x, p.y);
    if (n.x >= 0.0f) {
        uv.x.x = -uv.x.x;
    }
    if (n.y >= 0.0f) {
        uv.y.x = -uv.y.x;
    }
    if (n.z < 0.0f) {
        uv.z.x = -uv.z.x;
    }
    uv.x.y += 0.5f;
    uv.z.x += 0.5f;
    return uv;
}

/// Blend weights of the X, Y and Z projections for normal `n`:
/// pow(saturate(|n| − offset), exponent), normalised to sum 1.
///
/// `offset` (0..0.5) narrows the blend zones linearly, `exponent` (1..8)
/// sharpens them. Always finite, >= 0 and summing to 1: when every component
/// is cut away by the offset (or n is zero, denormal or NaN) the dominant
/// axis of |n| gets weight 1 (X on ties and NaN).
STRATA_INLINE vec3 triplanarWeights(vec3 n, float offset, float exponent)
{
    vec3 a = abs(n);
    vec3 w = saturate(a - vec3(offset));
    float m = max(w.x, max(w.y, w.z));
    if (m > 0.0f) {
        // Dividing by the largest weight first leaves the normalised result
        // unchanged and keeps pow() away from underflow: the sum is in [1, 3].
        w = pow(w / m, vec3(exponent));
        float s = w.x + w.y + w.z;
        if (s >= 1.0f && s <= 3.0f) {
            return w / s;
        }
    }
    if (a.y > a.x && a.y >= a.z) {
        return vec3(0.0f, 1.0f, 0.0f);
    }
    if (a.z > a.x && a.z > a.y) {
        return vec3(0.0f, 0.0f, 1.0f);
    }
    return vec3(1.0f, 0.0f, 0.0f);
}

/// Weighted sum of the three projections' samples.
STRATA_INLINE vec3 triplanarBlend(vec3 sampleX, vec3 sampleY, vec3 sampleZ, vec3 weights)
{
    return sampleX * weights.x + sampleY * weights.y + sampleZ * weights.z;
}

/// Diffuse lighting of a surface with linear `albedo` and unit normal `n`:
/// Lambert from one directional light (unit `sunDirection`, towards the sun)
/// plus a hemisphere ambient blending `groundAmbient` (n = −Y) to
/// `skyAmbient` (n = +Y). Radiance in linear units, not tone mapped.
STRATA_INLINE vec3 shadeLambertHemisphere(vec3 albedo, vec3 n, vec3 sunDirection, vec3 sunColor, vec3 skyAmbient,
                                          vec3 groundAmbient)
{
    float nDotL = max(dot(n, sunDirection), 0.0f);
    vec3 ambient = mix(groundAmbient, skyAmbient, saturate(n.y * 0.5f + 0.5f));
    return albedo * (sunColor * nDotL + ambient);
}

/// Narkowicz's fit of the ACES filmic curve: linear radiance to linear
/// display value in [0, 1].
STRATA_INLINE vec3 toneMapAces(vec3 x)
{
    vec3 num = x * (x * 2.51f + vec3(0.03f));
    vec3 den = x * (x * 2.43f + vec3(0.59f)) + vec3(0.14f);
    return saturate(num / den);
}

#endif // STRATA_TRIPLANAR_SHADING_H
