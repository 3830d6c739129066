// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

/// \file
/// Triplanar mapping and lighting math, written ONCE in the common subset of
/// GLSL 4.50 and C++20 with GLM, and compiled as both (docs/rendering.md:
/// the CPU sampler mirrors the shader). It is never included directly:
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

/// The three world-space projections of `v` (YZ, XZ, XY) with the U
/// mirroring of triplanarUV() but without its ½ offsets: shared by the UVs
/// and their screen-space derivatives.
STRATA_INLINE TriplanarUV triplanarProject(vec3 v, vec3 n)
{
    TriplanarUV uv;
    uv.x = vec2(v.z, v.y);
    uv.y = vec2(v.x, v.z);
    uv.z = vec2(v.x, v.y);
    if (n.x >= 0.0f) {
        uv.x.x = -uv.x.x;
    }
    if (n.y >= 0.0f) {
        uv.y.x = -uv.y.x;
    }
    if (n.z < 0.0f) {
        uv.z.x = -uv.z.x;
    }
    return uv;
}

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
    TriplanarUV uv = triplanarProject(p, n);
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

/// The blend offset for biplanar mapping (Quilez's two projections instead
/// of three): with `biplanar` set, at least the smallest component of |n|,
/// so that its projection's weight is zero and never sampled; the weights
/// stay continuous where the smallest axis changes (the two smallest are
/// equal there, and both cut). Unchanged otherwise.
STRATA_INLINE float biplanarOffset(vec3 n, float offset, float biplanar)
{
    vec3 a = abs(n);
    return biplanar > 0.5f ? max(offset, min(a.x, min(a.y, a.z))) : offset;
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


// ===========================================================================
// The full material model (issue 5). Everything below is plain math on
// values the caller samples; the material evaluation itself lives in
// TriplanarMaterial.h, which is compiled once per feature set.
// ===========================================================================

/// UV derivatives of the three projections, for the texture-space position
/// derivative `d` (dFdx or dFdy of p): the projections without the ½
/// offsets, with the same mirroring signs as triplanarUV().
STRATA_INLINE TriplanarUV triplanarUVDerivative(vec3 d, vec3 n)
{
    return triplanarProject(d, n);
}

/// Blend weights without height: saturate(|n| − offset) per axis, before
/// the exponent. A projection whose base weight is 0 keeps weight 0 after
/// height blending, so its maps need not be sampled at all.
STRATA_INLINE vec3 triplanarBaseWeights(vec3 n, float offset)
{
    return saturate(abs(n) - vec3(offset));
}

/// Height-blended weights (triplanar-mapping §4.3):
/// w = saturate(|n| − offset) · mix(1, heights, heightStrength), raised to
/// `exponent`, normalised. `heights` are the projections' MOHS.B values
/// (0..1), `heightStrength` 0..0.99. Never NaN, never all zero: falls back to
/// the dominant axis of |n| exactly as triplanarWeights() does. Exponents up
/// to 64 stay finite (the largest weight is divided out before pow()).
STRATA_INLINE vec3 triplanarWeightsHeight(vec3 n, float offset, float exponent, vec3 heights, float heightStrength)
{
    vec3 a = abs(n);
    vec3 w = saturate(a - vec3(offset)) * mix(vec3(1.0f), saturate(heights), heightStrength);
    float m = max(w.x, max(w.y, w.z));
    if (m > 0.0f) {
        w = pow(w / m, vec3(exponent));
        float s = w.x + w.y + w.z;
        if (s >= 1.0f && s <= 3.0f) {
            return w / s;
        }
    }
    return triplanarWeights(n, 2.0f, 1.0f); // offset 2 cuts everything: the dominant-axis fallback
}

/// A 32-bit hash of a lattice point (PCG's output permutation), the same
/// bits in GLSL and C++. The lattice repeats every 256 cells per axis, so
/// the host can rebase far origins in double without changing the pattern.
STRATA_INLINE uint latticeHash(int x, int y, int z, uint seed)
{
    uint h = uint(x & 255) | (uint(y & 255) << 8u) | (uint(z & 255) << 16u);
    h = h * 747796405u + 2891336453u + seed * 2654435761u;
    uint word = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    return (word >> 22u) ^ word;
}

// ---------------------------------------------------------------------------
// Anti-tiling: stochastic tiling on a triangle grid (after Mikkelsen's
// hex-tiling, 2022, and Heitz & Neyret's stochastic texturing). The texture
// plane is cut into unit cells (one texture repeat), each split along its
// diagonal; every lattice corner carries a random UV offset, and a fragment
// blends the map at its triangle's three corner offsets by barycentric
// weights raised to `sharpness`. The lattice is the texture repeats' own
// (not a skewed hex grid), so a host that rebases far origins by whole
// repeats can pass the dropped repeats (modulo the hash's 256) and the
// pattern stays anchored to the world. Offsets only, no rotation: normal
// maps need no re-orientation.

/// The three taps of one projection's anti-tiled fetch.
struct StochasticTaps
{
    vec2 offset0;
    vec2 offset1;
    vec2 offset2;
    vec3 weights; ///< sum 1
};

/// One tap, no offset: the plain fetch.
STRATA_INLINE StochasticTaps singleTap()
{
    StochasticTaps t;
    t.offset0 = vec2(0.0f);
    t.offset1 = vec2(0.0f);
    t.offset2 = vec2(0.0f);
    t.weights = vec3(1.0f, 0.0f, 0.0f);
    return t;
}

/// The random UV offset of lattice corner (x, y), in [0, 1)².
STRATA_INLINE vec2 cornerOffset(int x, int y)
{
    uint h = latticeHash(x, y, 0, 2654435769u);
    return vec2(float(h & 65535u), float(h >> 16u)) / 65536.0f;
}

/// The taps at `uv`; `shift` is the integer number of repeats the host
/// dropped from this projection's UVs (as floats). `sharpness` >= 1: larger
/// keeps more of one copy's contrast, smaller blends more.
STRATA_INLINE StochasticTaps stochasticTaps(vec2 uv, vec2 shift, float sharpness)
{
    vec2 cell = floor(uv);
    vec2 f = uv - cell;
    int x = int(cell.x) + int(shift.x);
    int y = int(cell.y) + int(shift.y);
    StochasticTaps t;
    vec3 w;
    if (f.x + f.y > 1.0f) {
        w = vec3(f.x + f.y - 1.0f, 1.0f - f.x, 1.0f - f.y);
        t.offset0 = cornerOffset(x + 1, y + 1);
        t.offset1 = cornerOffset(x, y + 1);
        t.offset2 = cornerOffset(x + 1, y);
    } else {
        w = vec3(1.0f - f.x - f.y, f.x, f.y);
        t.offset0 = cornerOffset(x, y);
        t.offset1 = cornerOffset(x + 1, y);
        t.offset2 = cornerOffset(x, y + 1);
    }
    // The largest barycentric weight is >= 1/3: divide it out before pow(),
    // so the sum stays in [1, 3] for any sharpness.
    w = max(w, vec3(0.0f));
    float m = max(w.x, max(w.y, w.z));
    w = pow(w / m, vec3(sharpness));
    t.weights = w / (w.x + w.y + w.z);
    return t;
}

/// Weighted sum of four-component samples.
STRATA_INLINE vec4 triplanarBlend4(vec4 sampleX, vec4 sampleY, vec4 sampleZ, vec3 weights)
{
    return sampleX * weights.x + sampleY * weights.y + sampleZ * weights.z;
}

// ---------------------------------------------------------------------------
// Normal maps without tangent space (triplanar-mapping §3.2–3.3).

const int NORMAL_BLEND_WHITEOUT = 0;
const int NORMAL_BLEND_UDN = 1;
const int NORMAL_BLEND_RNM = 2;

/// Decodes a normal-map texel (0..1 per channel, OpenGL +Y convention; DirectX
/// maps are flipped when loaded) into a tangent-space normal, scaling XY by
/// `strength` and rebuilding Z = sqrt(1 − x² − y²) (so strength 0 gives
/// exactly (0, 0, 1) and a flat texel stays flat). Not normalised beyond that.
STRATA_INLINE vec3 decodeNormal(vec4 texel, float strength)
{
    vec2 xy = (vec2(texel.x, texel.y) * 2.0f - vec2(1.0f)) * strength;
    float z = sqrt(max(1.0f - dot(xy, xy), 0.0f));
    if (dot(xy, xy) > 1.0f) {
        xy = normalize(xy);
    }
    return vec3(xy.x, xy.y, z);
}

/// Reoriented normal mapping (Barré-Brisebois & Hill): `detail` rotated by
/// the rotation that takes +Z to `base`. Both tangent space, base.z > −1.
/// The result is unit length when both inputs are.
STRATA_INLINE vec3 blendNormalRnm(vec3 base, vec3 detail)
{
    vec3 t = vec3(base.x, base.y, base.z + 1.0f);
    vec3 u = vec3(-detail.x, -detail.y, detail.z);
    return t * (dot(t, u) / t.z) - u;
}

/// Blends a mapped tangent-space normal `mapped` with the surface normal
/// `surface` expressed in the same projection space (Z = the projection
/// axis, which may point away: surface.z < 0 on the negative faces).
/// Whiteout: (m.xy + s.xy, m.z·s.z); UDN: (m.xy + s.xy, s.z); RNM: `mapped`
/// reoriented onto `surface`. The blend is done with |s.z| and the result's
/// Z sign restored, which for whiteout is exactly the seed text's formula.
/// Not normalised (the weighted sum is normalised once).
STRATA_INLINE vec3 blendProjectedNormal(vec3 mapped, vec3 surface, int mode)
{
    float sz = surface.z < 0.0f ? -1.0f : 1.0f;
    vec3 s = vec3(surface.x, surface.y, abs(surface.z));
    vec3 r;
    if (mode == NORMAL_BLEND_UDN) {
        r = vec3(mapped.x + s.x, mapped.y + s.y, s.z);
    } else if (mode == NORMAL_BLEND_RNM) {
        r = blendNormalRnm(s, mapped);
    } else {
        r = vec3(mapped.x + s.x, mapped.y + s.y, mapped.z * s.z);
    }
    return vec3(r.x, r.y, r.z * sz);
}

/// The X projection's mapped normal in world space: un-mirror (negate the
/// tangent X where triplanarUV negated U), move the surface normal into
/// projection space (zyx), blend, and move back.
STRATA_INLINE vec3 worldNormalX(vec3 mapped, vec3 n, int mode)
{
    if (n.x >= 0.0f) {
        mapped.x = -mapped.x;
    }
    vec3 b = blendProjectedNormal(mapped, vec3(n.z, n.y, n.x), mode);
    return vec3(b.z, b.y, b.x);
}

/// The Y projection's mapped normal in world space (projection space xzy).
STRATA_INLINE vec3 worldNormalY(vec3 mapped, vec3 n, int mode)
{
    if (n.y >= 0.0f) {
        mapped.x = -mapped.x;
    }
    vec3 b = blendProjectedNormal(mapped, vec3(n.x, n.z, n.y), mode);
    return vec3(b.x, b.z, b.y);
}

/// The Z projection's mapped normal in world space (projection space xyz).
STRATA_INLINE vec3 worldNormalZ(vec3 mapped, vec3 n, int mode)
{
    if (n.z < 0.0f) {
        mapped.x = -mapped.x;
    }
    return blendProjectedNormal(mapped, n, mode);
}

/// Normalises `v`, or returns `fallback` when v is zero or not finite.
STRATA_INLINE vec3 safeNormalize(vec3 v, vec3 fallback)
{
    float l2 = dot(v, v);
    if (l2 > 1e-30f && l2 < 1e30f) {
        return v / sqrt(l2);
    }
    return fallback;
}

// ---------------------------------------------------------------------------
// Detail maps (complex-maps §3).

/// Albedo detail: `detail` is the detail map's R (0..1, 0.5 neutral);
/// interpolates sqrt(albedo) towards 0 or 1 by |2·detail − 1| · strength ·
/// mask, then squares (a perceptual, roughly gamma-space modulation).
STRATA_INLINE vec3 applyDetailAlbedo(vec3 albedo, float detail, float strength, float mask)
{
    float d = (detail * 2.0f - 1.0f) * strength;
    vec3 g = mix(sqrt(max(albedo, vec3(0.0f))), vec3(d < 0.0f ? 0.0f : 1.0f), abs(d) * mask);
    return g * g;
}

/// Smoothness detail: the detail map's B, interpolated in the same way
/// but linearly.
STRATA_INLINE float applyDetailSmoothness(float smoothness, float detail, float strength, float mask)
{
    float d = (detail * 2.0f - 1.0f) * strength;
    return mix(smoothness, d < 0.0f ? 0.0f : 1.0f, abs(d) * mask);
}

// ---------------------------------------------------------------------------
// Lighting: the minimalist Cook–Torrance BRDF of Unity's scriptable render
// pipelines (Catlike Coding "Custom SRP"), with hemisphere ambient.

const float MIN_REFLECTIVITY = 0.04f;

struct Brdf
{
    vec3 diffuse;
    vec3 specular;
    float roughness;
    float perceptualRoughness;
    float fresnel;
};

/// Diffuse and specular colours from metallic (reflectivity at least 0.04),
/// roughness = (1 − smoothness)², the Fresnel colour's strength.
STRATA_INLINE Brdf makeBrdf(vec3 albedo, float metallic, float smoothness)
{
    Brdf b;
    float oneMinusReflectivity = (1.0f - MIN_REFLECTIVITY) - metallic * (1.0f - MIN_REFLECTIVITY);
    b.diffuse = albedo * oneMinusReflectivity;
    b.specular = mix(vec3(MIN_REFLECTIVITY), albedo, metallic);
    b.perceptualRoughness = 1.0f - smoothness;
    b.roughness = b.perceptualRoughness * b.perceptualRoughness;
    b.fresnel = saturate(smoothness + 1.0f - oneMinusReflectivity);
    return b;
}

/// r² / (d² · max(0.1, (L·H)²) · (4r + 2)), d = (N·H)²(r² − 1) + 1.00001.
STRATA_INLINE float specularStrength(vec3 n, vec3 viewDir, vec3 lightDir, float roughness)
{
    vec3 h = safeNormalize(lightDir + viewDir, n);
    float nh2 = saturate(dot(n, h));
    nh2 = nh2 * nh2;
    float lh2 = saturate(dot(lightDir, h));
    lh2 = lh2 * lh2;
    float r2 = roughness * roughness;
    float d = nh2 * (r2 - 1.0f) + 1.00001f;
    return r2 / (d * d * max(0.1f, lh2) * (roughness * 4.0f + 2.0f));
}

/// Radiance reflected from one directional light (unit `lightDir`, towards
/// the light).
STRATA_INLINE vec3 directLight(Brdf b, vec3 n, vec3 viewDir, vec3 lightDir, vec3 lightColor)
{
    float nDotL = saturate(dot(n, lightDir));
    return lightColor * nDotL * (b.specular * specularStrength(n, viewDir, lightDir, b.roughness) + b.diffuse);
}

/// Sky/ground hemisphere: `ground` at direction −Y, `sky` at +Y.
STRATA_INLINE vec3 hemisphere(vec3 dir, vec3 sky, vec3 ground)
{
    return mix(ground, sky, saturate(dir.y * 0.5f + 0.5f));
}

/// Indirect light: diffuse hemisphere ambient plus a reflection of the
/// hemisphere, with Fresnel strength `fresnelStrength`·(1 − N·V)⁴, divided
/// by r² + 1, all times `occlusion` (occlusion affects indirect light only).
STRATA_INLINE vec3 indirectLight(Brdf b, vec3 n, vec3 viewDir, vec3 sky, vec3 ground, float occlusion,
                                 float fresnelStrength)
{
    vec3 diffuseLight = hemisphere(n, sky, ground);
    vec3 r = reflect(-viewDir, n);
    // Rough surfaces see a blurrier, more ambient-like environment.
    vec3 specularLight = mix(hemisphere(r, sky, ground), diffuseLight, b.perceptualRoughness);
    float f = 1.0f - saturate(dot(n, viewDir));
    f = fresnelStrength * f * f * f * f;
    vec3 reflection = specularLight * mix(b.specular, vec3(b.fresnel), f) / (b.roughness * b.roughness + 1.0f);
    return (diffuseLight * b.diffuse + reflection) * occlusion;
}

/// Exposure, ACES tone map: linear radiance to linear display value 0..1.
STRATA_INLINE vec3 toneMap(vec3 radiance, float exposure)
{
    return toneMapAces(max(radiance, vec3(0.0f)) * exposure);
}

/// The sRGB transfer function, for one display value 0..1.
STRATA_INLINE float linearToSrgb(float c)
{
    if (c <= 0.0031308f) {
        return 12.92f * max(c, 0.0f);
    }
    return 1.055f * pow(min(c, 1.0f), 1.0f / 2.4f) - 0.055f;
}

#endif // STRATA_TRIPLANAR_SHADING_H
