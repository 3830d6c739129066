// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

/// \file
/// The triplanar material, evaluated per fragment, in the common subset of
/// GLSL 4.50 and C++20 (see TriplanarShading.h for the editing rules). It is
/// compiled once per *feature set*: STRATA_FEATURES, a bit set of the
/// FEATURE_* constants below, is a template parameter in C++ (every feature
/// test is an `if constexpr`) and a #define in GLSL (every feature test is a
/// constant the compiler folds), so a material without, say, a normal map
/// computes no normal blend at all.
///
/// Texture fetches stay outside: the material calls SAMPLE_MAP(map, uv,
/// dUVdx, dUVdy) with explicit UV derivatives; GLSL supplies sampleMap()
/// with textureGrad(), C++ a `maps.sample()` of the CPU sampler. Every map
/// returns values as GL would: sRGB maps already decoded to linear.

#ifndef STRATA_TRIPLANAR_MATERIAL_H
#define STRATA_TRIPLANAR_MATERIAL_H

// Feature bits. Keep in step with strata::render::MaterialFeature.
const uint FEATURE_MASK_MAP = 1u;      ///< a mask map (MOHS, or MODS with FEATURE_MODS)
const uint FEATURE_MODS = 2u;          ///< mask layout Metallic Occlusion Detail-mask Smoothness
const uint FEATURE_HEIGHT_BLEND = 4u;  ///< weights × mix(1, MOHS.B, heightStrength)
const uint FEATURE_NORMAL_MAP = 8u;    ///< per-projection normal maps
const uint FEATURE_TOP_MAPS = 16u;     ///< separate albedo/mask/normal for the Y projection where n.y > 0
const uint FEATURE_DETAIL = 32u;       ///< detail map: albedo (R) and smoothness (B) modulation
const uint FEATURE_DETAIL_NORMAL = 64u; ///< detail normal map, combined with RNM
const uint FEATURE_EMISSION = 128u;    ///< emission map × HDR colour
const uint FEATURE_NORMAL_UDN = 256u;  ///< UDN instead of whiteout
const uint FEATURE_NORMAL_RNM = 512u;  ///< RNM instead of whiteout
const uint FEATURE_LAYERS = 1024u;     ///< several layers (TerrainLayers.h); the other bits are their union
const uint FEATURE_ANTI_TILING = 2048u; ///< albedo, mask and normal maps fetched by stochastic tiling (3 taps)

// Map slots.
const int MAP_ALBEDO = 0;
const int MAP_MASK = 1;
const int MAP_NORMAL = 2;
const int MAP_TOP_ALBEDO = 3;
const int MAP_TOP_MASK = 4;
const int MAP_TOP_NORMAL = 5;
const int MAP_DETAIL = 6;
const int MAP_DETAIL_NORMAL = 7;
const int MAP_EMISSION = 8;
#define STRATA_MAP_COUNT 9

#define STRATA_MAX_LIGHTS 4

#ifdef STRATA_GLSL
vec4 sampleMap(int map, vec2 uv, vec2 dUVdx, vec2 dUVdy);
#endif

/// Material parameters (all ranges checked by the caller).
struct MaterialParams
{
    vec3 albedoTint;            ///< multiplies albedo (linear)
    float blendOffset;          ///< 0..0.5
    float blendExponent;        ///< 1..64
    float heightStrength;       ///< 0..0.99
    float metallic;             ///< multiplies mask R (or is the value without a mask map)
    float smoothness;           ///< multiplies mask A (or is the value)
    float occlusionStrength;    ///< 0..1: occlusion = mix(1, mask G, strength)
    float normalStrength;       ///< scales normal-map XY
    float detailScale;          ///< detail repeats per base repeat
    float detailAlbedo;         ///< 0..1
    float detailSmoothness;     ///< 0..1
    float detailNormalStrength; ///< 0..1 (× detail mask)
    float biplanar;             ///< 1: two projections (the smallest normal axis' is cut), 0: three
    float antiTilingSharpness;  ///< 1..16: exponent of the stochastic-tiling weights (FEATURE_ANTI_TILING)
    vec3 emissionColor;         ///< HDR, linear, multiplies the emission map
    float fresnelStrength;      ///< 0..1
};

