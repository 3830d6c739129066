#include <strata/render/ProceduralTextures.h>

#include <strata/Error.h>

#include <algorithm>
#include <cmath>
#include <string>

// Determinism: every value below comes from integer hashing and the float
// operations + − × ÷, floor and sqrt, which IEEE 754 rounds exactly the same
// everywhere (this file is compiled with -ffp-contract=off). No libm
// transcendental functions, no <random> distributions.
//
// Tileability: every noise is periodic on the unit square: lattice
// coordinates wrap modulo an integer period, and coordinates are u·period.

namespace strata::render {

namespace {

struct Rgb
{
    float r, g, b; // sRGB-encoded, 0..255
};

Rgb mixRgb(const Rgb& a, const Rgb& b, float t)
{
    return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

Rgb scaleRgb(const Rgb& a, float s) { return {a.r * s, a.g * s, a.b * s}; }

float clamp01(float x) { return std::clamp(x, 0.0f, 1.0f); }

float smoothstep(float edge0, float edge1, float x)
{
    const float t = clamp01((x - edge0) / (edge1 - edge0));
    return t * t * (3.0f - 2.0f * t);
}

/// Chris Wellons' lowbias32 integer hash.
std::uint32_t hash(std::uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

std::uint32_t hash(std::int32_t x, std::int32_t y, std::uint32_t seed)
{
    return hash(std::uint32_t(x) ^ hash(std::uint32_t(y) ^ hash(seed)));
}

/// Uniform in [0, 1), 24 bits.
float unitFloat(std::uint32_t h) { return float(h >> 8) * (1.0f / 16777216.0f); }

int wrap(int i, int period)
{
    const int m = i % period;
    return m < 0 ? m + period : m;
}

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

constexpr float GRADIENTS[16][2] = {
    {1.000000000f, 0.000000000f},   {0.923879533f, 0.382683432f},   {0.707106781f, 0.707106781f},
    {0.382683432f, 0.923879533f},   {0.000000000f, 1.000000000f},   {-0.382683432f, 0.923879533f},
    {-0.707106781f, 0.707106781f},  {-0.923879533f, 0.382683432f},  {-1.000000000f, 0.000000000f},
    {-0.923879533f, -0.382683432f}, {-0.707106781f, -0.707106781f}, {-0.382683432f, -0.923879533f},
    {0.000000000f, -1.000000000f},  {0.382683432f, -0.923879533f},  {0.707106781f, -0.707106781f},
    {0.923879533f, -0.382683432f},
};

/// Periodic 2D gradient noise on the unit square with periodX × periodY
/// lattice cells; about −1..1.
float gradientNoise(float u, float v, int periodX, int periodY, std::uint32_t seed)
{
    const float x = u * float(periodX);
    const float y = v * float(periodY);
    const float fx0 = std::floor(x);
    const float fy0 = std::floor(y);
    const int ix = int(fx0);
    const int iy = int(fy0);
    const float tx = x - fx0;
    const float ty = y - fy0;

    auto corner = [&](int dx, int dy) {
        const float* g = GRADIENTS[hash(wrap(ix + dx, periodX), wrap(iy + dy, periodY), seed) & 15U];
        return g[0] * (tx - float(dx)) + g[1] * (ty - float(dy));
    };
    const float sx = fade(tx);
    const float sy = fade(ty);
    const float a = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    const float b = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    return (a + (b - a) * sy) * 1.41421356f;
}

/// Periodic fractal sum of gradient noise; each octave doubles the periods.
/// About −1..1.
float fbm(float u, float v, int periodX, int periodY, int octaves, float gain, std::uint32_t seed)
{
    float sum = 0.0f;
    float amplitude = 1.0f;
    float norm = 0.0f;
    for (int o = 0; o < octaves; ++o) {
        sum += amplitude * gradientNoise(u, v, periodX, periodY, hash(seed + std::uint32_t(o) * 0x9e3779b9U));
        norm += amplitude;
        amplitude *= gain;
        periodX *= 2;
        periodY *= 2;
    }
    return sum / norm;
}

struct Cells
{
    float f1 = 0.0f; ///< distance to the nearest feature point, in cells
    float f2 = 0.0f; ///< distance to the second nearest
    std::uint32_t id = 0; ///< hash of the nearest point's cell
};

/// Periodic Worley noise: one jittered feature point per cell of a
/// periodX × periodY lattice (unequal periods give stretched cells).
Cells cellular(float u, float v, int periodX, int periodY, std::uint32_t seed)
{
    const float x = u * float(periodX);
    const float y = v * float(periodY);
    const int ix = int(std::floor(x));
    const int iy = int(std::floor(y));
    float best1 = 1e30f;
    float best2 = 1e30f;
    std::uint32_t bestId = 0;
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            const int cx = ix + dx;
            const int cy = iy + dy;
            const std::uint32_t h = hash(wrap(cx, periodX), wrap(cy, periodY), seed);
            const float px = float(cx) + 0.1f + 0.8f * unitFloat(h);
            const float py = float(cy) + 0.1f + 0.8f * unitFloat(hash(h));
            const float ddx = px - x;
            const float ddy = py - y;
            const float d2 = ddx * ddx + ddy * ddy;
            if (d2 < best1) {
                best2 = best1;
                best1 = d2;
                bestId = h;
            } else if (d2 < best2) {
                best2 = d2;
            }
        }
    }
    return {std::sqrt(best1), std::sqrt(best2), bestId};
}

std::uint8_t toByte(float v)
{
    const float c = std::clamp(v, 0.0f, 255.0f);
    return std::uint8_t(int(c + 0.5f));
}

void checkSize(int size, const char* what)
{
    if (size < 16 || size > 16384 || (size & (size - 1)) != 0) {
        throw Error(std::string(what) + " texture size must be a power of two in 16..16384, got " +
                    std::to_string(size));
    }
}

template <typename Shader>
Image makeImage(int size, Shader&& shader)
{
    Image image;
    image.width = size;
    image.height = size;
    image.pixels.resize(std::size_t(size) * std::size_t(size) * 4);
    const float inv = 1.0f / float(size);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            // v grows upwards in the texture: row 0 (top of the image) is v ≈ 1.
            const float u = (float(x) + 0.5f) * inv;
            const float v = 1.0f - (float(y) + 0.5f) * inv;
            const Rgb c = shader(u, v);
            std::uint8_t* p = image.at(x, y);
            p[0] = toByte(c.r);
            p[1] = toByte(c.g);
            p[2] = toByte(c.b);
            p[3] = 255;
        }
    }
    return image;
}

} // namespace

