// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

/// \file
/// The sky and aerial perspective, in the common subset of GLSL 4.50 and
/// C++20 (the editing rules are TriplanarShading.h's, whose functions it
/// uses; nothing of the material's): a sky gradient with
/// the sun, and exponential height fog whose colour is the sky's at the
/// horizon plus the sun's forward-scattered glow, so that distant terrain
/// fades into the horizon it stands against. Both renderers call these
/// functions: the GL sky pass (sky.frag) and terrain.frag, and the CPU
/// renderer for its sky pixels and fragments.
///
/// Positions are metres relative to the mesh origin, as everywhere in the
/// shaders; the host subtracts the origin from the fog's base height in
/// double, so a world 1e7 m from the origin keeps its precision.

#ifndef STRATA_ATMOSPHERE_H
#define STRATA_ATMOSPHERE_H

/// The atmosphere's parameters, laid out as its std140 block (binding 4 of
/// the terrain and sky programs; offsets checked in
/// render/src/AtmosphereSetup.h).
struct AtmosphereParams
{
    /// inverse(projection · view rotation): normalised device coordinates
    /// to a view ray in world axes (no translation: the ray's direction only).
    mat4 skyRayMatrix;
    vec3 zenithColor;   ///< sky radiance straight up, linear
    float fogDensity;   ///< extinction per metre at fogBaseHeight (0: no fog)
    vec3 horizonColor;  ///< sky radiance at the horizon, and the fog's colour
    float fogFalloff;   ///< per metre of height: the density is × e^(−falloff · (y − base))
    vec3 sunDirection;  ///< unit, towards the sun
    float fogBaseHeight; ///< metres, relative to the mesh origin
    vec3 sunColor;      ///< the sun's radiance (its disc and its glow scale with it)
    float sunGlow;      ///< strength of the forward-scattered glow around the sun, in the sky and the fog
    vec2 viewportSize;  ///< pixels, for gl_FragCoord → device coordinates
    float sunDiscCos;   ///< cosine of the sun disc's angular radius; ≥ 1: no disc
    int enabled;        ///< 0: a flat background and no fog (LightingParams' skyColor path)
    float exposure;     ///< the lighting's exposure, for the sky pass
    float padding0;     ///< (std140 rounds a block's struct up to 16 bytes)
    float padding1;
    float padding2;
};

/// The sun's glow towards unit direction `dir`: (max(0, dir·sun))^8 ×
/// sunGlow × sunColor (products, no pow: the same bits on both sides).
STRATA_INLINE vec3 sunGlowRadiance(AtmosphereParams a, vec3 dir)
{
    float s = saturate(dot(dir, a.sunDirection));
    float s2 = s * s;
    float s4 = s2 * s2;
    return a.sunColor * (a.sunGlow * s4 * s4);
}

/// The radiance the air scatters towards the camera along unit view ray
/// `dir`: the horizon colour plus the sun's glow. Fog tends to it with
/// distance; the sky equals it at the horizon.
STRATA_INLINE vec3 inscatterRadiance(AtmosphereParams a, vec3 dir)
{
    return a.horizonColor + sunGlowRadiance(a, dir);
}

/// Sky radiance along unit view ray `dir` (linear, before exposure): the
/// horizon colour turning to the zenith colour as the ray rises
/// (1 − (1 − y)^4: a narrow bright band above the horizon; half of that
/// below it), the sun's glow,
/// and its disc (16 × sunColor: white after the tone map) with a soft edge.
STRATA_INLINE vec3 skyRadiance(AtmosphereParams a, vec3 dir)
{
    float off = 1.0f - min(abs(dir.y), 1.0f);
    float off2 = off * off;
    float rise = 1.0f - off2 * off2;
    // Below the horizon (the void under a diorama) the gradient is mirrored
    // at half strength rather than left flat.
    vec3 sky = mix(a.horizonColor, a.zenithColor, dir.y >= 0.0f ? rise : 0.5f * rise) + sunGlowRadiance(a, dir);
    if (a.sunDiscCos < 1.0f) { // ≥ 1: no disc (smoothstep needs edge0 < edge1)
        float edge = (1.0f - a.sunDiscCos) * 0.36f; // the soft edge, in 1 − cos terms
        float disc = smoothstep(a.sunDiscCos, a.sunDiscCos + edge, dot(dir, a.sunDirection));
        sky += a.sunColor * (16.0f * disc);
    }
    return sky;
}

