// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/ProceduralTextures.h>

#include <strata/Error.h>
#include <strata/detail/IntegerHash.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

Rgb scaleRgb(const Rgb& a, float s)
{
    return {a.r * s, a.g * s, a.b * s};
}

float clamp01(float x)
{
    return std::clamp(x, 0.0f, 1.0f);
}

float smoothstep(float edge0, float edge1, float x)
{
    const float t = clamp01((x - edge0) / (edge1 - edge0));
    return t * t * (3.0f - 2.0f * t);
}

using strata::detail::lowbias32;

std::uint32_t hash(std::int32_t x, std::int32_t y, std::uint32_t seed)
{
    return lowbias32(std::uint32_t(x) ^ lowbias32(std::uint32_t(y) ^ lowbias32(seed)));
}

/// Uniform in [0, 1), 24 bits.
float unitFloat(std::uint32_t h)
{
    return float(h >> 8) * (1.0f / 16777216.0f);
}

int wrap(int i, int period)
{
    const int m = i % period;
    return m < 0 ? m + period : m;
}

float fade(float t)
{
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

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
        sum += amplitude * gradientNoise(u, v, periodX, periodY, lowbias32(seed + std::uint32_t(o) * 0x9e3779b9U));
        norm += amplitude;
        amplitude *= gain;
        periodX *= 2;
        periodY *= 2;
    }
    return sum / norm;
}

struct Cells
{
    float f1 = 0.0f;      ///< distance to the nearest feature point, in cells
    float f2 = 0.0f;      ///< distance to the second nearest
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
            const float py = float(cy) + 0.1f + 0.8f * unitFloat(lowbias32(h));
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
        throw Error(ErrorKind::BadInput, std::string(what) + " texture size must be a power of two in 16..16384, got " +
                    std::to_string(size));
    }
}

template <typename Shader> Image makeImage(int size, Shader&& shader)
{
    Image image;
    image.width = size;
    image.height = size;
    image.pixels.resize(std::size_t(size) * std::size_t(size) * 4);
    const float inv = 1.0f / float(size);
    // Rows in parallel: every pixel is a pure function of (u, v), so the
    // bytes do not depend on the thread count.
    tbb::parallel_for(0, size, [&](int y) {
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
    });
    return image;
}

} // namespace

