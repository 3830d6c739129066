// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Terrain fragment shader: the triplanar material of TriplanarMaterial.h for
// the feature set STRATA_FEATURES (defined by the renderer), lit by the
// minimalist Cook–Torrance BRDF, hemisphere ambient, seen through the
// atmosphere (Atmosphere.h), exposure and ACES, or one of the debug views
// (uFrame.debugView). Output is linear; the sRGB framebuffer encodes it.

in vec3 vTexturePosition; // texture space
in vec3 vNormal;
in vec3 vPosition;        // metres, relative to the mesh origin
in vec2 vSurface;         // cavity, cover (layer rules)
in vec4 vLandform;        // flow, wear, deposition, water (layer rules, landform debug views)
in vec2 vRock;            // hardness, bed (layer rules, rock debug views)

// std140 blocks, mirrored by render/src/UniformBlocks.h (FrameBlock, binding
// 0, is in TerrainFrame.glsl).
layout(std140, binding = 1) uniform MaterialBlock
{
    MaterialParams uMaterial;
};
layout(std140, binding = 2) uniform LightingBlock
{
    LightingParams uLighting;
};

// The nine map slots (MAP_* in TriplanarMaterial.h) on texture units 0..8,
// each a texture array with one layer per material layer (TerrainLayers.h;
// one layer without layers); sRGB textures sample linear.
layout(binding = 0) uniform sampler2DArray uMaps[STRATA_MAP_COUNT];
#ifdef STRATA_LAYERED
#define MAP_LAYER float(gLayer)
#else
#define MAP_LAYER 0.0f
#endif

// Sun shadows (Shadow.h): the parameters (binding 3, mirrored by
// shading::ShadowParams, checked in render/src/ShadowSetup.h) and the depth
// map on unit 9, read texel by texel (no hardware comparison or filtering:
// the PCF is Shadow.h's, the same on the CPU).
layout(std140, binding = 3) uniform ShadowBlock
{
    ShadowParams uShadow;
};
layout(binding = 9) uniform sampler2D uShadowMap;

// The sky and aerial perspective (Atmosphere.h; mirrored by
// shading::AtmosphereParams, checked in render/src/AtmosphereSetup.h).
layout(std140, binding = 4) uniform AtmosphereBlock
{
    AtmosphereParams uAtmosphere;
};

float shadowMapDepth(int x, int y)
{
    return texelFetch(uShadowMap, ivec2(x, y), 0).x;
}

layout(location = 0) out vec4 fragColor;

// The level of detail of a map of `size` texels sampled with the explicit
// gradients below, as the GL specification defines it and the CPU reference
// computes it (render/src/Texture.cpp, textureLod): the larger footprint
// in texels, lambda = log2 of it. Computed here and sampled with textureLod
// (uFrame.explicitLod), the GPU's own approximation of lambda (each vendor
// has one) no longer picks the mip level.
float mapLod(ivec3 size, vec2 dUVdx, vec2 dUVdy)
{
    vec2 x = dUVdx * vec2(size.xy), y = dUVdy * vec2(size.xy);
    float rho2 = max(dot(x, x), dot(y, y));
    if (!(rho2 > 0.0)) return -1000.0; // zero or NaN: the finest level
    if (isinf(rho2)) return 1000.0;
    return 0.5 * log2(rho2);
}

// Explicit gradients: the material samples inside branches (skipped
// projections, top maps), where implicit derivatives are undefined.
#define STRATA_SAMPLE_MAP(i)                                                                                   \
    (uFrame.explicitLod != 0                                                                                   \
         ? textureLod(uMaps[i], vec3(uv, MAP_LAYER), mapLod(textureSize(uMaps[i], 0), dUVdx, dUVdy))          \
         : textureGrad(uMaps[i], vec3(uv, MAP_LAYER), dUVdx, dUVdy))
vec4 sampleMap(int map, vec2 uv, vec2 dUVdx, vec2 dUVdy)
{
    switch (map) {
    case 0: return STRATA_SAMPLE_MAP(0);
    case 1: return STRATA_SAMPLE_MAP(1);
    case 2: return STRATA_SAMPLE_MAP(2);
    case 3: return STRATA_SAMPLE_MAP(3);
    case 4: return STRATA_SAMPLE_MAP(4);
    case 5: return STRATA_SAMPLE_MAP(5);
    case 6: return STRATA_SAMPLE_MAP(6);
    case 7: return STRATA_SAMPLE_MAP(7);
    default: return STRATA_SAMPLE_MAP(8);
    }
}

void main()
{
    if (uFrame.wireframePass != 0) {
        fragColor = uFrame.wireColor;
        return;
    }
    float len = length(vNormal);
    SurfaceInput s;
    s.n = len > 1e-12f ? vNormal / len : vec3(0.0f, 1.0f, 0.0f);
    s.p = vTexturePosition;
    s.detailOffset = uFrame.detailOffset.xyz;
    s.tileOffset = uFrame.tileOffset.xyz;
    s.dpdx = dFdx(vTexturePosition);
    s.dpdy = dFdy(vTexturePosition);
    s.viewDir = safeNormalize(vec3(uFrame.cameraPosition) - vPosition, s.n);
    // shadeFragment() and shadeDebugFragment() of TriplanarMaterial.h with
    // the material evaluated once, so the program holds one copy of it
    // (this halves llvmpipe's compile time per variant).
#ifdef STRATA_LAYERED
    // Each layer maps the position with its own scale (TerrainLayers.h).
    SurfaceInput world = s;
    world.p = vPosition;
    world.dpdx = dFdx(vPosition);
    world.dpdy = dFdy(vPosition);
    SurfaceOutput o = evaluateLayers(world, vSurface, vLandform, vRock);
#else
    SurfaceOutput o = evaluateSurface(s, uMaterial);
#endif
    if (uFrame.debugView != DEBUG_VIEW_SHADED) {
        fragColor = vec4(fragmentDebugColor(o, vLandform, vRock, uFrame.debugView), 1.0f);
        return;
    }
    // The interpolated normal (not the mapped one) biases the shadow lookup.
    float sun = sunVisibility(uShadow, vPosition, vNormal);
    LightingParams lit = shadowedLighting(uLighting, sun);
    vec3 radiance = lightSurface(o, s.viewDir, lit, o.fresnelStrength);
    fragColor = vec4(finishFragment(radiance, lit.exposure, uAtmosphere, vec3(uFrame.cameraPosition), vPosition), 1.0f);
}
