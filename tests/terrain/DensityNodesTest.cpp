// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/CacheMemory.h>
#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/DifferentialErosion.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/Transforms.h>

#include "WormCavesInspector.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

class Points
{
public:
    explicit Points(std::uint64_t state) : mState(state) {}
    double uniform(double lo, double hi)
    {
        mState = mState * 6364136223846793005ULL + 1442695040888963407ULL;
        return lo + (hi - lo) * double(mState >> 11) * 0x1.0p-53;
    }
    glm::dvec3 point3(const glm::dvec3& lo, const glm::dvec3& hi)
    {
        return {uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
    }

private:
    std::uint64_t mState;
};

std::shared_ptr<const NoiseHeightfield> hills(std::uint64_t seed = 1)
{
    return std::make_shared<NoiseHeightfield>(seed, NoiseHeightfieldOptions{});
}

/// Beds with every option that shapes them: dip, folds, a fault.
std::shared_ptr<const Lithology> foldedBeds()
{
    LithologyOptions o;
    o.beds = {{3.0, 0.9}, {4.0, 0.1}, {1.5, 0.6}};
    o.dip = 15.0;
    o.dipDirection = 120.0;
    o.foldAmplitude = 4.0;
    o.foldWavelength = 50.0;
    o.faultThrow = 3.0;
    o.faultStrike = 45.0;
    o.faultDip = 70.0;
    o.faultWidth = 2.0;
    return std::make_shared<Lithology>(6, o);
}

/// Every node of the library, each over ground it is meant for.
std::vector<std::pair<std::string, DensityFieldPtr>> allNodes()
{
    const DensityFieldPtr ground = hills();
    const DensityFieldPtr worms = std::make_shared<WormCaves>(3, WormOptions{});
    const DensityFieldPtr cheese = std::make_shared<CheeseCaves>(3, CheeseOptions{});
    const DensityFieldPtr spaghetti = std::make_shared<SpaghettiCaves>(3, SpaghettiOptions{});
    return {
        {"heightfield", ground},
        {"worms", worms},
        {"cheese", cheese},
        {"spaghetti", spaghetti},
        {"sphere", std::make_shared<SphereField>(glm::dvec3(1, 2, 3), 5.0)},
        {"box", std::make_shared<BoxField>(glm::dvec3(1, 2, 3), glm::dvec3(4, 5, 6), 1.0)},
        {"capsule", std::make_shared<CapsuleField>(glm::dvec3(-5, 0, 0), glm::dvec3(5, 3, 1), 2.0)},
        {"plane", std::make_shared<PlaneField>(glm::dvec3(0.2, 1, 0.1), 3.0)},
        {"union", std::make_shared<CsgField>(CsgOperation::UNION, std::vector<DensityFieldPtr>{ground, cheese})},
        {"smooth subtract",
         std::make_shared<CsgField>(CsgOperation::SUBTRACT, std::vector<DensityFieldPtr>{ground, worms, spaghetti}, 2.0)},
        {"smooth intersect",
         std::make_shared<CsgField>(CsgOperation::INTERSECT,
                                    std::vector<DensityFieldPtr>{ground, std::make_shared<SphereField>(glm::dvec3(0), 30.0)},
                                    3.0)},
        {"warp", std::make_shared<WarpField>(ground, 5, WarpOptions{})},
        {"terrace", std::make_shared<TerraceField>(ground, 4.0, 3.0)},
        {"translate", std::make_shared<TranslateField>(ground, glm::dvec3(1e6, 0, -1e6))},
        {"beds", std::make_shared<DifferentialErosionField>(
                     std::make_shared<WarpField>(ground, 5, WarpOptions{}), foldedBeds(), DifferentialErosionOptions{})},
    };
}

} // namespace

