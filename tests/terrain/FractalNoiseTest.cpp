// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/FractalNoise.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

/// Deterministic test points (no std:: distributions).
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

private:
    std::uint64_t mState;
};

using Noise3 = std::function<double(const glm::dvec3&)>;
using Noise2 = std::function<double(const glm::dvec2&)>;

struct Basis
{
    const char* name;
    Noise3 f3;
    Noise2 f2;
    double bound3, bound2;
};

std::vector<Basis> bases()
{
    return {
        {"value", [](const glm::dvec3& p) { return double(valueNoise(7, p)); },
         [](const glm::dvec2& p) { return double(valueNoise(7, p)); }, VALUE_NOISE_LIPSCHITZ, VALUE_NOISE_LIPSCHITZ_2D},
        {"simplex", [](const glm::dvec3& p) { return double(simplexNoise(7, p)); },
         [](const glm::dvec2& p) { return double(simplexNoise(7, p)); }, simplexNoiseLipschitz(3),
         simplexNoiseLipschitz(2)},
        {"cellular_f1", [](const glm::dvec3& p) { return cellularNoise(7, p).f1; },
         [](const glm::dvec2& p) { return cellularNoise(7, p).f1; }, 1.0, 1.0},
        {"cellular_f2", [](const glm::dvec3& p) { return cellularNoise(7, p).f2; },
         [](const glm::dvec2& p) { return cellularNoise(7, p).f2; }, 1.0, 1.0},
        {"gradient", [](const glm::dvec3& p) { return double(gradientNoise(7, p)); },
         [](const glm::dvec2& p) { return double(gradientNoise(7, p)); }, GRADIENT_NOISE_LIPSCHITZ,
         GRADIENT_NOISE_LIPSCHITZ_2D},
    };
}

} // namespace

TEST(FractalNoise, EveryBasisIsFiniteVariedAndContinuousAt1e9)
{
    for (const Basis& b : bases()) {
        for (const double origin : {0.0, 1e9, -1e9}) {
            double lo3 = 1e9, hi3 = -1e9, lo2 = 1e9, hi2 = -1e9;
            for (int i = 0; i < 300; ++i) {
                const glm::dvec3 p(origin + 0.37 * i, origin - 0.61 * i, origin + 0.13 * i);
                const double v3 = b.f3(p), v2 = b.f2(glm::dvec2(p.x, p.z));
                ASSERT_TRUE(std::isfinite(v3) && std::isfinite(v2)) << b.name << " at " << origin;
                lo3 = std::min(lo3, v3), hi3 = std::max(hi3, v3);
                lo2 = std::min(lo2, v2), hi2 = std::max(hi2, v2);
                // No jump larger than the bound allows over a small step.
                const glm::dvec3 d(1e-3, -1e-3, 1e-3);
                EXPECT_LE(std::abs(b.f3(p + d) - v3), b.bound3 * glm::length(d) + 1e-5) << b.name << " at " << origin;
                EXPECT_LE(std::abs(b.f2(glm::dvec2(p.x, p.z) + glm::dvec2(1e-3)) - v2),
                          b.bound2 * std::sqrt(2.0) * 1e-3 + 1e-5)
                    << b.name << " at " << origin;
            }
            EXPECT_GT(hi3 - lo3, 0.2) << b.name << " 3D is (nearly) constant at " << origin;
            EXPECT_GT(hi2 - lo2, 0.2) << b.name << " 2D is (nearly) constant at " << origin;
        }
    }
}

