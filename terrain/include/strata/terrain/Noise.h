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
    double gain = 0.5;        ///< amplitude ratio between octaves
};

/// fBm normalised by the sum of octave amplitudes, so its range stays about
/// [-1, 1] whatever the octave count. Each octave uses its own derived seed.
float fbm(std::uint64_t seed, const glm::dvec3& p, const FbmOptions& options);
float fbm(std::uint64_t seed, const glm::dvec2& p, const FbmOptions& options);

/// Upper bound of |∇ fbm| in noise units (per unit of p), used by sampling
/// to prune tiles far from the surface.
double fbmGradientBound(const FbmOptions& options);

/// Upper bound of |∇ gradientNoise| (3D and 2D) in noise units.
inline constexpr double GRADIENT_NOISE_LIPSCHITZ = 2.5;

} // namespace strata::terrain
