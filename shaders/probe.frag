// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Shading probe (tests/render/ShadingProbeTest.cpp): evaluates the shared
// material (TriplanarMaterial.h, feature set STRATA_FEATURES, defined by the
// caller after the #version line) at sample points given as data instead of
// rasterized, so GL and the C++ build of the same header can be compared
// value by value. Pixel (x, y) of the RGBA32F targets is sample
// y·PROBE_COLUMNS + x; its inputs are row `sample` of uInputs (RGBA32F, 5
// texels: texture-space position, unit normal, dp/dx, dp/dy, view direction).

const int PROBE_COLUMNS = 64;

layout(std140, binding = 1) uniform MaterialBlock
{
    MaterialParams uMaterial;
};
layout(std140, binding = 2) uniform LightingBlock
{
    LightingParams uLighting;
};

layout(binding = 0) uniform sampler2D uMaps[STRATA_MAP_COUNT];
layout(binding = 10) uniform sampler2D uInputs;

layout(location = 0) out vec4 outWeights; // xyz: blend weights
layout(location = 1) out vec4 outNormal;  // xyz: the mapped world normal
layout(location = 2) out vec4 outColor;   // xyz: shadeFragment(), linear display value
layout(location = 3) out vec4 outAlbedo;  // xyz: albedo; w: smoothness

vec4 sampleMap(int map, vec2 uv, vec2 dUVdx, vec2 dUVdy)
{
    switch (map) {
    case 0: return textureGrad(uMaps[0], uv, dUVdx, dUVdy);
    case 1: return textureGrad(uMaps[1], uv, dUVdx, dUVdy);
    case 2: return textureGrad(uMaps[2], uv, dUVdx, dUVdy);
    case 3: return textureGrad(uMaps[3], uv, dUVdx, dUVdy);
    case 4: return textureGrad(uMaps[4], uv, dUVdx, dUVdy);
    case 5: return textureGrad(uMaps[5], uv, dUVdx, dUVdy);
    case 6: return textureGrad(uMaps[6], uv, dUVdx, dUVdy);
    case 7: return textureGrad(uMaps[7], uv, dUVdx, dUVdy);
    default: return textureGrad(uMaps[8], uv, dUVdx, dUVdy);
    }
}

void main()
{
    int index = int(gl_FragCoord.y) * PROBE_COLUMNS + int(gl_FragCoord.x);
    if (index >= textureSize(uInputs, 0).y) {
        outWeights = vec4(0.0f);
        outNormal = vec4(0.0f);
        outColor = vec4(0.0f);
        outAlbedo = vec4(0.0f);
        return;
    }
    SurfaceInput s;
    s.p = texelFetch(uInputs, ivec2(0, index), 0).xyz;
    s.detailOffset = vec3(0.0f);
    s.tileOffset = vec3(0.0f);
    s.n = texelFetch(uInputs, ivec2(1, index), 0).xyz;
    s.dpdx = texelFetch(uInputs, ivec2(2, index), 0).xyz;
    s.dpdy = texelFetch(uInputs, ivec2(3, index), 0).xyz;
    s.viewDir = texelFetch(uInputs, ivec2(4, index), 0).xyz;
    SurfaceOutput o = evaluateSurface(s, uMaterial);
    outWeights = vec4(o.weights, 1.0f);
    outNormal = vec4(o.normal, 1.0f);
    outColor = vec4(shadeFragment(s, uMaterial, uLighting), 1.0f);
    outAlbedo = vec4(o.albedo, o.smoothness);
}
