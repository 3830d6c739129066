// Terrain fragment shader: the triplanar material of TriplanarMaterial.h for
// the feature set STRATA_FEATURES (defined by the renderer), lit by the
// minimalist Cook–Torrance BRDF, hemisphere ambient, exposure and ACES.
// Output is linear; the sRGB framebuffer encodes it.

in vec3 vTexturePosition; // texture space
in vec3 vNormal;
in vec3 vPosition;        // metres, relative to the mesh origin

// The nine map slots (MAP_* in TriplanarMaterial.h); sRGB textures sample linear.
uniform sampler2D uMaps[STRATA_MAP_COUNT];
uniform MaterialParams uMaterial;
uniform LightingParams uLighting;
uniform vec3 uCameraPosition; // relative to the mesh origin

layout(location = 0) out vec4 fragColor;

// Explicit gradients: the material samples inside branches (skipped
// projections, top maps), where implicit derivatives are undefined.
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
    float len = length(vNormal);
    SurfaceInput s;
    s.n = len > 1e-12f ? vNormal / len : vec3(0.0f, 1.0f, 0.0f);
    s.p = vTexturePosition;
    s.dpdx = dFdx(vTexturePosition);
    s.dpdy = dFdy(vTexturePosition);
    s.viewDir = safeNormalize(uCameraPosition - vPosition, s.n);
    fragColor = vec4(shadeFragment(s, uMaterial, uLighting), 1.0f);
}