struct DirectionalLight
{
    vec3 direction; ///< unit, towards the light
    vec3 color;     ///< linear radiance
};

struct LightingParams
{
    DirectionalLight lights[STRATA_MAX_LIGHTS];
    int lightCount;     ///< 0..STRATA_MAX_LIGHTS
    vec3 skyAmbient;    ///< hemisphere colour at +Y
    vec3 groundAmbient; ///< hemisphere colour at −Y
    float exposure;     ///< multiplies radiance before tone mapping
};

/// What the rasterizer supplies for one fragment.
struct SurfaceInput
{
    vec3 p;       ///< texture-space position (world × mapScale + offset)
    /// Added to p × detailScale for the detail maps: the fraction of the
    /// rebasing origin's tile count × detailScale (computed in double), so
    /// detail maps follow the world whatever the mesh origin, also when
    /// detailScale is not a whole number.
    vec3 detailOffset;
    /// The whole texture repeats the rebasing origin dropped from p, modulo
    /// 256 (integers as floats): anchors the anti-tiling lattice to the world.
    vec3 tileOffset;
    vec3 dpdx;    ///< its screen-space derivatives
    vec3 dpdy;
    vec3 n;       ///< unit interpolated surface normal
    vec3 viewDir; ///< unit, from the surface towards the camera
};

/// Everything the material computes before lighting (for tests and debug).
struct SurfaceOutput
{
    vec3 albedo;
    vec3 normal;
    vec3 weights;
    vec3 emission;
    float metallic;
    float occlusion;
    float smoothness;
    float height; ///< blended mask B: height (MOHS) or detail mask (MODS); 1 without a mask map
    vec3 layerColor; ///< the layers' weights as colour (DEBUG_VIEW_LAYERS); layer 0's alone outside TerrainLayers.h
    float fresnelStrength; ///< the material's (blended across layers)
};

/// The colour of layer `i` in the layers debug view (linear display values).
STRATA_INLINE vec3 layerPaletteColor(int i)
{
    if (i == 1) return vec3(0.8f, 0.1f, 0.05f);
    if (i == 2) return vec3(0.1f, 0.6f, 0.05f);
    if (i == 3) return vec3(0.05f, 0.15f, 0.9f);
    if (i == 4) return vec3(0.9f, 0.75f, 0.05f);
    if (i == 5) return vec3(0.05f, 0.7f, 0.8f);
    if (i == 6) return vec3(0.75f, 0.1f, 0.8f);
    if (i == 7) return vec3(1.0f, 1.0f, 1.0f);
    return vec3(0.2f, 0.2f, 0.2f);
}

STRATA_INLINE int normalBlendMode(uint features)
{
    if ((features & FEATURE_NORMAL_RNM) != 0u) {
        return NORMAL_BLEND_RNM;
    }
    if ((features & FEATURE_NORMAL_UDN) != 0u) {
        return NORMAL_BLEND_UDN;
    }
    return NORMAL_BLEND_WHITEOUT;
}

/// A base map (albedo, mask, normal, or their top versions) at one
/// projection: one fetch, or with anti-tiling the three taps' blend.
STRATA_FEATURE_FUNCTION vec4 sampleTiled(STRATA_MAPS_PARAM int map, vec2 uv, vec2 dUVdx, vec2 dUVdy, StochasticTaps t)
{
    STRATA_IF_FEATURE(FEATURE_ANTI_TILING)
    {
        return SAMPLE_MAP(map, uv + t.offset0, dUVdx, dUVdy) * t.weights.x +
               SAMPLE_MAP(map, uv + t.offset1, dUVdx, dUVdy) * t.weights.y +
               SAMPLE_MAP(map, uv + t.offset2, dUVdx, dUVdy) * t.weights.z;
    }
    return SAMPLE_MAP(map, uv, dUVdx, dUVdy);
}