TEST(DensityNodes, PrimitivesAreExactDistances)
{
    const BoxField box(glm::dvec3(0), glm::dvec3(1, 2, 3));
    EXPECT_DOUBLE_EQ(box.density({3, 0, 0}), 2.0);
    EXPECT_DOUBLE_EQ(box.density({0, 0, 0}), -1.0);
    EXPECT_DOUBLE_EQ(box.density({2, 3, 0}), std::sqrt(2.0));
    const CapsuleField capsule(glm::dvec3(0, 0, 0), glm::dvec3(0, 10, 0), 2.0);
    EXPECT_DOUBLE_EQ(capsule.density({5, 5, 0}), 3.0);
    EXPECT_DOUBLE_EQ(capsule.density({0, 14, 0}), 2.0);
    const PlaneField plane(glm::dvec3(0, 2, 0), 3.0);
    EXPECT_DOUBLE_EQ(plane.density({7, 5, -1}), 2.0);
    // A round cone with equal radii is a capsule.
    EXPECT_NEAR(roundConeDistance({5, 5, 0}, {0, 0, 0}, {0, 10, 0}, 2.0, 2.0), 3.0, 1e-12);
    // Growing radius: exact against a dense minimum over the segment.
    Points pts(2);
    for (int i = 0; i < 500; ++i) {
        const glm::dvec3 p = pts.point3(glm::dvec3(-10), glm::dvec3(10));
        double best = 1e9;
        for (int k = 0; k <= 20000; ++k) {
            const double t = k / 20000.0;
            best = std::min(best, glm::length(p - glm::dvec3(0, 10 * t, 0)) - (1.0 + 2.0 * t));
        }
        EXPECT_NEAR(roundConeDistance(p, {0, 0, 0}, {0, 10, 0}, 1.0, 3.0), best, 1e-5);
    }
}

TEST(DensityNodes, CsgCombinesSigns)
{
    const auto a = std::make_shared<SphereField>(glm::dvec3(-2, 0, 0), 3.0);
    const auto b = std::make_shared<SphereField>(glm::dvec3(2, 0, 0), 3.0);
    const CsgField both(CsgOperation::UNION, {a, b});
    const CsgField cut(CsgOperation::SUBTRACT, {a, b});
    const CsgField common(CsgOperation::INTERSECT, {a, b});
    EXPECT_LT(both.density({-4, 0, 0}), 0.0);
    EXPECT_LT(both.density({4, 0, 0}), 0.0);
    EXPECT_LT(cut.density({-4, 0, 0}), 0.0);
    EXPECT_GT(cut.density({0, 0, 0}), 0.0);
    EXPECT_LT(common.density({0, 0, 0}), 0.0);
    EXPECT_GT(common.density({-4, 0, 0}), 0.0);
    // Smooth variants differ from the sharp ones by at most k/4, and fill the crease.
    const CsgField smooth(CsgOperation::UNION, {a, b}, 2.0);
    Points pts(4);
    for (int i = 0; i < 1000; ++i) {
        const glm::dvec3 p = pts.point3(glm::dvec3(-8), glm::dvec3(8));
        EXPECT_LE(smooth.density(p), both.density(p) + 1e-12);
        EXPECT_GE(smooth.density(p), both.density(p) - 0.5 - 1e-12);
    }
    EXPECT_LT(smooth.density({0, 2.3, 0}), both.density({0, 2.3, 0}));
}

TEST(DensityNodes, NoJumpLargerThanTheGradientBoundAllows)
{
    for (const auto& [name, field] : allNodes()) {
        Points pts(7);
        const double L = field->lipschitz();
        for (int i = 0; i < 3000; ++i) {
            const glm::dvec3 p = pts.point3(glm::dvec3(-90, -40, -90), glm::dvec3(90, 40, 90));
            for (const double step : {0.5, 0.05}) {
                const glm::dvec3 q = p + step * glm::normalize(pts.point3(glm::dvec3(-1), glm::dvec3(1)) + 1e-9);
                const double jump = std::abs(field->density(q) - field->density(p));
                ASSERT_LE(jump, L * glm::length(q - p) * (1.0 + 1e-6) + 1e-9)
                    << name << " at " << p.x << ", " << p.y << ", " << p.z;
            }
        }
    }
}