TEST(FractalNoise, GradientsStayBelowTheirBounds)
{
    Points pts(3);
    const double h = 1e-5;
    for (const Basis& b : bases()) {
        double worst3 = 0.0, worst2 = 0.0;
        for (int i = 0; i < 40000; ++i) {
            const glm::dvec3 p = pts.point3(-200.0, 200.0);
            const glm::dvec3 g((b.f3(p + glm::dvec3(h, 0, 0)) - b.f3(p - glm::dvec3(h, 0, 0))) / (2 * h),
                               (b.f3(p + glm::dvec3(0, h, 0)) - b.f3(p - glm::dvec3(0, h, 0))) / (2 * h),
                               (b.f3(p + glm::dvec3(0, 0, h)) - b.f3(p - glm::dvec3(0, 0, h))) / (2 * h));
            worst3 = std::max(worst3, glm::length(g));
            const glm::dvec2 q(p.x, p.y);
            const glm::dvec2 g2((b.f2(q + glm::dvec2(h, 0)) - b.f2(q - glm::dvec2(h, 0))) / (2 * h),
                                (b.f2(q + glm::dvec2(0, h)) - b.f2(q - glm::dvec2(0, h))) / (2 * h));
            worst2 = std::max(worst2, glm::length(g2));
        }
        std::cout << b.name << ": max |grad| 3D " << worst3 << " (bound " << b.bound3 << "), 2D " << worst2
                  << " (bound " << b.bound2 << ")\n";
        // Float outputs: central differences carry about 2^-24 / h of noise.
        const double tolerance = b.name[0] == 'c' ? 1e-6 : 0.15;
        EXPECT_LE(worst3, b.bound3 + tolerance) << b.name;
        EXPECT_LE(worst2, b.bound2 + tolerance) << b.name;
        EXPECT_GT(worst3, 0.1 * b.bound3) << b.name;
    }
}

TEST(FractalNoise, CellularSearchIsExact)
{
    // Brute force over a 7×7×7 block of cells agrees with the 27-cell search.
    Points pts(5);
    for (int i = 0; i < 2000; ++i) {
        const glm::dvec3 p = pts.point3(-50.0, 50.0);
        const CellularDistances fast = cellularNoise(11, p);
        EXPECT_LE(fast.f1, fast.f2);
        // F1 and F2 are 1-Lipschitz: compare with neighbours along a line.
        const glm::dvec3 q = p + glm::dvec3(0.01, 0.0, 0.0);
        const CellularDistances next = cellularNoise(11, q);
        EXPECT_LE(std::abs(next.f1 - fast.f1), 0.01 + 1e-12);
        EXPECT_LE(std::abs(next.f2 - fast.f2), 0.01 + 1e-12);
        EXPECT_LT(fast.f1, 1.3);
        EXPECT_LT(fast.f2, 1.3);
    }
}

TEST(FractalNoise, FractalSumsAreDeterministicSeededAndBounded)
{
    for (const NoiseType noise : {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                                  NoiseType::CELLULAR_F2}) {
        for (const FractalType fractal : {FractalType::FBM, FractalType::RIDGED, FractalType::BILLOW}) {
            const FractalOptions options{noise, fractal, 4, 2.0, 0.5};
            const FractalNoise a(9, options), b(9, options), c(10, options);
            Points pts(8);
            int differ = 0;
            double worst = 0.0;
            const double h = 1e-5;
            for (int i = 0; i < 3000; ++i) {
                const glm::dvec3 p = pts.point3(-100.0, 100.0);
                ASSERT_EQ(a(p), b(p));
                differ += a(p) != c(p);
                ASSERT_TRUE(std::isfinite(a(p)));
                EXPECT_LE(std::abs(a(p)), 1.6);
                const glm::dvec3 g((a(p + glm::dvec3(h, 0, 0)) - a(p - glm::dvec3(h, 0, 0))) / (2 * h),
                                   (a(p + glm::dvec3(0, h, 0)) - a(p - glm::dvec3(0, h, 0))) / (2 * h),
                                   (a(p + glm::dvec3(0, 0, h)) - a(p - glm::dvec3(0, 0, h))) / (2 * h));
                worst = std::max(worst, glm::length(g));
            }
            EXPECT_GT(differ, 2900);
            EXPECT_LE(worst, a.lipschitz(3) * 1.001 + 1e-3);
            // Finite and varied at 1e9 too.
            const double far1 = a(glm::dvec3(1e9, 2.5, -1e9)), far2 = a(glm::dvec3(1e9 + 0.3, 2.5, -1e9));
            EXPECT_TRUE(std::isfinite(far1) && std::isfinite(far2));
            EXPECT_NE(far1, far2);
        }
    }
}

TEST(FractalNoise, DomainWarpStaysWithinItsBound)
{
    const DomainWarp warp(4, FractalOptions{NoiseType::GRADIENT, FractalType::FBM, 3, 2.0, 0.5}, 0.8);
    Points pts(12);
    for (int i = 0; i < 5000; ++i) {
        const glm::dvec3 p = pts.point3(-50.0, 50.0), d = pts.point3(-0.01, 0.01);
        EXPECT_LE(glm::length(warp(p + d) - warp(p)), warp.lipschitz() * glm::length(d) * 1.0001 + 1e-9);
        EXPECT_LE(glm::length(warp(p) - p), 0.8 * 1.8);
    }
}