#define SAMPLE_TILED(map, uv, dUVdx, dUVdy, taps) sampleTiled STRATA_FEATURE_ARGS(STRATA_MAPS_ARG map, uv, dUVdx, dUVdy, taps)

/// One fragment's projections, shared by evaluateSurface()'s steps: the
/// base maps' UVs, their derivatives and anti-tiling taps, which maps the Y
/// projection uses, and the detail maps' UVs and derivatives.
struct SurfaceProjections
{
    TriplanarUV uv;
    TriplanarUV ddx;
    TriplanarUV ddy;
    StochasticTaps tapsX; ///< a single tap without FEATURE_ANTI_TILING
    StochasticTaps tapsY;
    StochasticTaps tapsZ;
    bool useTop;          ///< the Y projection takes the top maps (FEATURE_TOP_MAPS, n.y > 0)
    TriplanarUV detailUV; ///< the base UVs without FEATURE_DETAIL or FEATURE_DETAIL_NORMAL
    TriplanarUV detailDdx;
    TriplanarUV detailDdy;
};

/// One map's samples at the three projections.
struct TriplanarSamples
{
    vec4 x;
    vec4 y;
    vec4 z;
};

/// The projections of fragment `s`; `need` are the weights before height
/// blending (the projections with weight 0 get no anti-tiling taps).
STRATA_FEATURE_FUNCTION SurfaceProjections projectSurface(STRATA_MAPS_PARAM SurfaceInput s, MaterialParams m,
                                                          vec3 need)
{
    vec3 n = s.n;
    SurfaceProjections pr;
    pr.uv = triplanarUV(s.p, n);
    pr.ddx = triplanarUVDerivative(s.dpdx, n);
    pr.ddy = triplanarUVDerivative(s.dpdy, n);
    pr.useTop = false;
    STRATA_IF_FEATURE(FEATURE_TOP_MAPS)
    {
        pr.useTop = n.y > 0.0f;
    }
    pr.tapsX = singleTap();
    pr.tapsY = singleTap();
    pr.tapsZ = singleTap();
    STRATA_IF_FEATURE(FEATURE_ANTI_TILING)
    {
        TriplanarUV shift = triplanarUVDerivative(s.tileOffset, n);
        if (need.x > 0.0f) {
            pr.tapsX = stochasticTaps(pr.uv.x, shift.x, m.antiTilingSharpness);
        }
        if (need.y > 0.0f) {
            pr.tapsY = stochasticTaps(pr.uv.y, shift.y, m.antiTilingSharpness);
        }
        if (need.z > 0.0f) {
            pr.tapsZ = stochasticTaps(pr.uv.z, shift.z, m.antiTilingSharpness);
        }
    }
    pr.detailUV = pr.uv;
    pr.detailDdx = pr.ddx;
    pr.detailDdy = pr.ddy;
    STRATA_IF_FEATURE(FEATURE_DETAIL | FEATURE_DETAIL_NORMAL)
    {
        pr.detailUV = triplanarUV(s.p * m.detailScale + s.detailOffset, n);
        pr.detailDdx = triplanarUVDerivative(s.dpdx * m.detailScale, n);
        pr.detailDdy = triplanarUVDerivative(s.dpdy * m.detailScale, n);
    }
    return pr;
}

// The Y projection's maps are chosen per fragment (top or side) with a
// branch around two constant-slot fetches rather than one fetch from a
// computed slot: a GLSL compiler then keeps two texture fetches instead
// of the sampler's whole slot switch (much less code on llvmpipe).

/// The albedo map (or the top one) at the projections with weight > 0; 1 elsewhere.
STRATA_FEATURE_FUNCTION TriplanarSamples sampleAlbedos(STRATA_MAPS_PARAM SurfaceProjections pr, vec3 need)
{
    vec4 one = vec4(1.0f);
    TriplanarSamples a;
    a.x = one;
    a.y = one;
    a.z = one;
    if (need.x > 0.0f) {
        a.x = SAMPLE_TILED(MAP_ALBEDO, pr.uv.x, pr.ddx.x, pr.ddy.x, pr.tapsX);
    }
    if (need.y > 0.0f) {
        if (pr.useTop) {
            a.y = SAMPLE_TILED(MAP_TOP_ALBEDO, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY);
        } else {
            a.y = SAMPLE_TILED(MAP_ALBEDO, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY);
        }
    }
    if (need.z > 0.0f) {
        a.z = SAMPLE_TILED(MAP_ALBEDO, pr.uv.z, pr.ddx.z, pr.ddy.z, pr.tapsZ);
    }
    return a;
}