TEST(DensityNodes, DistanceBoundsAreConservativeAndSigned)
{
    // No sign change within |bound(p)| of p (checked along random rays).
    for (const auto& [name, field] : allNodes()) {
        Points pts(9);
        int tested = 0;
        for (int i = 0; i < 1500; ++i) {
            const glm::dvec3 p = pts.point3(glm::dvec3(-90, -40, -90), glm::dvec3(90, 40, 90));
            const double b = field->distanceBound(p), d = field->density(p);
            if (b != 0.0) {
                ASSERT_EQ(b < 0.0, d < 0.0) << name;
            }
            if (std::abs(b) < 0.05) continue;
            ++tested;
            const glm::dvec3 dir = glm::normalize(pts.point3(glm::dvec3(-1), glm::dvec3(1)) + 1e-9);
            for (int k = 1; k <= 20; ++k) {
                const glm::dvec3 q = p + dir * (0.999 * std::abs(b) * k / 20.0);
                ASSERT_EQ(field->density(q) < 0.0, d < 0.0) << name << ": sign changes inside the bound";
            }
        }
        EXPECT_GT(tested, 100) << name;
    }
}

TEST(DensityNodes, EachCaveKindMakesAirPocketsInsideRock)
{
    const DensityFieldPtr ground = std::make_shared<PlaneField>(glm::dvec3(0, 1, 0), 40.0); // rock below y = 40
    for (const auto& [name, cave] : std::vector<std::pair<std::string, DensityFieldPtr>>{
             {"worms", std::make_shared<WormCaves>(5, WormOptions{})},
             {"cheese", std::make_shared<CheeseCaves>(5, CheeseOptions{})},
             {"spaghetti", std::make_shared<SpaghettiCaves>(5, SpaghettiOptions{})},
         }) {
        const CsgField rock(CsgOperation::SUBTRACT, {ground, cave});
        int air = 0, total = 0;
        for (double x = -96; x <= 96; x += 3)
            for (double y = -30; y <= 10; y += 3)
                for (double z = -96; z <= 96; z += 3) {
                    ++total;
                    air += rock.density({x, y, z}) > 0.0;
                }
        std::cout << name << ": " << 100.0 * air / total << "% of the rock is air\n";
        EXPECT_GT(air, total / 200) << name << " carves (almost) nothing";
        EXPECT_LT(air, total / 2) << name << " carves most of the rock";
    }
}

TEST(DensityNodes, WormsAreTheSameOnAnyThreadAndFromAnyBucketOrder)
{
    const WormCaves a(8, WormOptions{}), b(8, WormOptions{});
    Points pts(1);
    std::vector<glm::dvec3> points;
    for (int i = 0; i < 2000; ++i) points.push_back(pts.point3(glm::dvec3(-150, -40, -150), glm::dvec3(150, 20, 150)));
    for (std::size_t i = 0; i < points.size(); ++i) {
        const double forward = a.density(points[i]);
        const double backward = b.density(points[points.size() - 1 - i]);
        EXPECT_EQ(forward, b.density(points[i]));
        EXPECT_EQ(backward, a.density(points[points.size() - 1 - i]));
    }
    // Far from the origin too.
    const WormOptions o;
    const auto segments = detail::WormCavesInspector::wormsOfCell(a, 15625000, -15625000); // cells at 1e9 m
    for (const auto& s : segments) EXPECT_TRUE(std::isfinite(s.a.x) && std::isfinite(s.b.z));
}

TEST(DensityNodes, ImageHeightfieldInterpolatesTheImage)
{
    HeightImage ramp;
    ramp.width = 256;
    ramp.height = 4;
    for (int z = 0; z < ramp.height; ++z)
        for (int x = 0; x < ramp.width; ++x) ramp.values.push_back(float(x) / 255.0f);
    ImageHeightfieldOptions o;
    o.min = {0.0, 0.0};
    o.max = {255.0, 30.0};
    o.heightScale = 51.0;
    o.base = -10.0;
    const ImageHeightfield field(ramp, o);
    for (double x = 0.0; x <= 255.0; x += 0.37) EXPECT_NEAR(field.height(x, 12.0), -10.0 + 51.0 * x / 255.0, 1e-5);
    EXPECT_NEAR(field.height(-50.0, 0.0), -10.0, 1e-9); // clamped at the edges
    EXPECT_NEAR(field.slopeBound(), 51.0 / 255.0, 1e-4);
    EXPECT_THROW(ImageHeightfield(HeightImage{1, 1, {0.5f}}, o), strata::Error);
}

