#include <strata/terrain/Noise.h>

#include <algorithm>
#include <cassert>
#include <cmath>

#include "NoiseHash.h"

namespace strata::terrain {

namespace {

using namespace detail;

/// The 12 cube-edge directions of improved Perlin noise (length sqrt 2).
constexpr double GRAD3[12][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},
    {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},
};

inline double grad3(std::uint64_t h, double x, double y, double z)
{
    const double* g = GRAD3[pick(h, 12)];
    return g[0] * x + g[1] * y + g[2] * z;
}

/// 8 directions, 45 degrees apart, unit length.
constexpr double D = 0.70710678118654752440;
constexpr double GRAD2[8][2] = {
    {1, 0}, {-1, 0}, {0, 1}, {0, -1}, {D, D}, {-D, D}, {D, -D}, {-D, -D},
};

/// Unit gradients give 2D noise a range of about ±0.7; this brings it to
/// about ±1 like the 3D noise (whose gradients have length sqrt 2).
constexpr double NOISE2_SCALE = 1.41421356237309504880;

inline double grad2(std::uint64_t h, double x, double y)
{
    const double* g = GRAD2[pick(h, 8)];
    return g[0] * x + g[1] * y;
}

} // namespace

namespace detail {

/// 3D gradient noise from an already hashed seed.
double noise3(std::uint64_t s, const glm::dvec3& p)
{
    const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    // The fraction in double, from the unrounded floor: exact, and it keeps
    // its precision far from the origin.
    const double x = p.x - fx, y = p.y - fy, z = p.z - fz;
    const std::int64_t ix = latticeIndex(fx), iy = latticeIndex(fy), iz = latticeIndex(fz);

    // Hash the 8 corners hierarchically: 2 + 4 + 8 mixes instead of 8 * 3.
    const std::uint64_t hx0 = hashCombine(s, ix), hx1 = hashCombine(s, ix + 1);
    const std::uint64_t h00 = hashCombine(hx0, iy), h01 = hashCombine(hx0, iy + 1);
    const std::uint64_t h10 = hashCombine(hx1, iy), h11 = hashCombine(hx1, iy + 1);

    const double n000 = grad3(hashCombine(h00, iz), x, y, z);
    const double n001 = grad3(hashCombine(h00, iz + 1), x, y, z - 1.0);
    const double n010 = grad3(hashCombine(h01, iz), x, y - 1.0, z);
    const double n011 = grad3(hashCombine(h01, iz + 1), x, y - 1.0, z - 1.0);
    const double n100 = grad3(hashCombine(h10, iz), x - 1.0, y, z);
    const double n101 = grad3(hashCombine(h10, iz + 1), x - 1.0, y, z - 1.0);
    const double n110 = grad3(hashCombine(h11, iz), x - 1.0, y - 1.0, z);
    const double n111 = grad3(hashCombine(h11, iz + 1), x - 1.0, y - 1.0, z - 1.0);

    const double u = fade(x), v = fade(y), w = fade(z);
    const double n00 = lerp(n000, n001, w), n01 = lerp(n010, n011, w);
    const double n10 = lerp(n100, n101, w), n11 = lerp(n110, n111, w);
    return lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

/// 2D gradient noise from an already hashed seed.
double noise2(std::uint64_t s, const glm::dvec2& p)
{
    const double fx = std::floor(p.x), fy = std::floor(p.y);
    const double x = p.x - fx, y = p.y - fy;
    const std::int64_t ix = latticeIndex(fx), iy = latticeIndex(fy);

    const std::uint64_t hx0 = hashCombine(s, ix), hx1 = hashCombine(s, ix + 1);
    const double n00 = grad2(hashCombine(hx0, iy), x, y);
    const double n01 = grad2(hashCombine(hx0, iy + 1), x, y - 1.0);
    const double n10 = grad2(hashCombine(hx1, iy), x - 1.0, y);
    const double n11 = grad2(hashCombine(hx1, iy + 1), x - 1.0, y - 1.0);

    const double u = fade(x), v = fade(y);
    return NOISE2_SCALE * lerp(lerp(n00, n01, v), lerp(n10, n11, v), u);
}

} // namespace detail

std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream)
{
    return mix64(seedHash(seed) ^ mix64(stream + 0xd1b54a32d192ed03ULL));
}

float gradientNoise(std::uint64_t seed, const glm::dvec3& p)
{
    return float(noise3(seedHash(seed), p));
}

float gradientNoise(std::uint64_t seed, const glm::dvec2& p)
{
    return float(noise2(seedHash(seed), p));
}

Fbm::Fbm(std::uint64_t seed, const FbmOptions& options)
    : mOptions(options)
{
    assert(options.octaves >= 1 && options.octaves <= MAX_OCTAVES);
    mCount = std::clamp(options.octaves, 1, MAX_OCTAVES);
    double norm = 0.0, amplitude = 1.0, frequency = 1.0;
    for (int i = 0; i < mCount; ++i) {
        Octave& o = mOctaves[i];
        // Each octave gets its own seed and a random offset of its input,
        // so that the octaves are independent and do not all vanish on the
        // integer lattice (with lacunarity 2 every octave's lattice holds
        // the first one's).
        const std::uint64_t octaveSeed = deriveSeed(seed, std::uint64_t(i));
        o.hashedSeed = seedHash(octaveSeed);
        std::uint64_t h = octaveSeed;
        for (double& c : o.offset) {
            h = mix64(h + 0x9e3779b97f4a7c15ULL);
            c = double(h >> 11) * 0x1.0p-53; // [0, 1)
        }
        o.frequency = frequency;
        o.weight = amplitude;
        norm += amplitude;
        amplitude *= options.gain;
        frequency *= options.lacunarity;
    }
    for (int i = 0; i < mCount; ++i) mOctaves[i].weight /= norm;
}

float Fbm::operator()(const glm::dvec3& p) const
{
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        sum += o.weight * noise3(o.hashedSeed, p * o.frequency + glm::dvec3(o.offset[0], o.offset[1], o.offset[2]));
    }
    return float(sum);
}

float Fbm::operator()(const glm::dvec2& p) const
{
    double sum = 0.0;
    for (int i = 0; i < mCount; ++i) {
        const Octave& o = mOctaves[i];
        sum += o.weight * noise2(o.hashedSeed, p * o.frequency + glm::dvec2(o.offset[0], o.offset[1]));
    }
    return float(sum);
}

float fbm(std::uint64_t seed, const glm::dvec3& p, const FbmOptions& options)
{
    return Fbm(seed, options)(p);
}

float fbm(std::uint64_t seed, const glm::dvec2& p, const FbmOptions& options)
{
    return Fbm(seed, options)(p);
}

double fbmGradientBound(const FbmOptions& options, double noiseLipschitz)
{
    // Octave i is amplitude_i * noise(frequency_i * p): its gradient is at
    // most amplitude_i * frequency_i * noiseLipschitz.
    double bound = 0.0, norm = 0.0, amplitude = 1.0, frequency = 1.0;
    for (int i = 0; i < options.octaves; ++i) {
        bound += std::abs(amplitude) * frequency;
        norm += amplitude;
        amplitude *= options.gain;
        frequency *= options.lacunarity;
    }
    return norm > 0.0 ? noiseLipschitz * bound / norm : 0.0;
}

} // namespace strata::terrain