Image makeRockAlbedo(int size, std::uint32_t seed)
{
    checkSize(size, "rock");
    const std::uint32_t s = hash(seed ^ 0x524f434bU); // "ROCK"

    // Sediment layers from dark to light grey-brown (sRGB).
    constexpr Rgb PALETTE[] = {
        {78.0f, 72.0f, 67.0f},    {108.0f, 98.0f, 86.0f},  {128.0f, 117.0f, 101.0f}, {94.0f, 87.0f, 81.0f},
        {142.0f, 130.0f, 112.0f}, {113.0f, 101.0f, 88.0f}, {100.0f, 95.0f, 90.0f},  {134.0f, 121.0f, 104.0f},
    };
    constexpr int PALETTE_SIZE = int(sizeof(PALETTE) / sizeof(PALETTE[0]));

    return makeImage(size, [&](float u, float v) {
        // Layers: horizontal bands whose height wobbles with a large-scale warp.
        const float warp = 0.05f * fbm(u, v, 3, 2, 3, 0.5f, s + 1U);
        const float layerCoordinate = v + warp;
        // Band index: mostly a function of height (1D noise along V, so the
        // layers stay coherent across the tile), varying a little along U.
        const float band = 0.5f + 0.55f * (0.8f * fbm(0.0f, layerCoordinate, 1, 9, 3, 0.6f, s + 2U) +
                                           0.2f * fbm(u, layerCoordinate, 2, 12, 2, 0.5f, s + 9U));
        const float index = clamp01(band) * float(PALETTE_SIZE - 1);
        const int i0 = std::min(int(std::floor(index)), PALETTE_SIZE - 2);
        // Sharpen the transitions between layers.
        const float t = smoothstep(0.3f, 0.7f, index - float(i0));
        Rgb colour = mixRgb(PALETTE[i0], PALETTE[i0 + 1], t);

        // Fine bedding lines between layers.
        const float lines = 24.0f * layerCoordinate;
        const float lineDistance = std::abs(lines - std::floor(lines + 0.5f));
        const float lineMask = smoothstep(0.1f, 0.6f, 0.5f + 0.5f * fbm(u, v, 6, 4, 2, 0.5f, s + 3U));
        const float bedding = 1.0f - 0.22f * lineMask * (1.0f - smoothstep(0.0f, 0.12f, lineDistance));

        // Mottling and grain.
        const float mottle = fbm(u, v, 8, 8, 4, 0.55f, s + 4U);
        const float grain = fbm(u, v, 64, 64, 2, 0.5f, s + 5U);
        const float speckle = gradientNoise(u, v, 192, 192, s + 8U);
        float shade = 1.0f + 0.12f * mottle + 0.07f * grain + 0.06f * speckle;

        // Cracks: borders of stretched Voronoi cells (joints), partly hidden.
        const Cells joints = cellular(u + 0.02f * mottle, v, 5, 9, s + 6U);
        const float edge = joints.f2 - joints.f1;
        const float crackMask = smoothstep(-0.1f, 0.35f, fbm(u, v, 4, 4, 3, 0.5f, s + 7U));
        const float crack = (1.0f - smoothstep(0.0f, 0.07f, edge)) * crackMask;
        // Each joint block is a slightly different shade.
        shade *= 0.93f + 0.14f * unitFloat(joints.id);
        shade *= 1.0f - 0.55f * crack;
        // A light rim beside each crack, as if the edge were chipped.
        shade *= 1.0f + 0.08f * crackMask * (smoothstep(0.04f, 0.09f, edge) - smoothstep(0.09f, 0.16f, edge));

        return scaleRgb(colour, shade * bedding);
    });
}