TEST(DensityNodes, BadOptionsThrowNamingTheKey)
{
    const auto expectError = [](const std::function<void()>& make, const std::string& key) {
        try {
            make();
            ADD_FAILURE() << "no strata::Error for " << key;
        } catch (const strata::Error& e) {
            EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
        }
    };
    expectError([] { NoiseHeightfield(1, NoiseHeightfieldOptions{0.0, -1.0}); }, "amplitude = -1");
    expectError([] { NoiseHeightfield(1, NoiseHeightfieldOptions{0.0, 1.0, std::nan("")}); }, "wavelength = nan");
    expectError([] {
        NoiseHeightfieldOptions o;
        o.noise.octaves = 99;
        NoiseHeightfield(1, o);
    }, "octaves = 99");
    expectError([] {
        WormOptions o;
        o.radius = -2.0;
        WormCaves(1, o);
    }, "radius = -2");
    expectError([] {
        CheeseOptions o;
        o.wavelength = INFINITY;
        CheeseCaves(1, o);
    }, "wavelength = inf");
    expectError([] { TerraceField(hills(), -1.0, 2.0); }, "step = -1");
    expectError([] {
        WarpOptions o;
        o.amplitude = -3.0;
        WarpField(hills(), 1, o);
    }, "amplitude = -3");
}

namespace {

/// The default scene's tree: terraced fBm hills warped sideways, minus worms.
DensityFieldPtr terracedSceneTree()
{
    const DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(1, NoiseHeightfieldOptions{});
    const DensityFieldPtr steps = std::make_shared<TerraceField>(hills, 7.0, 4.0);
    WarpOptions warp;
    warp.amplitude = 4.0;
    warp.wavelength = 20.0;
    warp.vertical = 0.0;
    warp.noise.octaves = 1;
    const DensityFieldPtr land = std::make_shared<WarpField>(steps, 2, warp);
    WormOptions worms;
    worms.wormsPerCell = 3.0;
    worms.minY = -24.0;
    worms.maxY = 8.0;
    worms.radius = 3.2;
    return std::make_shared<CsgField>(CsgOperation::SUBTRACT,
                                      std::vector<DensityFieldPtr>{land, std::make_shared<WormCaves>(3, worms)});
}

DensityFieldPtr heightfieldOf(NoiseType noise, FractalType fractal)
{
    NoiseHeightfieldOptions o;
    o.noise = FractalOptions{noise, fractal, 4, 2.0, 0.5};
    o.amplitude = 30.0;
    return std::make_shared<NoiseHeightfield>(11, o);
}

/// Every node of allNodes() and more: the default scene's tree, smooth union,
/// heightfields over every basis and shape, an image heightfield.
std::vector<std::pair<std::string, DensityFieldPtr>> boundedNodes()
{
    auto nodes = allNodes();
    nodes.emplace_back("default scene tree", terracedSceneTree());
    nodes.emplace_back("smooth union",
                       std::make_shared<CsgField>(CsgOperation::UNION,
                                                  std::vector<DensityFieldPtr>{
                                                      hills(), std::make_shared<SphereField>(glm::dvec3(0), 20.0),
                                                      std::make_shared<CapsuleField>(glm::dvec3(-30, 0, 0),
                                                                                     glm::dvec3(30, 5, 0), 4.0)},
                                                  2.5));
    nodes.emplace_back("ridged value heightfield", heightfieldOf(NoiseType::VALUE, FractalType::RIDGED));
    nodes.emplace_back("billow cellular_f1 heightfield", heightfieldOf(NoiseType::CELLULAR_F1, FractalType::BILLOW));
    nodes.emplace_back("ridged gradient heightfield", heightfieldOf(NoiseType::GRADIENT, FractalType::RIDGED));
    nodes.emplace_back("simplex heightfield", heightfieldOf(NoiseType::SIMPLEX, FractalType::FBM));
    nodes.emplace_back("cellular_f2 heightfield", heightfieldOf(NoiseType::CELLULAR_F2, FractalType::FBM));
    HeightImage image;
    image.width = 64;
    image.height = 48;
    Points values(21);
    for (int i = 0; i < image.width * image.height; ++i) image.values.push_back(float(values.uniform(0.0, 1.0)));
    ImageHeightfieldOptions imageOptions;
    imageOptions.min = {-90.0, -80.0};
    imageOptions.max = {90.0, 70.0};
    imageOptions.heightScale = -12.0; // a negative scale flips the interval
    nodes.emplace_back("image heightfield", std::make_shared<ImageHeightfield>(image, imageOptions));
    WarpOptions lifted;
    lifted.vertical = 1.5;
    lifted.noise = FractalOptions{NoiseType::VALUE, FractalType::BILLOW, 3, 2.0, 0.5};
    nodes.emplace_back("vertical billow warp", std::make_shared<WarpField>(terracedSceneTree(), 9, lifted));
    return nodes;
}

} // namespace