/// The mask map (or the top one) at the projections with weight > 0; 1
/// elsewhere and without FEATURE_MASK_MAP.
STRATA_FEATURE_FUNCTION TriplanarSamples sampleMasks(STRATA_MAPS_PARAM SurfaceProjections pr, vec3 need)
{
    vec4 one = vec4(1.0f);
    TriplanarSamples k;
    k.x = one;
    k.y = one;
    k.z = one;
    STRATA_IF_FEATURE(FEATURE_MASK_MAP)
    {
        if (need.x > 0.0f) {
            k.x = SAMPLE_TILED(MAP_MASK, pr.uv.x, pr.ddx.x, pr.ddy.x, pr.tapsX);
        }
        if (need.y > 0.0f) {
            if (pr.useTop) {
                k.y = SAMPLE_TILED(MAP_TOP_MASK, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY);
            } else {
                k.y = SAMPLE_TILED(MAP_MASK, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY);
            }
        }
        if (need.z > 0.0f) {
            k.z = SAMPLE_TILED(MAP_MASK, pr.uv.z, pr.ddx.z, pr.ddy.z, pr.tapsZ);
        }
    }
    return k;
}

/// FEATURE_DETAIL: modulates o's albedo and smoothness by the blended
/// detail map (× detailMask).
STRATA_FEATURE_FUNCTION void applyDetailMap(STRATA_MAPS_PARAM SurfaceProjections pr, MaterialParams m, vec3 w,
                                            float detailMask, INOUT(SurfaceOutput) o)
{
    STRATA_IF_FEATURE(FEATURE_DETAIL)
    {
        vec4 grey = vec4(0.5f);
        vec4 detailX = grey;
        vec4 detailY = grey;
        vec4 detailZ = grey;
        if (w.x > 0.0f) {
            detailX = SAMPLE_MAP(MAP_DETAIL, pr.detailUV.x, pr.detailDdx.x, pr.detailDdy.x);
        }
        if (w.y > 0.0f) {
            detailY = SAMPLE_MAP(MAP_DETAIL, pr.detailUV.y, pr.detailDdx.y, pr.detailDdy.y);
        }
        if (w.z > 0.0f) {
            detailZ = SAMPLE_MAP(MAP_DETAIL, pr.detailUV.z, pr.detailDdx.z, pr.detailDdy.z);
        }
        vec4 detail = triplanarBlend4(detailX, detailY, detailZ, w);
        o.albedo = applyDetailAlbedo(o.albedo, detail.x, m.detailAlbedo, detailMask);
        o.smoothness = applyDetailSmoothness(o.smoothness, detail.z, m.detailSmoothness, detailMask);
    }
}

