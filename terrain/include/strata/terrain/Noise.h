// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Deterministic gradient noise and fBm.
///
/// Lattice points are hashed from 64-bit integer coordinates and the seed
/// (no permutation table, no std:: distributions), so the same seed gives the
/// same value on every platform and thread count, and the pattern does not
/// repeat within the range of int64. Coordinates are in noise units (world
/// metres times a frequency); the lattice cell and the fraction inside it are
/// split in double precision so detail survives far from the origin.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>

namespace strata::terrain {

/// A new seed for an independent stream (a layer, an octave) derived from
/// `seed` by 64-bit hashing: deriveSeed(s, 0), deriveSeed(s, 1)... are
/// unrelated to each other and to s.
std::uint64_t deriveSeed(std::uint64_t seed, std::uint64_t stream);

/// 3D gradient (Perlin-style) noise, quintic fade. Range about [-1, 1],
/// zero at every lattice point, C2 continuous.
float gradientNoise(std::uint64_t seed, const glm::dvec3& p);

/// 2D gradient noise, as above.
float gradientNoise(std::uint64_t seed, const glm::dvec2& p);

/// Fractal sum of gradient noise octaves.
struct FbmOptions
{
    int octaves = 5;          ///< number of octaves, 1..24
    double lacunarity = 2.0;  ///< frequency ratio between octaves
    double gain = 0.5;        ///< amplitude ratio between octaves, >= 0
};

/// fBm normalised by the sum of octave amplitudes, so its range stays about
/// [-1, 1] whatever the octave count. Each octave uses its own derived seed
/// and a hashed offset of its input. options.octaves must be in 1..24.
float fbm(std::uint64_t seed, const glm::dvec3& p, const FbmOptions& options);
float fbm(std::uint64_t seed, const glm::dvec2& p, const FbmOptions& options);

/// fbm() with the per-octave seeds, offsets and weights computed once: the
/// same values, about twice as fast when evaluated many times. Immutable,
/// so one instance may be shared by threads.
class Fbm
{
public:
    static constexpr int MAX_OCTAVES = 24;

    /// options.octaves must be in 1..MAX_OCTAVES (asserted; clamped).
    Fbm(std::uint64_t seed, const FbmOptions& options);

    float operator()(const glm::dvec3& p) const;
    float operator()(const glm::dvec2& p) const;

    /// operator() at n points given as arrays, into out[0, n): the same
    /// bits, evaluated as a block (FractalNoise::evaluate's path).
    void evaluate(const double* x, const double* y, const double* z, std::size_t n, float* out) const;
    /// The 2D sum at (x[i], y[i]).
    void evaluate(const double* x, const double* y, std::size_t n, float* out) const;

    const FbmOptions& options() const { return mOptions; }

private:
    struct Octave
    {
        std::uint64_t hashedSeed;
        double frequency;
        double weight; ///< amplitude / sum of amplitudes
        double offset[3];
    };
    FbmOptions mOptions;
    int mCount = 0;
    Octave mOctaves[MAX_OCTAVES];
};

/// Upper bound of |∇ gradientNoise| (3D) in noise units. It is the exact
/// supremum: at a cell centre, when all 8 corner gradients line up, the
/// gradient is 8 · 30/16 · 1/4 = 3.75 (an exhaustive search over all gradient
/// assignments finds no larger value; checked numerically too).
inline constexpr double GRADIENT_NOISE_LIPSCHITZ = 3.75;

/// Upper bound of |∇ gradientNoise| (2D) in noise units (supremum 2.8323,
/// rounded up).
inline constexpr double GRADIENT_NOISE_LIPSCHITZ_2D = 2.84;

/// Upper bound of |∇ fbm| in noise units (per unit of p), used by sampling
/// to prune tiles far from the surface: the sum over octaves of
/// amplitude · frequency · noiseLipschitz, divided by the sum of amplitudes.
/// Pass GRADIENT_NOISE_LIPSCHITZ_2D for the 2D fbm.
double fbmGradientBound(const FbmOptions& options,
                        double noiseLipschitz = GRADIENT_NOISE_LIPSCHITZ);

} // namespace strata::terrain