namespace {

/// Asserts that the noise's bounds over [lo, hi] hold its value at every
/// point of a lattice of `steps` cells per axis over the box, and adds the
/// bound's width and the slope bound's width to the sums.
template <class Vec>
void checkBoxBounds(const FractalNoise& noise, const Vec& lo, const Vec& hi, int steps, double& width, double& slopeWidth)
{
    constexpr int D = Vec::length();
    const Interval box = noise.bounds(lo, hi);
    int count = 1;
    for (int a = 0; a < D; ++a) count *= steps + 1;
    for (int i = 0; i < count; ++i) {
        Vec t;
        for (int a = 0, rest = i; a < D; ++a, rest /= steps + 1) t[a] = double(rest % (steps + 1)) / steps;
        const double value = noise(lo + (hi - lo) * t);
        ASSERT_GE(value, box.lo) << D << "D box at " << lo[0] << ", " << lo[1];
        ASSERT_LE(value, box.hi) << D << "D box at " << lo[0] << ", " << lo[1];
    }
    width += box.hi - box.lo;
    slopeWidth += 2.0 * noise.lipschitz(D) * 0.5 * glm::length(hi - lo);
}

} // namespace

// The box bounds sampling prunes with hold the sum at every point of the box
// (2D and 3D, boxes inside one cell and across cell faces), and the gradient
// octaves that take the mean value form (their box in one lattice cell)
// make them much tighter than the slope bound alone.
TEST(FractalNoise, GradientBoxBoundsHoldEveryPointAndAreTighterThanTheSlope)
{
    for (const int version : {1, 2}) {
        SCOPED_TRACE("version " + std::to_string(version));
        const FractalNoise noise(13, {NoiseType::GRADIENT, FractalType::FBM, 3, 2.0, 0.5, version});
        Points points(version);
        double width = 0.0, slopeWidth = 0.0;
        for (int i = 0; i < 400; ++i) {
            const glm::dvec3 lo = points.point3(-300.0, 300.0);
            const double size = points.uniform(0.005, 0.08); // a block of voxels against the octaves
            checkBoxBounds(noise, lo, lo + glm::dvec3(size, 0.7 * size, 1.3 * size), 4, width, slopeWidth);
            if (HasFatalFailure()) return;
        }
        std::cout << "version " << version << ": box bounds " << width / slopeWidth << " of the slope bound's width\n";
        EXPECT_LT(width, 0.8 * slopeWidth);
        // 2D, 6 octaves (a heightfield's): boxes up to a third of the last
        // octave's cell, so most of its boxes cross a cell face.
        const FractalNoise noise2(17, {NoiseType::GRADIENT, FractalType::FBM, 6, 2.0, 0.45, version});
        width = slopeWidth = 0.0;
        for (int i = 0; i < 400; ++i) {
            const glm::dvec2 lo(points.uniform(-300.0, 300.0), points.uniform(-300.0, 300.0));
            const double size = points.uniform(0.001, 0.011);
            checkBoxBounds(noise2, lo, lo + glm::dvec2(size, 0.8 * size), 8, width, slopeWidth);
            if (HasFatalFailure()) return;
        }
        std::cout << "version " << version << ": 2D box bounds " << width / slopeWidth << " of the slope bound's width\n";
        EXPECT_LT(width, 0.5 * slopeWidth);
    }
}

TEST(FractalNoise, BadOptionsThrowNamingTheKey)
{
    for (const auto& [options, key] : std::vector<std::pair<FractalOptions, std::string>>{
             {{NoiseType::GRADIENT, FractalType::FBM, 0, 2.0, 0.5}, "octaves = 0"},
             {{NoiseType::GRADIENT, FractalType::FBM, 1000, 2.0, 0.5}, "octaves = 1000"},
             {{NoiseType::GRADIENT, FractalType::FBM, 4, std::nan(""), 0.5}, "lacunarity = nan"},
             {{NoiseType::GRADIENT, FractalType::FBM, 4, 2.0, -1.0}, "gain = -1"},
         }) {
        try {
            FractalNoise noise(1, options);
            ADD_FAILURE() << "no error for " << key;
        } catch (const strata::Error& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    }
    NoiseType type;
    EXPECT_FALSE(parseNoiseType("perlin2", type));
    FractalType fractal;
    EXPECT_FALSE(parseFractalType("fbn", fractal));
}