/// The world normal with the normal maps and detail normal maps blended in
/// (`masks`' B is the detail mask with FEATURE_MODS); n without either.
STRATA_FEATURE_FUNCTION vec3 mappedNormal(STRATA_MAPS_PARAM SurfaceProjections pr, MaterialParams m, vec3 n, vec3 w,
                                          TriplanarSamples masks)
{
    STRATA_IF_FEATURE(FEATURE_NORMAL_MAP | FEATURE_DETAIL_NORMAL)
    {
        int mode = normalBlendMode(STRATA_FEATURE_BITS);
        vec3 flatNormal = vec3(0.0f, 0.0f, 1.0f);
        vec3 tangentX = flatNormal;
        vec3 tangentY = flatNormal;
        vec3 tangentZ = flatNormal;
        STRATA_IF_FEATURE(FEATURE_NORMAL_MAP)
        {
            if (w.x > 0.0f) {
                tangentX = decodeNormal(SAMPLE_TILED(MAP_NORMAL, pr.uv.x, pr.ddx.x, pr.ddy.x, pr.tapsX),
                                        m.normalStrength);
            }
            if (w.y > 0.0f) {
                if (pr.useTop) {
                    tangentY = decodeNormal(SAMPLE_TILED(MAP_TOP_NORMAL, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY),
                                            m.normalStrength);
                } else {
                    tangentY = decodeNormal(SAMPLE_TILED(MAP_NORMAL, pr.uv.y, pr.ddx.y, pr.ddy.y, pr.tapsY),
                                            m.normalStrength);
                }
            }
            if (w.z > 0.0f) {
                tangentZ = decodeNormal(SAMPLE_TILED(MAP_NORMAL, pr.uv.z, pr.ddx.z, pr.ddy.z, pr.tapsZ),
                                        m.normalStrength);
            }
        }
        STRATA_IF_FEATURE(FEATURE_DETAIL_NORMAL)
        {
            float maskX1 = 1.0f;
            float maskY1 = 1.0f;
            float maskZ1 = 1.0f;
            STRATA_IF_FEATURE(FEATURE_MODS)
            {
                maskX1 = masks.x.z;
                maskY1 = masks.y.z;
                maskZ1 = masks.z.z;
            }
            if (w.x > 0.0f) {
                vec4 t = SAMPLE_MAP(MAP_DETAIL_NORMAL, pr.detailUV.x, pr.detailDdx.x, pr.detailDdy.x);
                tangentX = blendNormalRnm(tangentX, decodeNormal(t, m.detailNormalStrength * maskX1));
            }
            if (w.y > 0.0f) {
                vec4 t = SAMPLE_MAP(MAP_DETAIL_NORMAL, pr.detailUV.y, pr.detailDdx.y, pr.detailDdy.y);
                tangentY = blendNormalRnm(tangentY, decodeNormal(t, m.detailNormalStrength * maskY1));
            }
            if (w.z > 0.0f) {
                vec4 t = SAMPLE_MAP(MAP_DETAIL_NORMAL, pr.detailUV.z, pr.detailDdx.z, pr.detailDdy.z);
                tangentZ = blendNormalRnm(tangentZ, decodeNormal(t, m.detailNormalStrength * maskZ1));
            }
        }
        vec3 sum = worldNormalX(tangentX, n, mode) * w.x + worldNormalY(tangentY, n, mode) * w.y +
                   worldNormalZ(tangentZ, n, mode) * w.z;
        return safeNormalize(sum, n);
    }
    return n;
}

/// The blended emission map × emissionColor; black without FEATURE_EMISSION.
STRATA_FEATURE_FUNCTION vec3 sampleEmission(STRATA_MAPS_PARAM SurfaceProjections pr, MaterialParams m, vec3 w)
{
    STRATA_IF_FEATURE(FEATURE_EMISSION)
    {
        vec4 eX = vec4(0.0f);
        vec4 eY = vec4(0.0f);
        vec4 eZ = vec4(0.0f);
        if (w.x > 0.0f) {
            eX = SAMPLE_MAP(MAP_EMISSION, pr.uv.x, pr.ddx.x, pr.ddy.x);
        }
        if (w.y > 0.0f) {
            eY = SAMPLE_MAP(MAP_EMISSION, pr.uv.y, pr.ddx.y, pr.ddy.y);
        }
        if (w.z > 0.0f) {
            eZ = SAMPLE_MAP(MAP_EMISSION, pr.uv.z, pr.ddx.z, pr.ddy.z);
        }
        vec4 e = triplanarBlend4(eX, eY, eZ, w);
        return vec3(e.x, e.y, e.z) * m.emissionColor;
    }
    return vec3(0.0f);
}