Image makeRockAlbedo(int size, std::uint32_t seed)
{
    checkSize(size, "rock");
    const std::uint32_t s = lowbias32(seed ^ 0x524f434bU); // "ROCK"

    // Sediment layers from dark to light grey-brown (sRGB).
    constexpr Rgb PALETTE[] = {
        {78.0f, 72.0f, 67.0f},    {108.0f, 98.0f, 86.0f},  {128.0f, 117.0f, 101.0f}, {94.0f, 87.0f, 81.0f},
        {142.0f, 130.0f, 112.0f}, {113.0f, 101.0f, 88.0f}, {100.0f, 95.0f, 90.0f},   {134.0f, 121.0f, 104.0f},
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
    const std::uint32_t s = lowbias32(seed ^ 0x47525353U); // "GRSS"

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

namespace {

/// A float field over the texture, sampled at texel centres (rows top to bottom).
template <typename Field> std::vector<float> makeField(int size, Field&& field)
{
    std::vector<float> values(std::size_t(size) * std::size_t(size));
    const float inv = 1.0f / float(size);
    tbb::parallel_for(0, size, [&](int y) {
        for (int x = 0; x < size; ++x) {
            values[std::size_t(y) * std::size_t(size) + std::size_t(x)] =
                field((float(x) + 0.5f) * inv, 1.0f - (float(y) + 0.5f) * inv);
        }
    });
    return values;
}

/// Rescales to 0..1.
void normalise(std::vector<float>& values)
{
    float lo = values[0];
    float hi = values[0];
    for (float v : values) {
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    const float scale = hi > lo ? 1.0f / (hi - lo) : 0.0f;
    for (float& v : values) {
        v = (v - lo) * scale;
    }
}

std::vector<float> luminanceOf(const Image& image)
{
    std::vector<float> values(std::size_t(image.width) * std::size_t(image.height));
    for (std::size_t i = 0; i < values.size(); ++i) {
        const std::uint8_t* p = image.pixels.data() + i * 4;
        values[i] = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    }
    normalise(values);
    return values;
}

Image blankImage(int size)
{
    Image image;
    image.width = size;
    image.height = size;
    image.pixels.assign(std::size_t(size) * std::size_t(size) * 4, 255);
    return image;
}

/// Tangent-space normals (OpenGL +Y = texture up) of a periodic height field
/// whose full range 0..1 spans `bump` texels of relief.
Image normalsFromHeight(const std::vector<float>& h, int size, float bump)
{
    Image image = blankImage(size);
    auto at = [&](int x, int y) {
        return h[std::size_t(wrap(y, size)) * std::size_t(size) + std::size_t(wrap(x, size))];
    };
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            const float dhdu = 0.5f * (at(x + 1, y) - at(x - 1, y)) * bump;
            const float dhdv = 0.5f * (at(x, y - 1) - at(x, y + 1)) * bump; // row y − 1 is up (+V)
            const float nx = -dhdu;
            const float ny = -dhdv;
            const float inv = 1.0f / std::sqrt(nx * nx + ny * ny + 1.0f);
            std::uint8_t* p = image.at(x, y);
            p[0] = toByte((nx * inv * 0.5f + 0.5f) * 255.0f);
            p[1] = toByte((ny * inv * 0.5f + 0.5f) * 255.0f);
            p[2] = toByte((inv * 0.5f + 0.5f) * 255.0f);
            p[3] = 255;
        }
    }
    return image;
}

Image detailMap(int size, std::uint32_t s)
{
    Image image = blankImage(size);
    const float inv = 1.0f / float(size);
    tbb::parallel_for(0, size, [&](int y) {
        for (int x = 0; x < size; ++x) {
            const float u = (float(x) + 0.5f) * inv;
            const float v = 1.0f - (float(y) + 0.5f) * inv;
            const float a = fbm(u, v, 16, 16, 3, 0.55f, s + 21U);
            const float b = fbm(u, v, 24, 24, 2, 0.5f, s + 22U);
            std::uint8_t* p = image.at(x, y);
            p[0] = toByte((0.5f + 0.35f * a) * 255.0f);
            p[1] = 128;
            p[2] = toByte((0.5f + 0.3f * b) * 255.0f);
            p[3] = 255;
        }
    });
    return image;
}

/// MOHS from a height field: metallic, occlusion darkening the low parts,
/// the height, smoothness = base + slope·height.
Image mohsFromHeight(const std::vector<float>& h, int size, float metallic, float occlusionDepth, float smoothBase,
                     float smoothSlope)
{
    Image image = blankImage(size);
    for (std::size_t i = 0; i < h.size(); ++i) {
        std::uint8_t* p = image.pixels.data() + i * 4;
        p[0] = toByte(metallic * 255.0f);
        p[1] = toByte((1.0f - occlusionDepth * (1.0f - h[i]) * (1.0f - h[i])) * 255.0f);
        p[2] = toByte(h[i] * 255.0f);
        p[3] = toByte(clamp01(smoothBase + smoothSlope * h[i]) * 255.0f);
    }
    return image;
}

Image makeSoilLike(int size, std::uint32_t s, Rgb dark, Rgb light, float pebbles)
{
    return makeImage(size, [&](float u, float v) {
        const float broad = fbm(u, v, 4, 4, 4, 0.55f, s + 1U);
        Rgb colour = mixRgb(dark, light, clamp01(0.5f + 0.8f * broad));
        const float grain = gradientNoise(u, v, 128, 128, s + 2U) + 0.5f * gradientNoise(u, v, 256, 256, s + 3U);
        const Cells stones = cellular(u, v, 20, 20, s + 4U);
        const float stone = (1.0f - smoothstep(0.15f, 0.35f, stones.f1)) * pebbles *
                            smoothstep(0.0f, 0.4f, fbm(u, v, 3, 3, 2, 0.5f, s + 5U) + 0.2f);
        colour = mixRgb(colour, scaleRgb(light, 0.8f + 0.4f * unitFloat(stones.id)), 0.8f * stone);
        return scaleRgb(colour, 1.0f + 0.15f * grain);
    });
}

Image makeSnowAlbedo(int size, std::uint32_t s)
{
    return makeImage(size, [&](float u, float v) {
        const float broad = fbm(u, v, 3, 3, 4, 0.5f, s + 1U);
        const float sparkle = gradientNoise(u, v, 200, 200, s + 2U);
        Rgb colour = mixRgb(Rgb{214.0f, 222.0f, 236.0f}, Rgb{246.0f, 248.0f, 252.0f}, clamp01(0.5f + 0.8f * broad));
        return scaleRgb(colour, 1.0f + 0.03f * sparkle);
    });
}

struct Circuit
{
    float height = 0.25f; // board
    float metal = 0.0f;
    float light = 0.0f;
};

/// Golden traces and pads on a green board, on a 16×16 grid of cells.
Circuit circuitAt(float u, float v, std::uint32_t s)
{
    constexpr int CELLS = 16;
    const float x = u * float(CELLS);
    const float y = v * float(CELLS);
    const int cx = int(std::floor(x));
    const int cy = int(std::floor(y));
    const float fx = x - float(cx);
    const float fy = y - float(cy);
    const std::uint32_t h = hash(wrap(cx, CELLS), wrap(cy, CELLS), s);
    Circuit c;
    const float halfWidth = 0.09f + 0.06f * float((h >> 4) & 1U);
    const bool horizontal = (h & 3U) == 0U || (h & 3U) == 2U;
    const bool vertical = (h & 3U) == 1U || (h & 3U) == 2U;
    float trace = 0.0f;
    if (horizontal)
        trace = std::max(trace, 1.0f - smoothstep(halfWidth - 0.03f, halfWidth + 0.03f, std::abs(fy - 0.5f)));
    if (vertical) trace = std::max(trace, 1.0f - smoothstep(halfWidth - 0.03f, halfWidth + 0.03f, std::abs(fx - 0.5f)));
    const float dx = fx - 0.5f;
    const float dy = fy - 0.5f;
    const float r = std::sqrt(dx * dx + dy * dy);
    const bool pad = ((h >> 8) & 7U) == 0U;
    if (pad) {
        const float p = 1.0f - smoothstep(0.22f, 0.27f, r);
        trace = std::max(trace, p);
        if (((h >> 12) & 1U) == 0U) c.light = 1.0f - smoothstep(0.1f, 0.18f, r);
    }
    c.metal = trace;
    c.height = 0.25f + 0.65f * trace + 0.1f * (pad ? 1.0f - smoothstep(0.0f, 0.27f, r) : 0.0f);
    return c;
}

} // namespace

const char* builtinSetName(BuiltinSet set)
{
    switch (set) {
    case BuiltinSet::Rock:
        return "rock";
    case BuiltinSet::Grass:
        return "grass";
    case BuiltinSet::Soil:
        return "soil";
    case BuiltinSet::Sand:
        return "sand";
    case BuiltinSet::Snow:
        return "snow";
    case BuiltinSet::Circuitry:
        return "circuitry";
    }
    return "?";
}

std::optional<BuiltinSet> builtinSetFromName(const std::string& name)
{
    for (BuiltinSet set : {BuiltinSet::Rock, BuiltinSet::Grass, BuiltinSet::Soil, BuiltinSet::Sand, BuiltinSet::Snow,
                           BuiltinSet::Circuitry}) {
        if (name == builtinSetName(set)) return set;
    }
    return std::nullopt;
}

TextureSetImages makeBuiltinSet(BuiltinSet set, int size, std::uint32_t seed)
{
    checkSize(size, builtinSetName(set));
    const std::uint32_t s = lowbias32(seed ^ (0x5e7U + std::uint32_t(set) * 0x9e3779b9U));
    TextureSetImages maps;
    std::vector<float> height;
    float bump = 4.0f;
    switch (set) {
    case BuiltinSet::Rock:
        maps.albedo = makeRockAlbedo(size, seed);
        height = luminanceOf(maps.albedo);
        bump = 0.012f * float(size);
        maps.mohs = mohsFromHeight(height, size, 0.0f, 0.6f, 0.2f, 0.25f);
        break;
    case BuiltinSet::Grass:
        maps.albedo = makeGrassAlbedo(size, seed);
        height = luminanceOf(maps.albedo);
        bump = 0.006f * float(size);
        maps.mohs = mohsFromHeight(height, size, 0.0f, 0.5f, 0.1f, 0.2f);
        break;
    case BuiltinSet::Soil:
        maps.albedo = makeSoilLike(size, s, Rgb{62.0f, 48.0f, 36.0f}, Rgb{112.0f, 90.0f, 68.0f}, 1.0f);
        height = luminanceOf(maps.albedo);
        bump = 0.008f * float(size);
        maps.mohs = mohsFromHeight(height, size, 0.0f, 0.5f, 0.08f, 0.15f);
        break;
    case BuiltinSet::Sand:
        maps.albedo = makeSoilLike(size, s, Rgb{176.0f, 150.0f, 108.0f}, Rgb{214.0f, 192.0f, 146.0f}, 0.25f);
        height = makeField(size, [&](float u, float v) {
            // Ripples along U, wobbling.
            const float w = u + 0.04f * fbm(u, v, 3, 3, 2, 0.5f, s + 7U);
            const float r = 12.0f * (w + 0.15f * v);
            return 0.5f + 0.5f * std::abs(r - std::floor(r) - 0.5f) * 2.0f - 0.25f +
                   0.25f * fbm(u, v, 8, 8, 2, 0.5f, s + 8U);
        });
        normalise(height);
        bump = 0.005f * float(size);
        maps.mohs = mohsFromHeight(height, size, 0.0f, 0.3f, 0.15f, 0.1f);
        break;
    case BuiltinSet::Snow:
        maps.albedo = makeSnowAlbedo(size, s);
        height = makeField(size, [&](float u, float v) { return fbm(u, v, 4, 4, 4, 0.5f, s + 9U); });
        normalise(height);
        bump = 0.004f * float(size);
        maps.mohs = mohsFromHeight(height, size, 0.0f, 0.2f, 0.45f, 0.2f);
        break;
    case BuiltinSet::Circuitry: {
        maps.albedo = blankImage(size);
        maps.mohs = blankImage(size);
        maps.emission = blankImage(size);
        height.resize(std::size_t(size) * std::size_t(size));
        const float inv = 1.0f / float(size);
        for (int y = 0; y < size; ++y) {
            for (int x = 0; x < size; ++x) {
                const float u = (float(x) + 0.5f) * inv;
                const float v = 1.0f - (float(y) + 0.5f) * inv;
                const Circuit c = circuitAt(u, v, s);
                const float noise = fbm(u, v, 32, 32, 2, 0.5f, s + 11U);
                const Rgb board = scaleRgb(Rgb{28.0f, 92.0f, 52.0f}, 1.0f + 0.1f * noise);
                const Rgb gold{232.0f, 182.0f, 86.0f};
                const Rgb colour = mixRgb(board, gold, c.metal);
                std::uint8_t* p = maps.albedo.at(x, y);
                p[0] = toByte(colour.r);
                p[1] = toByte(colour.g);
                p[2] = toByte(colour.b);
                std::uint8_t* m = maps.mohs.at(x, y);
                m[0] = toByte(c.metal * 255.0f);
                m[1] = toByte((0.55f + 0.45f * c.height) * 255.0f);
                m[2] = toByte(c.height * 255.0f);
                m[3] = toByte((0.45f + 0.4f * c.metal) * 255.0f);
                std::uint8_t* e = maps.emission.at(x, y);
                e[0] = toByte(c.light * 40.0f);
                e[1] = toByte(c.light * 220.0f);
                e[2] = toByte(c.light * 255.0f);
                height[std::size_t(y) * std::size_t(size) + std::size_t(x)] = c.height;
            }
        }
        bump = 0.01f * float(size);
        break;
    }
    }
    maps.normal = normalsFromHeight(height, size, bump);
    maps.detail = detailMap(size, s);
    if (maps.emission.pixels.empty()) {
        maps.emission = blankImage(size);
        for (std::size_t i = 0; i < maps.emission.pixels.size(); i += 4) {
            maps.emission.pixels[i] = maps.emission.pixels[i + 1] = maps.emission.pixels[i + 2] = 0;
        }
    }
    return maps;
}

} // namespace strata::render
