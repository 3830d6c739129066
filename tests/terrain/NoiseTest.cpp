// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Noise.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

using namespace strata::terrain;

namespace {

/// A tiny deterministic generator for test points (no std:: distributions).
class Points
{
public:
    explicit Points(std::uint64_t state) : mState(state) {}
    double uniform(double lo, double hi)
    {
        mState = mState * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * double(mState >> 11) * 0x1.0p-53;
    }
    glm::dvec3 point3(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
    glm::dvec2 point2(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi)}; }
    glm::dvec3 direction3()
    {
        for (;;) {
            const glm::dvec3 d = point3(-1.0, 1.0);
            const double l = glm::length(d);
            if (l > 0.1 && l <= 1.0) return d / l;
        }
    }

private:
    std::uint64_t mState;
};

/// Largest central-difference gradient magnitude of f over `count` random points.
template<typename F>
double maxGradient3(F f, int count, double spread, std::uint64_t state)
{
    Points pts(state);
    const double h = 1e-4;
    double worst = 0.0;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 p = pts.point3(-spread, spread);
        const glm::dvec3 g((f(p + glm::dvec3(h, 0, 0)) - f(p - glm::dvec3(h, 0, 0))) / (2 * h),
                           (f(p + glm::dvec3(0, h, 0)) - f(p - glm::dvec3(0, h, 0))) / (2 * h),
                           (f(p + glm::dvec3(0, 0, h)) - f(p - glm::dvec3(0, 0, h))) / (2 * h));
        worst = std::max(worst, glm::length(g));
    }
    return worst;
}

template<typename F>
double maxGradient2(F f, int count, double spread, std::uint64_t state)
{
    Points pts(state);
    const double h = 1e-4;
    double worst = 0.0;
    for (int i = 0; i < count; ++i) {
        const glm::dvec2 p = pts.point2(-spread, spread);
        const glm::dvec2 g((f(p + glm::dvec2(h, 0)) - f(p - glm::dvec2(h, 0))) / (2 * h),
                           (f(p + glm::dvec2(0, h)) - f(p - glm::dvec2(0, h))) / (2 * h));
        worst = std::max(worst, glm::length(g));
    }
    return worst;
}

// Central differences of float outputs carry rounding error of about
// 2^-24 / h; allow for it.
constexpr double FD_TOLERANCE = 2e-3;

} // namespace

TEST(Noise, SameSeedGivesIdenticalValues)
{
    Points pts(1);
    const FbmOptions options;
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 p = pts.point3(-1000.0, 1000.0);
        const glm::dvec2 q(p.x, p.z);
        EXPECT_EQ(gradientNoise(42, p), gradientNoise(42, p));
        EXPECT_EQ(gradientNoise(42, q), gradientNoise(42, q));
        EXPECT_EQ(fbm(42, p, options), fbm(42, p, options));
        EXPECT_EQ(fbm(42, q, options), fbm(42, q, options));
        // The prepared form gives the same bits as the free function.
        EXPECT_EQ(Fbm(42, options)(p), fbm(42, p, options));
        EXPECT_EQ(Fbm(42, options)(q), fbm(42, q, options));
    }
}

TEST(Noise, ValuesArePinned)
{
    // Values are part of the output format (the same seed must give the same
    // terrain everywhere): changing the noise must be a deliberate act.
    const FbmOptions options;
    EXPECT_EQ(gradientNoise(1, glm::dvec3(0.5, 0.25, 0.125)), -0x1.0d600cp-2f);
    EXPECT_EQ(gradientNoise(1, glm::dvec2(0.5, 0.25)), -0x1.ff11d6p-2f);
    EXPECT_EQ(fbm(7, glm::dvec3(12.3, -4.5, 6.7), options), -0x1.78ff82p-4f);
    EXPECT_EQ(fbm(7, glm::dvec2(12.3, -4.5), options), 0x1.4d7096p-2f);
}