/// Samples and combines every enabled map of the material at one fragment.
STRATA_FEATURE_FUNCTION SurfaceOutput evaluateSurface(STRATA_MAPS_PARAM SurfaceInput s, MaterialParams m)
{
    vec3 n = s.n;
    // Projections with weight 0 here keep weight 0 with any heights: skip them.
    float offset = biplanarOffset(n, m.blendOffset, m.biplanar);
    vec3 need = triplanarWeights(n, offset, m.blendExponent);
    SurfaceProjections pr = projectSurface STRATA_FEATURE_ARGS(STRATA_MAPS_ARG s, m, need);
    TriplanarSamples albedos = sampleAlbedos STRATA_FEATURE_ARGS(STRATA_MAPS_ARG pr, need);
    TriplanarSamples masks = sampleMasks STRATA_FEATURE_ARGS(STRATA_MAPS_ARG pr, need);

    vec3 w = need;
    STRATA_IF_FEATURE(FEATURE_HEIGHT_BLEND)
    {
        w = triplanarWeightsHeight(n, offset, m.blendExponent, vec3(masks.x.z, masks.y.z, masks.z.z),
                                   m.heightStrength);
    }

    SurfaceOutput o;
    o.weights = w;
    vec4 albedo = triplanarBlend4(albedos.x, albedos.y, albedos.z, w);
    o.albedo = vec3(albedo.x, albedo.y, albedo.z) * m.albedoTint;
    vec4 mask = triplanarBlend4(masks.x, masks.y, masks.z, w);
    o.metallic = saturate(mask.x * m.metallic);
    o.occlusion = mix(1.0f, mask.y, m.occlusionStrength);
    o.smoothness = saturate(mask.w * m.smoothness);
    o.height = mask.z;
    o.layerColor = layerPaletteColor(0);
    o.fresnelStrength = m.fresnelStrength;
    float detailMask = 1.0f;
    STRATA_IF_FEATURE(FEATURE_MODS)
    {
        detailMask = mask.z;
    }
    applyDetailMap STRATA_FEATURE_ARGS(STRATA_MAPS_ARG pr, m, w, detailMask, o);
    o.normal = mappedNormal STRATA_FEATURE_ARGS(STRATA_MAPS_ARG pr, m, n, w, masks);
    o.emission = sampleEmission STRATA_FEATURE_ARGS(STRATA_MAPS_ARG pr, m, w);
    return o;
}

/// Lights a surface: the BRDF for every directional light, indirect
/// hemisphere light × occlusion, plus emission. Linear radiance.
STRATA_INLINE vec3 lightSurface(SurfaceOutput o, vec3 viewDir, LightingParams l, float fresnelStrength)
{
    Brdf b = makeBrdf(o.albedo, o.metallic, o.smoothness);
    vec3 radiance = indirectLight(b, o.normal, viewDir, l.skyAmbient, l.groundAmbient, o.occlusion, fresnelStrength);
    for (int i = 0; i < STRATA_MAX_LIGHTS; ++i) {
        if (i < l.lightCount) {
            radiance += directLight(b, o.normal, viewDir, l.lights[i].direction, l.lights[i].color);
        }
    }
    return radiance + o.emission;
}

/// The whole fragment: material, lighting, exposure and tone map. Returns the
/// linear display value 0..1 (the sRGB encoding is the framebuffer's job on
/// the GPU, linearToSrgb()'s on the CPU).
STRATA_FEATURE_FUNCTION vec3 shadeFragment(STRATA_MAPS_PARAM SurfaceInput s, MaterialParams m, LightingParams l)
{
    SurfaceOutput o = evaluateSurface STRATA_FEATURE_ARGS(STRATA_MAPS_ARG s, m);
    return toneMap(lightSurface(o, s.viewDir, l, m.fresnelStrength), l.exposure);
}

// ---------------------------------------------------------------------------
// Debug views (the viewer's keys): what the material computed, shown as
// colour instead of the lit result. Pure math on SurfaceOutput, so the CPU
// renderer can show the same views through shadeDebugFragment().

