// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The roughness-vs-scale exponent on surfaces whose answers are known: a
// tilted plane (every residual zero: no exponent), a sine ridge (the
// residual at each window is the sine times 1 − the window's mean of cos,
// so σ is known exactly, and a smooth surface's exponent is about 2), white
// noise (σ hardly changes with the window: about 0), a grid narrower than
// the widest window, and bad input.

#include <strata/Error.h>
#include <strata/terrain/SurfaceRoughness.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::at;
using strata::test::errorOf;
using strata::test::tiltedPlane;

TEST(SurfaceRoughness, TiltedPlaneHasZeroResidualsAndNoExponent)
{
    constexpr int W = 40, H = 30;
    const std::vector<double> heights = tiltedPlane(W, H, 812.0, 0.4, -0.25);
    const SurfaceRoughness r = measureSurfaceRoughness(heights, W, H, 2.0);
    ASSERT_EQ(r.scales.size(), 4u);
    const int windows[] = {3, 5, 9, 17};
    for (std::size_t i = 0; i < 4; ++i) {
        EXPECT_EQ(r.scales[i].window, windows[i]);
        EXPECT_EQ(r.scales[i].length, 2.0 * windows[i]);
        EXPECT_EQ(r.scales[i].cells, std::size_t((W - windows[i] + 1) * (H - windows[i] + 1)));
        EXPECT_LT(r.scales[i].residualStd, 1e-9);
    }
    EXPECT_EQ(r.fit.points, 0u);
    EXPECT_TRUE(std::isnan(r.exponent));
}

TEST(SurfaceRoughness, SineRidgeHasItsExactSpreadAndAnExponentNearTwo)
{
    // z = A sin(kx): the window's mean is sin(kx)·S(w), S(w) = (1/w) Σ_d cos(kd)
    // for d in −w/2..w/2, so r = sin(kx)·(1 − S(w)) over the columns whose
    // window fits.
    constexpr int W = 120, H = 25;
    constexpr double A = 30.0, CELL = 3.0;
    const double k = 2.0 * std::numbers::pi / 200.0; // per cell: a wavelength of 200 cells, smooth at 3–17
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x) heights[at(W, x, z)] = A * std::sin(k * x);
    const SurfaceRoughness r = measureSurfaceRoughness(heights, W, H, CELL);
    for (const RoughnessAtScale& s : r.scales) {
        const int half = s.window / 2;
        double mean = 0.0;
        for (int d = -half; d <= half; ++d) mean += std::cos(k * d);
        const double factor = 1.0 - mean / s.window;
        double sum = 0.0, squares = 0.0;
        int n = 0;
        for (int x = half; x + half < W; ++x, ++n) sum += A * std::sin(k * x) * factor;
        const double m = sum / n;
        for (int x = half; x + half < W; ++x) squares += std::pow(A * std::sin(k * x) * factor - m, 2);
        EXPECT_NEAR(s.residualStd, std::sqrt(squares / n), 1e-9 * std::sqrt(squares / n)) << s.window;
    }
    EXPECT_EQ(r.fit.points, 4u);
    // σ ∝ w² − 1: the log–log slope is 2w²/(w² − 1), 2.25 at w = 3 to 2.007 at 17.
    EXPECT_GT(r.exponent, 1.95);
    EXPECT_LT(r.exponent, 2.15);
    EXPECT_GT(r.fit.rSquared, 0.99);
}

TEST(SurfaceRoughness, WhiteNoiseBarelyGrowsWithScale)
{
    constexpr int W = 200, H = 200;
    std::vector<double> heights(W * H);
    std::uint32_t state = 12345u;
    for (double& h : heights) {
        state = state * 1664525u + 1013904223u; // fixed LCG: the same heights everywhere
        h = double(state >> 8) / double(1u << 24) * 10.0;
    }
    // var(r) = σ²(1 − 1/w²): σ grows by √(1 − 1/289) / √(1 − 1/9) ≈ 1.06 from w = 3 to 17.
    const SurfaceRoughness r = measureSurfaceRoughness(heights, W, H, 1.0);
    EXPECT_GT(r.exponent, -0.05);
    EXPECT_LT(r.exponent, 0.1);
    const double sigma = 10.0 / std::sqrt(12.0);
    EXPECT_NEAR(r.scales[0].residualStd, sigma * std::sqrt(1.0 - 1.0 / 9.0), 0.03 * sigma);
}

TEST(SurfaceRoughness, WindowsWiderThanTheGridAreLeftOut)
{
    constexpr int W = 12, H = 7; // 3 and 5 fit, 9 and 17 do not
    std::vector<double> heights(W * H);
    for (int z = 0; z < H; ++z)
        for (int x = 0; x < W; ++x) heights[at(W, x, z)] = std::sin(0.9 * x) * std::cos(1.3 * z) * 5.0;
    const SurfaceRoughness r = measureSurfaceRoughness(heights, W, H, 1.0);
    EXPECT_EQ(r.scales[1].cells, std::size_t((W - 4) * (H - 4)));
    EXPECT_EQ(r.scales[2].cells, 0u);
    EXPECT_TRUE(std::isnan(r.scales[2].residualStd));
    EXPECT_TRUE(std::isnan(r.scales[3].residualStd));
    EXPECT_EQ(r.fit.points, 2u);
    EXPECT_TRUE(std::isfinite(r.exponent));

    SurfaceRoughnessOptions options;
    options.windows = {5, 9, 17};
    EXPECT_TRUE(std::isnan(measureSurfaceRoughness(heights, W, H, 1.0, options).exponent)); // one scale: no line
}

TEST(SurfaceRoughness, BadInputThrows)
{
    EXPECT_NE(errorOf([] { measureSurfaceRoughness(std::vector<double>(10, 0.0), 2, 5, 1.0); }).find("3 x 3"),
              std::string::npos);
    EXPECT_NE(errorOf([] { measureSurfaceRoughness(std::vector<double>(8, 0.0), 3, 3, 1.0); }).find("8 heights"),
              std::string::npos);
    std::vector<double> heights(20, 1.0);
    heights[at(5, 4, 1)] = INFINITY;
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, 1.0); }).find("(x 4, z 1)"), std::string::npos);
    heights[at(5, 4, 1)] = 1.0;
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, 0.0); }).find("cell size"), std::string::npos);
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, NAN); }).find("cell size"), std::string::npos);
    SurfaceRoughnessOptions options;
    options.windows = {3, 4};
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, 1.0, options); }).find("windows[1] = 4"),
              std::string::npos);
    options.windows = {5, 3};
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, 1.0, options); }).find("wider"), std::string::npos);
    options.windows = {};
    EXPECT_NE(errorOf([&] { measureSurfaceRoughness(heights, 5, 4, 1.0, options); }).find("windows"),
              std::string::npos);
}

} // namespace
