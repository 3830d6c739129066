// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

/// \file
/// Terrain layers: up to STRATA_MAX_LAYERS triplanar materials (rock, grass,
/// sand, snow...) painted over one another by placement rules and combined
/// by the seeds' height blend generalised to N layers, in the common subset
/// of GLSL 4.50 and C++20 (the editing rules are TriplanarShading.h's).
///
/// Per fragment:
///  1. each layer's *coverage* c from its rule: soft bands on altitude,
///     slope, the mesh's baked cavity and cover ("under rock"), its
///     landform masks from erosion (flow, wear, deposition, water), and a
///     noise mask, times its opacity (layer 0, the base, covers everything);
///  2. painter's order: a layer hides what lies under it, so layer i keeps
///     a_i = c_i · Π_{j>i} (1 − c_j) (the a_i sum to 1);
///  3. every layer with a_i > 0 is evaluated (evaluateSurface(), its own
///     maps, feature set and texture scale); layers with a_i = 0 cost nothing;
///  4. height blend: key_i = height_i + a_i, where height_i is the layer's
///     blended MOHS height (0.5 without one); the highest key wins and the
///     others within `blendDepth` of it share: w_i = a_i · max(key_i − (best −
///     blendDepth), 0), normalised. So sand fills the gaps between rocks
///     instead of cross-fading, and a layer fades in continuously as its
///     coverage rises from 0.
///
/// Map fetches go through SAMPLE_MAP like a single material's; the layer to
/// sample is selected with STRATA_SELECT_LAYER (GLSL: a global that
/// sampleMap() reads as the texture array's layer; C++: the sampler's).

#ifndef STRATA_TERRAIN_LAYERS_H
#define STRATA_TERRAIN_LAYERS_H

#define STRATA_MAX_LAYERS 8

/// One layer's placement rule and texture mapping. A band (vec4) is
/// (min, max, softness, enabled): weight 1 inside [min, max], smooth ramps
/// `softness` wide outside each bound, 0 beyond; enabled = 0 switches it
/// off (weight 1). std140: 256 bytes (offsets checked in
/// render/src/LayerSetup.h).
struct LayerParams
{
    vec4 altitude;      ///< band on the height, metres relative to the mesh origin (the host subtracts it in double)
    vec4 slope;         ///< band on the slope in degrees: 0 flat ground, 90 a wall, 180 a ceiling
    vec4 cavity;        ///< band on the vertex cavity (0 open .. 1 a deep crevice)
    vec4 cover;         ///< band on the vertex cover (0 open sky .. 1 rock overhead)
    vec4 flow;          ///< band on the vertex flow: log10 of the drainage area in m² (landform x)
    vec4 wear;          ///< band on the vertex wear: metres eroded (landform y)
    vec4 deposition;    ///< band on the vertex deposition: metres of sediment (landform z)
    vec4 water;         ///< band on the vertex water: 0 dry .. 1 river or lake (landform w)
    vec4 hardness;      ///< band on the vertex rock hardness: 0 soft .. 1 hard (rock x)
    vec4 bed;           ///< band on the vertex bed: its index in the beds' sequence (rock y)
    vec4 noise;         ///< x: frequency (1/m), y: threshold 0..1, z: softness, w: enabled
    vec4 noiseOffset;   ///< xyz: origin · frequency modulo the noise period (in double on the host)
    vec4 textureOffset; ///< xyz: fract(origin · mapScale), as FrameBlock's
    vec4 detailOffset;  ///< xyz: as FrameBlock's, for this layer's scales
    vec4 tileOffset;    ///< xyz: as FrameBlock's, for this layer's mapScale
    float mapScale;     ///< texture repeats per metre
    float opacity;      ///< 0..1: multiplies the coverage
    uint features;      ///< the layer's feature set (FEATURE_* bits)
    uint seed;          ///< of the noise mask
};

/// Every layer of a material; layer 0 is the base.
struct LayerSetParams
{
    LayerParams layers[STRATA_MAX_LAYERS];
    MaterialParams materials[STRATA_MAX_LAYERS];
    int count;        ///< 1..STRATA_MAX_LAYERS
    float blendDepth; ///< > 0: how far below the highest key a layer still shows
    float padding0;
    float padding1;
};

#ifdef STRATA_GLSL
#ifdef STRATA_LAYERED
// The layer set of layered terrain programs (mirrored by
// render::detail::LayerSetBlock).
layout(std140, binding = 5) uniform LayerBlock
{
    LayerSetParams uLayerSet;
};
#endif
#endif