const int DEBUG_VIEW_SHADED = 0;     ///< the lit, tone-mapped material (no debug view)
const int DEBUG_VIEW_WEIGHTS = 1;    ///< triplanar blend weights X, Y, Z as red, green, blue
const int DEBUG_VIEW_NORMALS = 2;    ///< the mapped world normal as n·½ + ½
const int DEBUG_VIEW_METALLIC = 3;   ///< metallic as grey
const int DEBUG_VIEW_OCCLUSION = 4;  ///< occlusion (after occlusionStrength) as grey
const int DEBUG_VIEW_HEIGHT = 5;     ///< mask B (height, or the MODS detail mask) as grey
const int DEBUG_VIEW_SMOOTHNESS = 6; ///< smoothness (after detail) as grey
const int DEBUG_VIEW_ALBEDO = 7;     ///< albedo (tinted, with detail), unlit
const int DEBUG_VIEW_LAYERS = 8;     ///< the terrain layers' weights, each layer a colour (layerPaletteColor)
// The landform views show the mesh's landform masks, not the material
// (landformDebugColor() in TerrainLayers.h).
const int DEBUG_VIEW_FLOW = 9;        ///< flow (log10 drainage area) 0..7, dark navy to pale blue
const int DEBUG_VIEW_WEAR = 10;       ///< wear 0..20 m, dark brown to orange to pale
const int DEBUG_VIEW_DEPOSITION = 11; ///< deposition 0..20 m, dark olive to sand
const int DEBUG_VIEW_WATER = 12;      ///< water 0..1, dark grey to cyan
// The rock views show the mesh's rock masks (rockDebugColor()).
const int DEBUG_VIEW_HARDNESS = 13; ///< rock hardness 0..1, plum to rose to cream
const int DEBUG_VIEW_BED = 14;      ///< the bed, one colour per index (golden-ratio steps along a ramp)
const int DEBUG_VIEW_COUNT = 15;

/// The sRGB decoding function, for one encoded value 0..1 (inverse of
/// linearToSrgb()).
STRATA_INLINE float srgbToLinear(float c)
{
    if (c <= 0.04045f) {
        return max(c, 0.0f) / 12.92f;
    }
    return pow((min(c, 1.0f) + 0.055f) / 1.055f, 2.4f);
}

/// The colour of debug view `view` (DEBUG_VIEW_*) for a fragment: a linear
/// display value 0..1 like shadeFragment()'s, so the sRGB encoding stores
/// the data views' values unchanged (value v becomes byte round(255·v)),
/// while albedo is shown as the colour it is. DEBUG_VIEW_SHADED, the
/// landform and rock views and unknown views give black.
STRATA_INLINE vec3 debugViewColor(SurfaceOutput o, int view)
{
    vec3 v = vec3(0.0f);
    if (view == DEBUG_VIEW_ALBEDO) {
        return saturate(o.albedo);
    }
    if (view == DEBUG_VIEW_LAYERS) {
        return saturate(o.layerColor);
    }
    if (view == DEBUG_VIEW_WEIGHTS) {
        v = o.weights;
    } else if (view == DEBUG_VIEW_NORMALS) {
        v = o.normal * 0.5f + vec3(0.5f);
    } else if (view == DEBUG_VIEW_METALLIC) {
        v = vec3(o.metallic);
    } else if (view == DEBUG_VIEW_OCCLUSION) {
        v = vec3(o.occlusion);
    } else if (view == DEBUG_VIEW_HEIGHT) {
        v = vec3(o.height);
    } else if (view == DEBUG_VIEW_SMOOTHNESS) {
        v = vec3(o.smoothness);
    }
    v = saturate(v);
    return vec3(srgbToLinear(v.x), srgbToLinear(v.y), srgbToLinear(v.z));
}

/// A debug view of the material at one fragment (no lighting).
STRATA_FEATURE_FUNCTION vec3 shadeDebugFragment(STRATA_MAPS_PARAM SurfaceInput s, MaterialParams m, int view)
{
    return debugViewColor(evaluateSurface STRATA_FEATURE_ARGS(STRATA_MAPS_ARG s, m), view);
}

#undef SAMPLE_TILED

#endif // STRATA_TRIPLANAR_MATERIAL_H