TEST(Noise, OtherSeedGivesDifferentValues)
{
    Points pts(2);
    const FbmOptions options;
    int differ3 = 0, differ2 = 0, differFbm = 0;
    const int count = 1000;
    for (int i = 0; i < count; ++i) {
        const glm::dvec3 p = pts.point3(-1000.0, 1000.0);
        const glm::dvec2 q(p.x, p.y);
        differ3 += gradientNoise(1, p) != gradientNoise(2, p);
        differ2 += gradientNoise(1, q) != gradientNoise(2, q);
        differFbm += fbm(1, p, options) != fbm(2, p, options);
    }
    EXPECT_GT(differ3, count * 99 / 100);
    EXPECT_GT(differ2, count * 99 / 100);
    EXPECT_GT(differFbm, count * 99 / 100);
    EXPECT_NE(deriveSeed(1, 0), deriveSeed(1, 1));
    EXPECT_NE(deriveSeed(1, 0), deriveSeed(2, 0));
}

TEST(Noise, ZeroOnTheLatticeButNotFbm)
{
    EXPECT_EQ(gradientNoise(3, glm::dvec3(4.0, -7.0, 12.0)), 0.0f);
    EXPECT_EQ(gradientNoise(3, glm::dvec2(4.0, -7.0)), 0.0f);
    // Octave offsets keep fbm from vanishing on the integer lattice.
    EXPECT_NE(fbm(3, glm::dvec3(0.0), FbmOptions{}), 0.0f);
    EXPECT_NE(fbm(3, glm::dvec2(0.0), FbmOptions{}), 0.0f);
}

TEST(Noise, FiniteVariedAndContinuousFarFromTheOrigin)
{
    for (const double origin : {1e9, -1e9, 4.0e9}) {
        std::vector<float> values3, values2;
        for (int i = 0; i < 200; ++i) {
            const glm::dvec3 p(origin + 0.37 * i, origin - 0.61 * i, origin + 0.13 * i);
            const float v3 = gradientNoise(5, p);
            const float v2 = gradientNoise(5, glm::dvec2(p.x, p.z));
            ASSERT_TRUE(std::isfinite(v3) && std::isfinite(v2)) << "at " << origin;
            values3.push_back(v3);
            values2.push_back(v2);

            // Continuity: a small step changes the value by at most L·step.
            const double step = 1e-3;
            const glm::dvec3 d(step, -step, step);
            EXPECT_LE(std::abs(gradientNoise(5, p + d) - v3), GRADIENT_NOISE_LIPSCHITZ * glm::length(d) + 1e-6);
            EXPECT_LE(std::abs(gradientNoise(5, glm::dvec2(p.x, p.z) + glm::dvec2(step)) - v2),
                      GRADIENT_NOISE_LIPSCHITZ_2D * step * std::sqrt(2.0) + 1e-6);
        }
        const auto spread = [](const std::vector<float>& v) {
            const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
            return double(*hi - *lo);
        };
        EXPECT_GT(spread(values3), 0.3) << "3D noise is (nearly) constant at " << origin;
        EXPECT_GT(spread(values2), 0.3) << "2D noise is (nearly) constant at " << origin;
    }
    // Beyond the int64 lattice range the noise saturates instead of overflowing.
    EXPECT_TRUE(std::isfinite(gradientNoise(5, glm::dvec3(1e30, -1e30, 3.0))));
}

TEST(Noise, GradientStaysBelowTheBound)
{
    const auto noise3 = [](const glm::dvec3& p) { return double(gradientNoise(11, p)); };
    const auto noise2 = [](const glm::dvec2& p) { return double(gradientNoise(11, p)); };
    const double measured3 = maxGradient3(noise3, 200000, 1000.0, 3);
    const double measured2 = maxGradient2(noise2, 200000, 1000.0, 4);
    std::cout << "max |grad noise| measured: 3D " << measured3 << " (bound " << GRADIENT_NOISE_LIPSCHITZ
              << "), 2D " << measured2 << " (bound " << GRADIENT_NOISE_LIPSCHITZ_2D << ")\n";
    EXPECT_LE(measured3, GRADIENT_NOISE_LIPSCHITZ + FD_TOLERANCE);
    EXPECT_LE(measured2, GRADIENT_NOISE_LIPSCHITZ_2D + FD_TOLERANCE);
    // The bounds are not wildly loose either (random sampling gets within 25%).
    EXPECT_GT(measured3, 0.75 * GRADIENT_NOISE_LIPSCHITZ);
    EXPECT_GT(measured2, 0.75 * GRADIENT_NOISE_LIPSCHITZ_2D);
}