/// Weight of `x` in the soft band `band` (see LayerParams): smoothstep
/// ramps, exact 0 and 1 away from the bounds, 1 when the band is off.
/// Unbounded sides are stored as ±1e30 (no overflow: x is finite).
STRATA_INLINE float bandWeight(float x, vec4 band)
{
    if (band.w < 0.5f) {
        return 1.0f;
    }
    float s = max(band.z, 1e-6f);
    float up = saturate((x - band.x) / s + 1.0f);
    float down = saturate((band.y - x) / s + 1.0f);
    up = up * up * (3.0f - 2.0f * up);
    down = down * down * (3.0f - 2.0f * down);
    return up * down;
}

/// The lattice value at (x, y, z) in [0, 1].
STRATA_INLINE float latticeValue(int x, int y, int z, uint seed)
{
    return float(latticeHash(x, y, z, seed) & 65535u) / 65535.0f;
}

/// Value noise in [0, 1]: lattice values blended with smoothstep weights.
STRATA_INLINE float valueNoise(vec3 p, uint seed)
{
    vec3 f = floor(p);
    int x = int(f.x);
    int y = int(f.y);
    int z = int(f.z);
    vec3 t = p - f;
    t = t * t * (vec3(3.0f) - t * 2.0f);
    float a = mix(latticeValue(x, y, z, seed), latticeValue(x + 1, y, z, seed), t.x);
    float b = mix(latticeValue(x, y + 1, z, seed), latticeValue(x + 1, y + 1, z, seed), t.x);
    float c = mix(latticeValue(x, y, z + 1, seed), latticeValue(x + 1, y, z + 1, seed), t.x);
    float d = mix(latticeValue(x, y + 1, z + 1, seed), latticeValue(x + 1, y + 1, z + 1, seed), t.x);
    return mix(mix(a, b, t.y), mix(c, d, t.y), t.z);
}

/// Three octaves of value noise (gain ½, lacunarity 2), in [0, 1]. Every
/// octave's lattice period (256 cells) is a multiple of the first's, so the
/// host's rebasing (modulo 256) holds for all of them.
STRATA_INLINE float layerNoise(vec3 p, uint seed)
{
    float n = valueNoise(p, seed) + 0.5f * valueNoise(p * 2.0f, seed + 1u) + 0.25f * valueNoise(p * 4.0f, seed + 2u);
    return n / 1.75f;
}

/// A layer's coverage at a fragment: opacity × every enabled band.
/// `n` is the unit interpolated (not normal-mapped) normal, `position`
/// metres relative to the mesh origin, `surface` the interpolated cavity
/// and cover, `landform` the interpolated flow, wear, deposition and water,
/// `rock` the interpolated hardness and bed.
STRATA_INLINE float layerCoverage(LayerParams l, vec3 n, vec3 position, vec2 surface, vec4 landform, vec2 rock)
{
    float c = l.opacity;
    c *= bandWeight(position.y, l.altitude);
    c *= bandWeight(degrees(acos(clamp(n.y, -1.0f, 1.0f))), l.slope);
    c *= bandWeight(surface.x, l.cavity);
    c *= bandWeight(surface.y, l.cover);
    c *= bandWeight(landform.x, l.flow);
    c *= bandWeight(landform.y, l.wear);
    c *= bandWeight(landform.z, l.deposition);
    c *= bandWeight(landform.w, l.water);
    c *= bandWeight(rock.x, l.hardness);
    c *= bandWeight(rock.y, l.bed);
    if (l.noise.w > 0.5f && c > 0.0f) {
        vec3 q = position * l.noise.x + vec3(l.noiseOffset.x, l.noiseOffset.y, l.noiseOffset.z);
        c *= bandWeight(layerNoise(q, l.seed), vec4(l.noise.y, 1e30f, l.noise.z, 1.0f));
    }
    return c;
}

/// The height a layer competes with in the blend: its blended MOHS height
/// when it has one, else ½.
STRATA_INLINE float layerHeight(SurfaceOutput o, uint features)
{
    if ((features & FEATURE_MASK_MAP) != 0u && (features & FEATURE_MODS) == 0u) {
        return saturate(o.height);
    }
    return 0.5f;
}

