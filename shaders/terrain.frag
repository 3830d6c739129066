// Terrain fragment shader: albedo-only triplanar material (side maps for
// the X and Z projections, an optional top map for the Y projection on
// upward faces), Lambert sun plus hemisphere ambient, ACES tone map.
// Output is linear; the sRGB framebuffer encodes it.

in vec3 vTexturePosition;
in vec3 vNormal;

uniform sampler2D uSideAlbedo; // sRGB texture: sampled values are linear
uniform sampler2D uTopAlbedo;  // sRGB texture; used only when uHasTopAlbedo (else the side map)
uniform bool uHasTopAlbedo;
uniform float uBlendOffset;
uniform float uBlendExponent;
uniform vec3 uSunDirection;    // unit, towards the sun
uniform vec3 uSunColor;
uniform vec3 uSkyAmbient;
uniform vec3 uGroundAmbient;

layout(location = 0) out vec4 fragColor;

void main()
{
    float len = length(vNormal);
    vec3 n = len > 1e-12f ? vNormal / len : vec3(0.0f, 1.0f, 0.0f);

    TriplanarUV uv = triplanarUV(vTexturePosition, n);
    vec3 weights = triplanarWeights(n, uBlendOffset, uBlendExponent);

    vec3 albedoX = texture(uSideAlbedo, uv.x).rgb;
    vec3 albedoY = texture(uSideAlbedo, uv.y).rgb;
    vec3 albedoZ = texture(uSideAlbedo, uv.z).rgb;
    // Sampled outside the branch: implicit derivatives need uniform control flow.
    vec3 topY = texture(uTopAlbedo, uv.y).rgb;
    if (uHasTopAlbedo && n.y > 0.0f) {
        albedoY = topY;
    }
    vec3 albedo = triplanarBlend(albedoX, albedoY, albedoZ, weights);

    vec3 radiance = shadeLambertHemisphere(albedo, n, uSunDirection, uSunColor, uSkyAmbient, uGroundAmbient);
    fragColor = vec4(toneMapAces(radiance), 1.0f);
}