TEST(Noise, FbmGradientStaysBelowItsBound)
{
    for (const FbmOptions options : {FbmOptions{1, 2.0, 0.5}, FbmOptions{2, 2.0, 0.5}, FbmOptions{6, 2.0, 0.5},
                                     FbmOptions{4, 2.7, 0.35}}) {
        const Fbm f(9, options);
        const auto f3 = [&](const glm::dvec3& p) { return double(f(p)); };
        const auto f2 = [&](const glm::dvec2& p) { return double(f(p)); };
        const double bound3 = fbmGradientBound(options);
        const double bound2 = fbmGradientBound(options, GRADIENT_NOISE_LIPSCHITZ_2D);
        // Finer octaves amplify the float rounding of finite differences.
        const double tolerance = FD_TOLERANCE * std::pow(options.lacunarity, options.octaves - 1);
        EXPECT_LE(maxGradient3(f3, 20000, 500.0, 5), bound3 + tolerance) << options.octaves << " octaves";
        EXPECT_LE(maxGradient2(f2, 20000, 500.0, 6), bound2 + tolerance) << options.octaves << " octaves";
    }
    // The documented formula: sum of amplitude·frequency·L over sum of amplitudes.
    EXPECT_DOUBLE_EQ(fbmGradientBound(FbmOptions{1, 2.0, 0.5}), GRADIENT_NOISE_LIPSCHITZ);
    EXPECT_DOUBLE_EQ(fbmGradientBound(FbmOptions{2, 2.0, 0.5}), GRADIENT_NOISE_LIPSCHITZ * 2.0 / 1.5);
    EXPECT_DOUBLE_EQ(fbmGradientBound(FbmOptions{3, 3.0, 0.5}, 1.0), (1.0 + 1.5 + 2.25) / 1.75);
}

TEST(Noise, FbmRange)
{
    Points pts(7);
    for (const int octaves : {1, 3, 8}) {
        const Fbm f(13, FbmOptions{octaves, 2.0, 0.5});
        double lo3 = 0, hi3 = 0, lo2 = 0, hi2 = 0, sum3 = 0, sumSq3 = 0;
        const int count = 50000;
        for (int i = 0; i < count; ++i) {
            const glm::dvec3 p = pts.point3(-500.0, 500.0);
            const double v3 = f(p), v2 = f(glm::dvec2(p.x, p.y));
            lo3 = std::min(lo3, v3), hi3 = std::max(hi3, v3);
            lo2 = std::min(lo2, v2), hi2 = std::max(hi2, v2);
            sum3 += v3, sumSq3 += v3 * v3;
        }
        // The noise's supremum is 1.0364 in 3D (at a cell centre) and 1 in 2D;
        // fbm is a weighted mean of octaves, so it stays inside that too.
        EXPECT_GE(lo3, -1.0365);
        EXPECT_LE(hi3, 1.0365);
        EXPECT_GE(lo2, -1.0);
        EXPECT_LE(hi2, 1.0);
        // ... and it actually uses a good part of it, centred on zero.
        EXPECT_GT(hi3 - lo3, 0.8) << octaves;
        EXPECT_GT(hi2 - lo2, 0.8) << octaves;
        const double mean = sum3 / count, deviation = std::sqrt(sumSq3 / count - mean * mean);
        EXPECT_NEAR(mean, 0.0, 0.02) << octaves;
        EXPECT_GT(deviation, 0.1) << octaves;
        EXPECT_LT(deviation, 0.4) << octaves;
    }
}