/// Adds `o` × `w` to the running sum `sum` (normal, weights and the
/// scalars; normalised by the caller).
STRATA_INLINE SurfaceOutput accumulateSurface(SurfaceOutput sum, SurfaceOutput o, float w)
{
    sum.albedo += o.albedo * w;
    sum.normal += o.normal * w;
    sum.weights += o.weights * w;
    sum.emission += o.emission * w;
    sum.metallic += o.metallic * w;
    sum.occlusion += o.occlusion * w;
    sum.smoothness += o.smoothness * w;
    sum.height += o.height * w;
    sum.layerColor += o.layerColor * w;
    sum.fresnelStrength += o.fresnelStrength * w;
    return sum;
}

// ---------------------------------------------------------------------------
// Landform and rock debug views: the mesh's landform and rock masks as
// colours, on any program (layered or not).

/// A three-stop ramp at t in [0, 1] (clamped) through `a`, `b` and `c`,
/// given as display (sRGB-encoded) values and returned linear, like
/// debugViewColor()'s data views.
STRATA_INLINE vec3 rampColor(float t, vec3 a, vec3 b, vec3 c)
{
    float u = saturate(t) * 2.0f;
    vec3 v = u < 1.0f ? mix(a, b, u) : mix(b, c, u - 1.0f);
    return vec3(srgbToLinear(v.x), srgbToLinear(v.y), srgbToLinear(v.z));
}

/// The colour of a landform debug view (DEBUG_VIEW_FLOW .. WATER) for the
/// interpolated landform masks (flow, wear, deposition, water): flow 0..7
/// (log10 m²), wear and deposition 0..20 m, water 0..1, each on its own
/// ramp, so every view differs even where the masks are 0. Other views
/// give black.
STRATA_INLINE vec3 landformDebugColor(vec4 landform, int view)
{
    if (view == DEBUG_VIEW_FLOW) {
        return rampColor(landform.x / 7.0f, vec3(0.05f, 0.06f, 0.16f), vec3(0.13f, 0.42f, 0.85f),
                         vec3(0.85f, 0.95f, 1.0f));
    }
    if (view == DEBUG_VIEW_WEAR) {
        return rampColor(landform.y / 20.0f, vec3(0.14f, 0.09f, 0.05f), vec3(0.80f, 0.38f, 0.10f),
                         vec3(1.0f, 0.88f, 0.60f));
    }
    if (view == DEBUG_VIEW_DEPOSITION) {
        return rampColor(landform.z / 20.0f, vec3(0.10f, 0.11f, 0.04f), vec3(0.55f, 0.55f, 0.15f),
                         vec3(0.96f, 0.90f, 0.58f));
    }
    if (view == DEBUG_VIEW_WATER) {
        return rampColor(landform.w, vec3(0.16f, 0.14f, 0.12f), vec3(0.10f, 0.45f, 0.60f), vec3(0.25f, 0.90f, 1.0f));
    }
    return vec3(0.0f);
}

/// The colour of a rock debug view (DEBUG_VIEW_HARDNESS, BED) for the
/// interpolated rock masks (hardness, bed): hardness 0..1 on a ramp; the
/// bed rounded to its index, each index a colour (golden-ratio steps along
/// a ramp, so neighbouring beds differ). Other views give black.
STRATA_INLINE vec3 rockDebugColor(vec2 rock, int view)
{
    if (view == DEBUG_VIEW_HARDNESS) {
        return rampColor(rock.x, vec3(0.30f, 0.08f, 0.24f), vec3(0.86f, 0.42f, 0.40f), vec3(0.98f, 0.94f, 0.82f));
    }
    if (view == DEBUG_VIEW_BED) {
        float index = floor(rock.y + 0.5f);
        float t = index * 0.618034f;
        return rampColor(t - floor(t), vec3(0.08f, 0.32f, 0.22f), vec3(0.90f, 0.76f, 0.22f),
                         vec3(0.52f, 0.22f, 0.72f));
    }
    return vec3(0.0f);
}

/// The colour of any debug view at a fragment: the landform views from
/// `landform`, the rock views from `rock`, the others from the material's
/// output `o` (debugViewColor()).
STRATA_INLINE vec3 fragmentDebugColor(SurfaceOutput o, vec4 landform, vec2 rock, int view)
{
    if (view >= DEBUG_VIEW_FLOW && view <= DEBUG_VIEW_WATER) {
        return landformDebugColor(landform, view);
    }
    if (view == DEBUG_VIEW_HARDNESS || view == DEBUG_VIEW_BED) {
        return rockDebugColor(rock, view);
    }
    return debugViewColor(o, view);
}