/// The unit view ray through normalised device coordinates `ndc` (−1..1,
/// y up): the ray matrix maps a point of the ray at depth 0 to its
/// direction. Falls back to straight ahead in −Z for a degenerate matrix.
STRATA_INLINE vec3 skyRayDirection(AtmosphereParams a, vec2 ndc)
{
    vec4 h = a.skyRayMatrix * vec4(ndc.x, ndc.y, 0.0f, 1.0f);
    vec3 p = vec3(h.x, h.y, h.z) / h.w;
    return safeNormalize(p, vec3(0.0f, 0.0f, -1.0f));
}

/// Optical depth of the height fog along the segment `from` → `to` (metres,
/// relative to the mesh origin): fogDensity · |to − from| times the mean of
/// e^(−falloff · (y − base)) over the segment, which is
/// (e^(−h0) − e^(−h1)) / (h1 − h0) for the scaled heights h0, h1 (its
/// series where they are within 1e-3, which avoids the cancellation).
/// Scaled heights are clamped to ±60, so the result is finite for any
/// input (beyond that the fog is either opaque or absent anyway); 0 for a
/// zero-length segment or zero density.
STRATA_INLINE float fogOpticalDepth(AtmosphereParams a, vec3 from, vec3 to)
{
    float distance = length(to - from);
    float h0 = clamp(a.fogFalloff * (from.y - a.fogBaseHeight), -60.0f, 60.0f);
    float h1 = clamp(a.fogFalloff * (to.y - a.fogBaseHeight), -60.0f, 60.0f);
    float dh = h1 - h0;
    float mean;
    if (abs(dh) < 1e-3f) {
        mean = exp(-h0) * (1.0f - dh * (0.5f - dh * (1.0f / 6.0f)));
    } else {
        mean = (exp(-h0) - exp(-h1)) / dh;
    }
    return a.fogDensity * distance * mean;
}

/// Aerial perspective: the lit radiance of a surface at `position` seen from
/// `cameraPosition` (both relative to the mesh origin), attenuated by the
/// fog's transmittance and filled in with the in-scattered radiance along
/// the ray. Unchanged when the atmosphere is off.
STRATA_INLINE vec3 applyAerialPerspective(AtmosphereParams a, vec3 radiance, vec3 cameraPosition, vec3 position)
{
    if (a.enabled == 0) {
        return radiance;
    }
    vec3 ray = position - cameraPosition;
    vec3 dir = safeNormalize(ray, vec3(0.0f, -1.0f, 0.0f));
    float transmittance = exp(-fogOpticalDepth(a, cameraPosition, position));
    return mix(inscatterRadiance(a, dir), radiance, transmittance);
}

/// What a terrain fragment at `position` shows: its lit radiance through the
/// atmosphere, exposed and tone mapped (a linear display value 0..1).
STRATA_INLINE vec3 finishFragment(vec3 radiance, float exposure, AtmosphereParams a, vec3 cameraPosition,
                                  vec3 position)
{
    return toneMap(applyAerialPerspective(a, radiance, cameraPosition, position), exposure);
}

/// What a sky pixel at device coordinates `ndc` shows, exposed and tone
/// mapped like the terrain (only with the atmosphere on: otherwise the
/// renderers clear to the flat background colour).
STRATA_INLINE vec3 skyPixel(AtmosphereParams a, float exposure, vec2 ndc)
{
    return toneMap(skyRadiance(a, skyRayDirection(a, ndc)), exposure);
}

#endif // STRATA_ATMOSPHERE_H
