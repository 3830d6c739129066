// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The height graph's nodes: their values, and the promises every height
// node makes to the sampler (slope bound, interval bounds, block heights
// with the same bits).

#include <strata/Error.h>
#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/NodeRegistry.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

HeightNodePtr hills(std::uint64_t seed = 1, double amplitude = 40.0)
{
    NoiseHeightfieldOptions o;
    o.amplitude = amplitude;
    o.wavelength = 120.0;
    return std::make_shared<NoiseHeightfield>(seed, o);
}

HeightNodePtr constant(double v) { return std::make_shared<ConstantHeight>(v); }

/// A deterministic sequence in [lo, hi) (no <random> distributions).
class Points
{
public:
    double next(double lo, double hi)
    {
        mState = mState * 6364136223846793005ull + 1442695040888963407ull;
        return lo + (hi - lo) * double(mState >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t mState = 12345;
};

/// Checks the slope bound on close pairs, heightBounds on random
/// rectangles, and heights() against height() bit for bit.
void checkPromises(const HeightfieldBase& node, const std::string& name, double centre = 0.0)
{
    Points rng;
    double worstRatio = 0.0;
    for (int i = 0; i < 2000; ++i) {
        const double x = centre + rng.next(-500.0, 500.0), z = centre + rng.next(-500.0, 500.0);
        const double dx = rng.next(-2.0, 2.0), dz = rng.next(-2.0, 2.0);
        const double d = std::hypot(dx, dz);
        if (d < 1e-3) continue;
        const double rise = std::abs(node.height(x + dx, z + dz) - node.height(x, z));
        worstRatio = std::max(worstRatio, rise / d);
    }
    EXPECT_LE(worstRatio, node.slopeBound() * (1.0 + 1e-9) + 1e-12) << name;

    for (int r = 0; r < 60; ++r) {
        const double x = centre + rng.next(-400.0, 400.0), z = centre + rng.next(-400.0, 400.0);
        const double w = rng.next(0.5, 120.0), h = rng.next(0.5, 120.0);
        const Interval b = node.heightBounds({x, z}, {x + w, z + h});
        for (int k = 0; k < 40; ++k) {
            const double v = node.height(x + rng.next(0.0, w), z + rng.next(0.0, h));
            EXPECT_GE(v, b.lo - 1e-9) << name << " rect " << r;
            EXPECT_LE(v, b.hi + 1e-9) << name << " rect " << r;
        }
    }

    std::vector<double> xs, zs;
    for (int i = 0; i < 257; ++i) {
        xs.push_back(centre + rng.next(-300.0, 300.0));
        zs.push_back(centre + rng.next(-300.0, 300.0));
    }
    std::vector<double> block(xs.size());
    node.heights(xs.data(), zs.data(), xs.size(), block.data());
    for (std::size_t i = 0; i < xs.size(); ++i) {
        ASSERT_EQ(block[i], node.height(xs[i], zs[i])) << name << " column " << i;
    }
}

} // namespace

TEST(HeightGraph, CombinationsComputeTheirOperation)
{
    const HeightNodePtr a = hills(1), b = hills(2);
    const double x = 13.25, z = -71.5, ha = a->height(x, z), hb = b->height(x, z);
    EXPECT_EQ(HeightCombine(HeightOp::Add, {a, b}).height(x, z), ha + hb);
    EXPECT_EQ(HeightCombine(HeightOp::Subtract, {a, b, constant(3.0)}).height(x, z), ha - hb - 3.0);
    EXPECT_EQ(HeightCombine(HeightOp::Multiply, {a, constant(0.5)}).height(x, z), ha * 0.5);
    EXPECT_EQ(HeightCombine(HeightOp::Min, {a, b}).height(x, z), std::min(ha, hb));
    EXPECT_EQ(HeightCombine(HeightOp::Max, {a, b}).height(x, z), std::max(ha, hb));
    EXPECT_THROW(HeightCombine(HeightOp::Add, {a}), strata::Error);
}

TEST(HeightGraph, BlendTakesAWhereTheMaskIsZeroAndBWhereItIsOne)
{
    const HeightNodePtr a = constant(10.0), b = constant(50.0);
    EXPECT_EQ(HeightBlend(a, b, constant(0.0)).height(1, 2), 10.0);
    EXPECT_EQ(HeightBlend(a, b, constant(1.0)).height(1, 2), 50.0);
    EXPECT_EQ(HeightBlend(a, b, constant(0.25)).height(1, 2), 20.0);
    EXPECT_EQ(HeightBlend(a, b, constant(7.0)).height(1, 2), 50.0); // clamped
}

TEST(HeightGraph, CurvePassesThroughItsPointsWithoutOvershoot)
{
    const std::vector<glm::dvec2> points{{0.0, 0.0}, {10.0, 2.0}, {20.0, 18.0}, {30.0, 20.0}};
    for (const glm::dvec2& p : points) {
        EXPECT_NEAR(HeightCurve(constant(p.x), points).height(0, 0), p.y, 1e-12);
    }
    // Monotone data stays monotone and inside the data's range.
    double previous = -1.0;
    for (double h = -5.0; h <= 35.0; h += 0.05) {
        const double v = HeightCurve(constant(h), points).height(0, 0);
        EXPECT_GE(v, previous - 1e-12);
        EXPECT_GE(v, 0.0);
        EXPECT_LE(v, 20.0);
        previous = v;
    }
    EXPECT_THROW(HeightCurve(constant(0), {{0.0, 0.0}}), strata::Error);
    EXPECT_THROW(HeightCurve(constant(0), {{0.0, 0.0}, {0.0, 1.0}}), strata::Error);
}

TEST(HeightGraph, ScaleClampAndTerrace)
{
    HeightAffineOptions o;
    o.scale = -2.0;
    o.offset = 5.0;
    EXPECT_EQ(HeightAffine(constant(3.0), o).height(0, 0), -1.0);
    o.min = 0.0;
    EXPECT_EQ(HeightAffine(constant(3.0), o).height(0, 0), 0.0);
    // A terrace keeps whole steps and flattens inside them.
    EXPECT_EQ(HeightTerrace(constant(20.0), 10.0, 4.0).height(0, 0), 20.0);
    EXPECT_NEAR(HeightTerrace(constant(25.0), 10.0, 4.0).height(0, 0), 20.0 + 10.0 * std::pow(0.5, 4.0), 1e-12);
}

TEST(HeightGraph, MasksMeasureHeightSlopeAndCurvature)
{
    MaskOptions band;
    band.min = 10.0;
    band.max = 20.0;
    band.softness = 5.0;
    EXPECT_EQ(HeightMask(constant(15.0), band).height(0, 0), 1.0);
    EXPECT_EQ(HeightMask(constant(30.0), band).height(0, 0), 0.0);
    EXPECT_NEAR(HeightMask(constant(7.5), band).height(0, 0), 0.5, 1e-12);

    // A plane of slope 0.3 along x: a slope band around 0.3 is 1, one
    // around 0.8 is 0; its curvature is 0.
    struct Plane final : HeightfieldBase
    {
        Plane() { setSlopeBound(0.3); }
        double height(double x, double) const override { return 0.3 * x; }
    };
    const auto plane = std::make_shared<Plane>();
    MaskOptions slope;
    slope.source = MaskSource::Slope;
    slope.min = 0.25;
    slope.max = 0.35;
    slope.softness = 0.05;
    EXPECT_NEAR(HeightMask(plane, slope).height(100.0, -40.0), 1.0, 1e-9);
    slope.min = 0.75;
    slope.max = 0.85;
    EXPECT_NEAR(HeightMask(plane, slope).height(100.0, -40.0), 0.0, 1e-9);

    // A paraboloid bowl h = (x² + z²)/100: −∇²h = −0.04 everywhere (a valley).
    struct Bowl final : HeightfieldBase
    {
        Bowl() { setSlopeBound(1e9); }
        double height(double x, double z) const override { return (x * x + z * z) / 100.0; }
    };
    MaskOptions curvature;
    curvature.source = MaskSource::Curvature;
    curvature.min = -0.05;
    curvature.max = -0.03;
    curvature.softness = 0.001;
    EXPECT_NEAR(HeightMask(std::make_shared<Bowl>(), curvature).height(3.0, 4.0), 1.0, 1e-9);
    curvature.min = 0.03;
    curvature.max = 0.05;
    EXPECT_NEAR(HeightMask(std::make_shared<Bowl>(), curvature).height(3.0, 4.0), 0.0, 1e-9);
}

TEST(HeightGraph, EveryNodeKeepsItsSlopeBoundsAndBlockBits)
{
    const HeightNodePtr a = hills(1), b = hills(2, 25.0);
    MaskOptions slope;
    slope.source = MaskSource::Slope;
    slope.min = 0.0;
    slope.max = 0.2;
    slope.softness = 0.2;
    MaskOptions curvature;
    curvature.source = MaskSource::Curvature;
    curvature.min = -1.0;
    curvature.max = 0.0;
    curvature.softness = 0.02;
    curvature.radius = 6.0;
    MaskOptions height;
    height.min = -5.0;
    height.max = 5.0;
    height.softness = 8.0;
    const HeightNodePtr mask = std::make_shared<HeightMask>(a, slope);
    HeightAffineOptions clamp;
    clamp.scale = 1.5;
    clamp.min = -10.0;
    clamp.max = 12.0;
    const std::vector<std::pair<std::string, HeightNodePtr>> nodes{
        {"add", std::make_shared<HeightCombine>(HeightOp::Add, std::vector<HeightNodePtr>{a, b})},
        {"subtract", std::make_shared<HeightCombine>(HeightOp::Subtract, std::vector<HeightNodePtr>{a, b})},
        {"multiply", std::make_shared<HeightCombine>(HeightOp::Multiply, std::vector<HeightNodePtr>{a, mask})},
        {"min", std::make_shared<HeightCombine>(HeightOp::Min, std::vector<HeightNodePtr>{a, b})},
        {"max", std::make_shared<HeightCombine>(HeightOp::Max, std::vector<HeightNodePtr>{a, b})},
        {"blend", std::make_shared<HeightBlend>(a, b, mask)},
        {"affine", std::make_shared<HeightAffine>(a, clamp)},
        {"curve", std::make_shared<HeightCurve>(a, std::vector<glm::dvec2>{{-20, -30}, {0, 0}, {5, 20}, {30, 22}})},
        {"terrace", std::make_shared<HeightTerrace>(a, 6.0, 3.0)},
        {"warp", std::make_shared<HeightWarp>(a, 9, HeightWarpOptions{})},
        {"mask_height", std::make_shared<HeightMask>(a, height)},
        {"mask_slope", mask},
        {"mask_curvature", std::make_shared<HeightMask>(a, curvature)},
    };
    for (const auto& [name, node] : nodes) {
        checkPromises(*node, name);
        checkPromises(*node, name + " far out", 1e7);
    }
}

TEST(HeightGraph, TheRegistryNamesEveryNodeAndItsKeys)
{
    const NodeRegistry& r = NodeRegistry::builtin();
    for (const char* name : {"height_constant", "height_add", "height_subtract", "height_multiply", "height_min",
                             "height_max", "height_blend", "height_curve", "height_scale", "height_clamp",
                             "height_warp", "height_terrace", "mask_height", "mask_slope", "mask_curvature", "erode"}) {
        const NodeType* type = r.find(name);
        ASSERT_NE(type, nullptr) << name;
        EXPECT_FALSE(type->description.empty()) << name;
    }
    // The heightfield node takes a height graph instead of its noise.
    EXPECT_NE(r.find("heightfield")->findKey("height"), nullptr);
}

TEST(HeightGraph, AChildThatIsA3DNodeIsRefusedNamingTheKey)
{
    const NodeType* blend = NodeRegistry::builtin().find("height_blend");
    NodeArgs args("b", 1);
    args.set("a", DensityFieldPtr(std::make_shared<SphereField>(glm::dvec3(0.0), 5.0)));
    args.set("b", DensityFieldPtr(constant(1.0)));
    args.set("mask", DensityFieldPtr(constant(1.0)));
    try {
        blend->build(args);
        FAIL() << "a 3D child was accepted";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.place().key, "a");
        EXPECT_NE(std::string(e.what()).find("height node"), std::string::npos) << e.what();
    }
}