#if defined(STRATA_CPP) || defined(STRATA_LAYERED)

/// Every layer at one fragment, blended. `world` holds the fragment in
/// metres: p relative to the mesh origin, dpdx/dpdy its screen
/// derivatives; each layer maps it with its own mapScale and offsets.
/// `surface` is the interpolated cavity and cover, `landform` the
/// interpolated landform masks (flow, wear, deposition, water), `rock` the
/// interpolated rock masks (hardness, bed). Always
/// finite: the a_i sum to 1, so the highest key's layer has a positive
/// weight (layer 0 alone when no rule covers the fragment; the winner alone
/// should every weight underflow).
STRATA_FEATURE_FUNCTION SurfaceOutput evaluateLayers(STRATA_MAPS_PARAM STRATA_LAYERS_PARAM SurfaceInput world,
                                                     vec2 surface, vec4 landform, vec2 rock)
{
    // GLSL programs are built for their layer count (STRATA_LAYER_COUNT), so
    // the loops unroll to exactly that many copies of the material; C++
    // reads the count at run time.
#ifdef STRATA_LAYER_COUNT
    const int count = STRATA_LAYER_COUNT;
#else
    int count = min(max(LAYER_SET.count, 1), STRATA_MAX_LAYERS);
#endif
    float share[STRATA_MAX_LAYERS];
    float keys[STRATA_MAX_LAYERS];
    SurfaceOutput outputs[STRATA_MAX_LAYERS];
    float remaining = 1.0f;
    for (int i = count - 1; i >= 0; --i) {
        float c = i == 0 ? 1.0f : layerCoverage(LAYER_SET.layers[i], world.n, world.p, surface, landform, rock);
        share[i] = c * remaining;
        remaining *= 1.0f - c;
    }

    float best = -1e30f;
    int bestLayer = 0;
    for (int i = 0; i < count; ++i) {
        keys[i] = -1e30f;
        if (share[i] > 0.0f) {
            LayerParams l = LAYER_SET.layers[i];
            SurfaceInput s = world;
            s.p = world.p * l.mapScale + vec3(l.textureOffset.x, l.textureOffset.y, l.textureOffset.z);
            s.detailOffset = vec3(l.detailOffset.x, l.detailOffset.y, l.detailOffset.z);
            s.tileOffset = vec3(l.tileOffset.x, l.tileOffset.y, l.tileOffset.z);
            s.dpdx = world.dpdx * l.mapScale;
            s.dpdy = world.dpdy * l.mapScale;
            STRATA_SELECT_LAYER(i, l.features);
            outputs[i] = evaluateSurface STRATA_FEATURE_ARGS(STRATA_MAPS_ARG s, LAYER_SET.materials[i]);
            outputs[i].layerColor = layerPaletteColor(i);
            keys[i] = layerHeight(outputs[i], l.features) + share[i];
            if (keys[i] > best) {
                best = keys[i];
                bestLayer = i;
            }
        }
    }

    SurfaceOutput sum;
    sum.albedo = vec3(0.0f);
    sum.normal = vec3(0.0f);
    sum.weights = vec3(0.0f);
    sum.emission = vec3(0.0f);
    sum.metallic = 0.0f;
    sum.occlusion = 0.0f;
    sum.smoothness = 0.0f;
    sum.height = 0.0f;
    sum.layerColor = vec3(0.0f);
    sum.fresnelStrength = 0.0f;
    float total = 0.0f;
    for (int i = 0; i < count; ++i) {
        if (share[i] > 0.0f) {
            float w = share[i] * max(keys[i] - (best - LAYER_SET.blendDepth), 0.0f);
            if (w > 0.0f) {
                sum = accumulateSurface(sum, outputs[i], w);
                total += w;
            }
        }
    }
    if (!(total > 0.0f)) {
        return outputs[bestLayer]; // every weight underflowed: the winner alone
    }
    float inv = 1.0f / total;
    sum.albedo *= inv;
    sum.weights *= inv;
    sum.emission *= inv;
    sum.metallic *= inv;
    sum.occlusion *= inv;
    sum.smoothness *= inv;
    sum.height *= inv;
    sum.layerColor *= inv;
    sum.fresnelStrength *= inv;
    sum.normal = safeNormalize(sum.normal, world.n);
    return sum;
}

#endif

#endif // STRATA_TERRAIN_LAYERS_H
