// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Noise and density far from the origin: finite and in range at 1e9 m (and
// at the octave frequencies that puts beyond 2^62 lattice cells), and a
// level set sampled at 1e9 m with no NaN or infinity in it.

#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Noise.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/TerrainField.h>
#include <strata/terrain/Transforms.h>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <vector>

namespace {

using namespace strata::terrain;

/// Points at ±1e9 m on every axis, on and off the lattice, and a few
/// farther out (1e12, 1e15) where the fraction of a cell is lost.
std::vector<glm::dvec3> farPoints()
{
    std::vector<glm::dvec3> points;
    for (const double x : {-1e9, 1e9}) {
        for (const double y : {-1e9, 0.0, 1e9}) {
            for (const double z : {-1e9, 1e9}) {
                points.emplace_back(x, y, z);
                points.emplace_back(x + 0.37, y - 0.61, z + 0.13);
            }
        }
    }
    points.emplace_back(1e12 + 0.5, 3.25, -1e12);
    points.emplace_back(-1e15, 1e15, 7.75);
    return points;
}

TEST(Extremes, BasisNoiseIsFiniteAndInRangeAt1e9)
{
    int evaluated = 0;
    for (const glm::dvec3& p : farPoints()) {
        for (const std::uint64_t seed : {0ull, 1ull, 0xffffffffffffffffull}) {
            const float g3 = gradientNoise(seed, p), g2 = gradientNoise(seed, glm::dvec2(p.x, p.z));
            const float s3 = simplexNoise(seed, p), s2 = simplexNoise(seed, glm::dvec2(p.x, p.z));
            const float v3 = valueNoise(seed, p), v2 = valueNoise(seed, glm::dvec2(p.x, p.z));
            for (const float n : {g3, g2, s3, s2, v3, v2}) {
                EXPECT_TRUE(std::isfinite(n)) << p.x << "," << p.y << "," << p.z;
                EXPECT_LE(std::abs(n), 1.5f) << p.x << "," << p.y << "," << p.z;
            }
            for (const CellularDistances c : {cellularNoise(seed, p), cellularNoise(seed, glm::dvec2(p.x, p.z))}) {
                EXPECT_TRUE(std::isfinite(c.f1) && std::isfinite(c.f2));
                EXPECT_GE(c.f1, 0.0);
                EXPECT_LE(c.f1, c.f2);
                EXPECT_LE(c.f2, 2.0); // within the 27-cell neighbourhood
            }
            evaluated += 8;
        }
    }
    std::cout << "[ extremes ] " << evaluated << " basis noise values at up to 1e15 m: all finite and in range"
              << std::endl;
}

// At 1e9 m the noise still varies on the scale of its cells (the 64-bit
// lattice and the double fraction keep it from going flat or blocky):
// neighbours a hundredth of a cell apart are close, points a cell apart are not
// all equal.
TEST(Extremes, NoiseStaysSmoothAndVariedAt1e9)
{
    const glm::dvec3 base(1e9 + 0.25, 0.5, -1e9 + 0.75);
    double largestStep = 0.0, spread = 0.0;
    float lo = 1e30f, hi = -1e30f;
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 p = base + glm::dvec3(1.37 * i, 0.0, 0.71 * i);
        const float a = gradientNoise(5, p), b = gradientNoise(5, p + glm::dvec3(0.01, 0.0, 0.0));
        largestStep = std::max(largestStep, double(std::abs(a - b)));
        lo = std::min(lo, a);
        hi = std::max(hi, a);
    }
    spread = double(hi - lo);
    std::cout << "[ extremes ] gradient noise at 1e9 m: range over 64 cells " << spread
              << ", largest change over 0.01 cell " << largestStep << std::endl;
    EXPECT_GT(spread, 0.5);
    EXPECT_LT(largestStep, 0.1);
}

// Noise version 2 splits the cell in double and does the rest in float:
// at 1e9 m (and past 2^32 cells, where the high word of the index steps)
// it is as smooth and as varied as at the origin, every basis.
TEST(Extremes, NoiseVersion2StaysSmoothAndVariedAt1e9)
{
    const NoiseType bases[] = {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                               NoiseType::CELLULAR_F2};
    for (const NoiseType basis : bases) {
        const FractalNoise noise(5, {basis, FractalType::FBM, 1, 2.0, 0.5, 2});
        for (const glm::dvec3& base : {glm::dvec3(0.25, 0.5, 0.75), glm::dvec3(1e9 + 0.25, 0.5, -1e9 + 0.75),
                                       glm::dvec3(6e9 + 0.25, -5e9, 0.75)}) {
            double largestStep = 0.0, lo = 1e30, hi = -1e30;
            for (int i = 0; i < 64; ++i) {
                const glm::dvec3 p = base + glm::dvec3(1.37 * i, 0.0, 0.71 * i);
                const double a = noise(p), b = noise(p + glm::dvec3(0.01, 0.0, 0.0));
                largestStep = std::max(largestStep, std::abs(a - b));
                lo = std::min(lo, a);
                hi = std::max(hi, a);
            }
            EXPECT_GT(hi - lo, 0.5) << "basis " << int(basis) << " at " << base.x;
            EXPECT_LE(largestStep, noise.lipschitz(3) * 0.01 + 1e-4) << "basis " << int(basis) << " at " << base.x;
        }
    }
}