TEST(DensityNodes, IntervalBoundsHoldEveryDensityInTheBox)
{
    // Random boxes from 5 mm to 64 m a side (each axis on its own), near the
    // origin and around (1e6, 0, −1e6); every corner, the centre and random
    // points inside must lie within the interval.
    for (const auto& [name, field] : boundedNodes()) {
        for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1e6, 0.0, -1e6)}) {
            Points pts(31);
            for (int i = 0; i < 250; ++i) {
                const glm::dvec3 c = origin + pts.point3(glm::dvec3(-90, -40, -90), glm::dvec3(90, 40, 90));
                glm::dvec3 half;
                for (int a = 0; a < 3; ++a) half[a] = 0.5 * std::exp(pts.uniform(std::log(0.005), std::log(64.0)));
                const WorldBox box{c - half, c + half};
                const Interval bound = field->bounds(box);
                ASSERT_LE(bound.lo, bound.hi) << name;
                ASSERT_TRUE(std::isfinite(bound.hi)) << name;
                for (int k = 0; k < 30; ++k) {
                    glm::dvec3 p = k < 8 ? glm::dvec3((k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y,
                                                      (k & 4) ? box.max.z : box.min.z)
                                         : (k == 8 ? c : pts.point3(box.min, box.max));
                    const double d = field->density(p);
                    const double tolerance = 1e-9 * (1.0 + std::abs(d));
                    ASSERT_GE(d, bound.lo - tolerance) << name << ": box centre " << c.x << ", " << c.y << ", " << c.z
                                                       << ", half size " << half.x << ", " << half.y << ", " << half.z;
                    ASSERT_LE(d, bound.hi + tolerance) << name << ": box centre " << c.x << ", " << c.y << ", " << c.z
                                                       << ", half size " << half.x << ", " << half.y << ", " << half.z;
                }
            }
        }
    }
}

TEST(DensityNodes, IntervalBoundsOfTheDefaultTreeAreTighterThanTheGradientBound)
{
    // The overrides must pay off where sampling uses them: 2³- and 4³-voxel
    // blocks (0.5 m voxels) near the ground. The default bound is
    // density(c) ± L·r; the tree's own interval should be several times narrower.
    const DensityFieldPtr tree = terracedSceneTree();
    for (const double size : {0.5, 1.5}) {
        Points pts(5);
        double own = 0.0, lipschitz = 0.0;
        for (int i = 0; i < 2000; ++i) {
            const glm::dvec3 c = pts.point3(glm::dvec3(-90, -12, -90), glm::dvec3(90, 12, 90));
            const WorldBox box{c - 0.5 * size, c + 0.5 * size};
            const Interval b = tree->bounds(box);
            own += b.hi - b.lo;
            lipschitz += 2.0 * tree->lipschitz() * box.radius();
        }
        std::cout << size << " m blocks: mean interval width " << own / 2000 << " (gradient bound "
                  << lipschitz / 2000 << ")\n";
        EXPECT_LT(own, 0.25 * lipschitz) << size;
    }
}