Image makeGrassAlbedo(int size, std::uint32_t seed)
{
    checkSize(size, "grass");
    const std::uint32_t s = hash(seed ^ 0x47525353U); // "GRSS"

    constexpr Rgb DARK_GREEN{38.0f, 56.0f, 30.0f};
    constexpr Rgb GREEN{58.0f, 80.0f, 40.0f};
    constexpr Rgb LIGHT_GREEN{82.0f, 102.0f, 50.0f};
    constexpr Rgb DRY{116.0f, 106.0f, 70.0f};
    constexpr Rgb SOIL{70.0f, 58.0f, 44.0f};

    return makeImage(size, [&](float u, float v) {
        // Broad variation of the lawn, then clumps: softer, smaller patches.
        const float broad = fbm(u, v, 3, 3, 3, 0.5f, s + 1U);
        Rgb colour = mixRgb(GREEN, LIGHT_GREEN, clamp01(0.5f + 0.9f * broad));
        const float clumps = fbm(u, v, 10, 10, 3, 0.6f, s + 2U);
        colour = mixRgb(colour, DARK_GREEN, smoothstep(0.0f, 0.5f, clumps) * 0.7f);
        colour = mixRgb(colour, LIGHT_GREEN, smoothstep(-0.1f, -0.5f, clumps) * 0.4f);

        // Dry patches, ragged at the edge.
        const float dryNoise = fbm(u, v, 2, 2, 5, 0.6f, s + 3U);
        const float dry = smoothstep(0.2f, 0.45f, dryNoise);
        colour = mixRgb(colour, DRY, 0.7f * dry);

        // Blades: fine grain plus short streaks along V, with dark gaps.
        const float grain = gradientNoise(u, v, 96, 96, s + 4U) + 0.6f * gradientNoise(u, v, 192, 192, s + 5U);
        const float streaks = gradientNoise(u, v, 160, 48, s + 6U);
        float shade = 1.0f + 0.22f * grain + 0.16f * streaks;
        shade *= 1.0f - 0.35f * smoothstep(0.25f, 0.75f, -grain);

        // A few spots of bare soil.
        const float wobble = 0.02f * fbm(u, v, 16, 16, 2, 0.5f, s + 10U);
        const Cells spots = cellular(u + wobble, v - wobble, 24, 24, s + 7U);
        const float spotMask = smoothstep(0.2f, 0.5f, fbm(u, v, 4, 4, 2, 0.5f, s + 8U) + 0.3f * dry);
        const float soil = (1.0f - smoothstep(0.08f, 0.3f, spots.f1)) * spotMask;
        colour = mixRgb(colour, SOIL, 0.6f * soil * (0.5f + unitFloat(spots.id)));

        return scaleRgb(colour, shade);
    });
}

} // namespace strata::render