TEST(Extremes, FractalSumsAreFiniteAt1e9WithEveryBasisAndTheLargestFrequencies)
{
    const NoiseType bases[] = {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                               NoiseType::CELLULAR_F2};
    const FractalType fractals[] = {FractalType::FBM, FractalType::RIDGED, FractalType::BILLOW};
    for (const int version : {1, 2})
    for (const NoiseType basis : bases) {
        for (const FractalType fractal : fractals) {
            // 24 octaves at lacunarity 8: the last octave's frequency times
            // 1e9 m is about 6e29 cells, beyond the 64-bit lattice.
            const FractalNoise noise(9, {basis, fractal, 24, 8.0, 0.5, version});
            for (const glm::dvec3& p : farPoints()) {
                const double n3 = noise(p), n2 = noise(glm::dvec2(p.x, p.z));
                EXPECT_TRUE(std::isfinite(n3) && std::isfinite(n2)) << int(basis) << " " << int(fractal);
                EXPECT_LE(std::abs(n3), 2.0);
                EXPECT_LE(std::abs(n2), 2.0);
                const Interval b = noise.bounds(p - 1.0, p + 1.0);
                EXPECT_TRUE(std::isfinite(b.lo) && std::isfinite(b.hi) && b.lo <= n3 && n3 <= b.hi);
            }
        }
    }
    const FbmOptions fbmOptions{24, 8.0, 0.5};
    const Fbm fbm(3, fbmOptions);
    for (const glm::dvec3& p : farPoints()) {
        EXPECT_TRUE(std::isfinite(fbm(p)) && std::isfinite(fbm(glm::dvec2(p.x, p.z))));
        EXPECT_TRUE(std::isfinite(strata::terrain::fbm(3, p, fbmOptions)));
    }
}

TEST(Extremes, TerrainDensityIsFiniteAt1e9)
{
    TerrainOptions options;
    options.seed = 11;
    const TerrainField terrain(options);
    for (const glm::dvec3& p : farPoints()) {
        const double d = terrain.density(p);
        EXPECT_TRUE(std::isfinite(d)) << p.x << "," << p.y << "," << p.z;
        EXPECT_TRUE(std::isfinite(terrain.height(p.x, p.z)));
        EXPECT_TRUE(std::isfinite(terrain.distanceBound(p)));
        const Interval b = terrain.bounds({p - 2.0, p + 2.0});
        EXPECT_TRUE(std::isfinite(b.lo) && std::isfinite(b.hi));
        EXPECT_LE(b.lo, d);
        EXPECT_GE(b.hi, d);
    }
}

// The default terrain sampled in a 32 m box 1e9 m out on x and z: a surface
// is there (heights stay near zero), and every value in the grid is finite.
TEST(Extremes, LevelSetSampledAt1e9HasNoNanOrInfinity)
{
    TerrainOptions options;
    options.seed = 11;
    const auto terrain = std::make_shared<TerrainField>(options);
    const auto warped = std::make_shared<WarpField>(terrain, 4, WarpOptions{});
    SampleOptions sampling;
    sampling.voxelSize = 1.0;
    sampling.region = {glm::dvec3(1e9 - 16.0, -40.0, -1e9 - 16.0), glm::dvec3(1e9 + 16.0, 40.0, -1e9 + 16.0)};
    for (const DensityField* field : {static_cast<const DensityField*>(terrain.get()),
                                      static_cast<const DensityField*>(warped.get())}) {
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(*field, sampling);
        std::size_t nonFinite = 0, negative = 0;
        for (auto it = grid->cbeginValueOn(); it; ++it) {
            if (!std::isfinite(*it)) ++nonFinite;
            if (*it < 0.0f) ++negative;
        }
        for (auto it = grid->cbeginValueAll(); it; ++it) {
            if (!std::isfinite(*it)) ++nonFinite;
        }
        std::cout << "[ extremes ] level set at x = 1e9, z = -1e9 m: " << grid->activeVoxelCount()
                  << " active voxels, " << nonFinite << " non-finite values" << std::endl;
        EXPECT_EQ(nonFinite, 0u);
        EXPECT_GT(grid->activeVoxelCount(), 1000u);
        EXPECT_GT(negative, 0u);
    }
}

} // namespace