TEST(DensityNodes, FractalBoundsHoldForEveryBasisAndShape)
{
    for (const NoiseType noise : {NoiseType::GRADIENT, NoiseType::SIMPLEX, NoiseType::VALUE, NoiseType::CELLULAR_F1,
                                  NoiseType::CELLULAR_F2}) {
        for (const FractalType fractal : {FractalType::FBM, FractalType::RIDGED, FractalType::BILLOW}) {
            const FractalNoise f(4, FractalOptions{noise, fractal, 3, 2.0, 0.5});
            Points pts(3);
            for (int i = 0; i < 300; ++i) {
                const glm::dvec3 c = pts.point3(glm::dvec3(-1e6), glm::dvec3(1e6));
                glm::dvec3 half;
                for (int a = 0; a < 3; ++a) half[a] = std::exp(pts.uniform(std::log(1e-3), std::log(4.0)));
                const Interval b3 = f.bounds(c - half, c + half);
                const glm::dvec2 c2(c.x, c.z), half2(half.x, half.z);
                const Interval b2 = f.bounds(c2 - half2, c2 + half2);
                for (int k = 0; k < 20; ++k) {
                    const glm::dvec3 p = pts.point3(c - half, c + half);
                    ASSERT_GE(f(p), b3.lo) << int(noise) << " " << int(fractal);
                    ASSERT_LE(f(p), b3.hi) << int(noise) << " " << int(fractal);
                    const glm::dvec2 q(p.x, p.z);
                    ASSERT_GE(f(q), b2.lo) << int(noise) << " " << int(fractal) << " 2D";
                    ASSERT_LE(f(q), b2.hi) << int(noise) << " " << int(fractal) << " 2D";
                }
            }
            // Far from every sample, the range alone still bounds the sum.
            const Interval wide = f.bounds(glm::dvec3(-1e9), glm::dvec3(1e9));
            if (noise == NoiseType::VALUE) {
                EXPECT_GE(wide.lo, -1.0 - 1e-5);
                EXPECT_LE(wide.hi, 1.0 + 1e-5);
            }
        }
    }
}

TEST(DensityNodes, WormCacheStaysBoundedAndEvictionChangesNothing)
{
    WormOptions o;
    o.wormsPerCell = 2.0;
    // The process-wide cache limit (--max-memory) bounds the worm caches
    // too: under a 1 MiB limit they evict constantly.
    const std::uint64_t before = strata::cacheMemoryLimit();
    strata::setCacheMemoryLimit(std::uint64_t(1) << 20);
    const WormCaves streamed(12, o), fresh(12, o);
    // A 96 × 96 grid of 8 m buckets at tunnel depth (144 regions), walked twice.
    std::vector<double> first;
    for (int pass = 0; pass < 2; ++pass) {
        std::size_t n = 0;
        for (int i = 0; i < 96; ++i)
            for (int k = 0; k < 96; ++k) {
                const glm::dvec3 p(8.0 * i + 3.1 - 380.0, -10.0 + 0.37 * (i % 7), 8.0 * k + 5.3 - 380.0);
                const double d = streamed.density(p);
                if (pass == 0) first.push_back(d);
                else ASSERT_EQ(d, first[n]) << "after eviction";
                ++n;
            }
        // The limit, give or take the one entry per shard a cache keeps.
        EXPECT_LE(streamed.cacheBytes(), (std::uint64_t(1) << 20) + (std::uint64_t(1) << 20));
        EXPECT_GT(streamed.cacheBytes(), 0u);
    }
    strata::setCacheMemoryLimit(before);
    // A fresh instance, walked backwards (a different cache history), agrees.
    std::size_t n = first.size();
    for (int i = 95; i >= 0; --i)
        for (int k = 95; k >= 0; --k) {
            const glm::dvec3 p(8.0 * i + 3.1 - 380.0, -10.0 + 0.37 * (i % 7), 8.0 * k + 5.3 - 380.0);
            ASSERT_EQ(fresh.density(p), first[--n]);
        }
    int inside = 0;
    for (const double d : first) inside += d < 0.0;
    EXPECT_GT(inside, 0) << "the walk should cross some tunnels";
}
