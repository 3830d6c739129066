// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The top surface of fields whose answer is known: a noise heightfield (its
// height()), a sphere (its upper cap, nothing outside its disc), a heightfield
// with a cave carved under the surface (the upper surface kept) and with a
// rock floating above it (the rock's top), boxes entirely above and below the
// ground; the grid layout, the same bits on 1 and N threads, interruption and
// bad input.

#include <strata/Error.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/TopSurface.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <string>

namespace {

using namespace strata::terrain;

constexpr double TOLERANCE = 1e-3; // metres: the goal; the sampler aims at 1e-4

std::shared_ptr<const NoiseHeightfield> hills()
{
    return std::make_shared<NoiseHeightfield>(7, NoiseHeightfieldOptions{});
}

WorldBox box(double x0, double y0, double z0, double x1, double y1, double z1)
{
    return {{x0, y0, z0}, {x1, y1, z1}};
}

TEST(TopSurface, GridLayoutCoversTheRegion)
{
    const SphereField ball({0.0, 0.0, 0.0}, 5.0);
    // x: 10 / 4 = 2.5 cells, columns at -3, 1, 5; z: 8 / 4 = 2 cells, rows at -1, 3, 7.
    const TopSurfaceGrid grid = sampleTopSurface(ball, box(-3.0, -10.0, -1.0, 7.0, 10.0, 7.0), 4.0);
    EXPECT_EQ(grid.width, 3);
    EXPECT_EQ(grid.height, 3);
    EXPECT_EQ(grid.cellSize, 4.0);
    EXPECT_EQ(grid.origin.x, -3.0);
    EXPECT_EQ(grid.origin.y, -1.0);
    ASSERT_EQ(grid.heights.size(), 9u);
    // A point region is one column.
    const TopSurfaceGrid point = sampleTopSurface(ball, box(1.0, -10.0, 1.0, 1.0, 10.0, 1.0), 1.0);
    EXPECT_EQ(point.width, 1);
    EXPECT_EQ(point.height, 1);
    EXPECT_NEAR(point.heights[0], std::sqrt(23.0), TOLERANCE);
    // Rounding of the extent does not drop the last column: 0.3 / 0.1 is 2.9999999999999996.
    EXPECT_EQ(sampleTopSurface(ball, box(0.0, -1.0, 0.0, 0.3, 1.0, 0.3), 0.1).width, 4);
}

TEST(TopSurface, NoiseHeightfieldTopIsItsHeight)
{
    const auto ground = hills();
    const TopSurfaceGrid grid = sampleTopSurface(*ground, box(-200.0, -150.0, -120.0, 200.0, 150.0, 160.0), 10.0);
    ASSERT_EQ(grid.width, 41);
    ASSERT_EQ(grid.height, 29);
    double worst = 0.0;
    for (int z = 0; z < grid.height; ++z) {
        for (int x = 0; x < grid.width; ++x) {
            const double h = ground->height(-200.0 + 10.0 * x, -120.0 + 10.0 * z);
            ASSERT_GT(h, -150.0);
            ASSERT_LT(h, 150.0);
            worst = std::max(worst, std::abs(grid.heights[std::size_t(z * grid.width + x)] - h));
        }
    }
    EXPECT_LE(worst, TOLERANCE);
    EXPECT_EQ(grid.columnsAtTop, 0u);
    EXPECT_EQ(grid.columnsAtBottom, 0u);
}

TEST(TopSurface, SphereTopIsItsUpperCapAndNothingOutside)
{
    const glm::dvec3 centre(1.5, 2.0, -0.5);
    const double radius = 10.0;
    const SphereField ball(centre, radius);
    const WorldBox region = box(-12.0, -20.0, -14.0, 14.0, 20.0, 12.0);
    const TopSurfaceGrid grid = sampleTopSurface(ball, region, 1.0);
    std::size_t outside = 0;
    for (int z = 0; z < grid.height; ++z) {
        for (int x = 0; x < grid.width; ++x) {
            const double px = region.min.x + x, pz = region.min.z + z;
            const double r2 = radius * radius - (px - centre.x) * (px - centre.x) - (pz - centre.z) * (pz - centre.z);
            const double h = grid.heights[std::size_t(z * grid.width + x)];
            if (r2 < 0.0) {
                EXPECT_EQ(h, region.min.y) << px << ", " << pz;
                ++outside;
            } else {
                EXPECT_NEAR(h, centre.y + std::sqrt(r2), TOLERANCE) << px << ", " << pz;
            }
        }
    }
    EXPECT_GT(outside, 0u);
    EXPECT_EQ(grid.columnsAtBottom, outside);
    EXPECT_EQ(grid.columnsAtTop, 0u);
}

TEST(TopSurface, CaveUnderTheSurfaceKeepsTheUpperSurface)
{
    const auto ground = hills();
    const double h0 = ground->height(0.0, 0.0);
    // A cave 8 m across whose roof is 6 m below the ground at its centre.
    const DensityFieldPtr cave = std::make_shared<SphereField>(glm::dvec3(0.0, h0 - 14.0, 0.0), 8.0);
    const CsgField carved(CsgOperation::SUBTRACT, {ground, cave});
    const WorldBox region = box(-20.0, h0 - 40.0, -20.0, 20.0, h0 + 40.0, 20.0);
    ASSERT_GT(carved.density({0.0, h0 - 14.0, 0.0}), 0.0); // the cave is air inside
    const TopSurfaceGrid top = sampleTopSurface(carved, region, 2.0);
    const TopSurfaceGrid plain = sampleTopSurface(*ground, region, 2.0);
    ASSERT_EQ(top.heights.size(), plain.heights.size());
    for (int z = 0; z < top.height; ++z) {
        for (int x = 0; x < top.width; ++x) {
            const std::size_t i = std::size_t(z * top.width + x);
            EXPECT_NEAR(top.heights[i], ground->height(-20.0 + 2.0 * x, -20.0 + 2.0 * z), TOLERANCE) << x << ", " << z;
            EXPECT_NEAR(top.heights[i], plain.heights[i], TOLERANCE);
        }
    }
}

TEST(TopSurface, FloatingRockAboveTheGroundIsTheTop)
{
    const auto ground = hills();
    const double h0 = ground->height(0.0, 0.0);
    const DensityFieldPtr rock = std::make_shared<SphereField>(glm::dvec3(0.0, h0 + 20.0, 0.0), 4.0);
    const CsgField both(CsgOperation::UNION, {ground, rock});
    const TopSurfaceGrid grid = sampleTopSurface(both, box(0.0, h0 - 30.0, 0.0, 0.0, h0 + 30.0, 6.0), 6.0);
    ASSERT_EQ(grid.heights.size(), 2u);
    EXPECT_NEAR(grid.heights[0], h0 + 24.0, TOLERANCE);                // over the rock: its top
    EXPECT_NEAR(grid.heights[1], ground->height(0.0, 6.0), TOLERANCE); // beside it: the ground
}

TEST(TopSurface, EmptyAndFullColumns)
{
    const auto ground = hills();
    const double h0 = ground->height(0.0, 0.0);
    // The hills stay well within 500 m of h0.
    const WorldBox above = box(-30.0, h0 + 500.0, -30.0, 30.0, h0 + 600.0, 30.0);
    const TopSurfaceGrid empty = sampleTopSurface(*ground, above, 10.0);
    for (double h : empty.heights) EXPECT_EQ(h, above.min.y);
    EXPECT_EQ(empty.columnsAtBottom, empty.heights.size());
    EXPECT_EQ(empty.columnsAtTop, 0u);

    const WorldBox below = box(-30.0, h0 - 600.0, -30.0, 30.0, h0 - 500.0, 30.0);
    const TopSurfaceGrid full = sampleTopSurface(*ground, below, 10.0);
    for (double h : full.heights) EXPECT_EQ(h, below.max.y);
    EXPECT_EQ(full.columnsAtTop, full.heights.size());
    EXPECT_EQ(full.columnsAtBottom, 0u);

    // A flat box (min.y == max.y) gives its one height either way.
    const WorldBox flat = box(-30.0, h0 + 500.0, -30.0, 30.0, h0 + 500.0, 30.0);
    for (double h : sampleTopSurface(*ground, flat, 10.0).heights) EXPECT_EQ(h, flat.min.y);
}

TEST(TopSurface, FarFromTheOriginEveryStepMoves)
{
    // Doubles are 2 m apart near 1e16: steps of the tolerance would not move.
    const SphereField ball({0.0, 1e16, 0.0}, 1e3);
    const TopSurfaceGrid grid = sampleTopSurface(ball, box(0.0, 1e16 - 1e6, 0.0, 0.0, 1e16 + 1e6, 0.0), 1.0);
    ASSERT_EQ(grid.heights.size(), 1u);
    EXPECT_NEAR(grid.heights[0], 1e16 + 1e3, 8.0);
}

TEST(TopSurface, SameBitsOnOneAndManyThreads)
{
    const auto ground = hills();
    const DensityFieldPtr cave = std::make_shared<SphereField>(glm::dvec3(10.0, -5.0, 3.0), 12.0);
    const CsgField carved(CsgOperation::SUBTRACT, {ground, cave}, 1.5);
    const WorldBox region = box(-64.0, -100.0, -64.0, 64.0, 100.0, 64.0);
    TopSurfaceGrid one;
    {
        const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        one = sampleTopSurface(carved, region, 2.0);
    }
    const TopSurfaceGrid many = sampleTopSurface(carved, region, 2.0);
    ASSERT_EQ(one.heights.size(), many.heights.size());
    EXPECT_EQ(std::memcmp(one.heights.data(), many.heights.data(), one.heights.size() * sizeof(double)), 0);
}

TEST(TopSurface, ProgressReportsAndInterrupts)
{
    const auto ground = hills();
    const WorldBox region = box(-64.0, -100.0, -64.0, 64.0, 100.0, 64.0);
    double last = -1.0;
    bool monotonic = true;
    sampleTopSurface(*ground, region, 4.0, [&](double fraction) {
        monotonic = monotonic && fraction >= last;
        last = fraction;
        return true;
    });
    EXPECT_TRUE(monotonic);
    EXPECT_EQ(last, 1.0);
    try {
        sampleTopSurface(*ground, region, 4.0, [](double fraction) { return fraction < 0.3; });
        FAIL() << "no error";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Interrupted);
        EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos);
    }
}

TEST(TopSurface, BadInputThrows)
{
    const SphereField ball({0.0, 0.0, 0.0}, 5.0);
    const WorldBox region = box(-8.0, -8.0, -8.0, 8.0, 8.0, 8.0);
    auto expectError = [](auto&& call, const std::string& expected) {
        try {
            call();
            ADD_FAILURE() << "no error; expected '" << expected << "'";
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
        }
    };
    expectError([&] { sampleTopSurface(ball, region, 0.0); }, "cell size");
    expectError([&] { sampleTopSurface(ball, region, -1.0); }, "cell size");
    expectError([&] { sampleTopSurface(ball, region, std::nan("")); }, "cell size");
    expectError([&] { sampleTopSurface(ball, box(1.0, -8.0, -8.0, -1.0, 8.0, 8.0), 1.0); }, "min <= max");
    expectError([&] { sampleTopSurface(ball, box(-8.0, 8.0, -8.0, 8.0, -8.0, 8.0), 1.0); }, "min <= max");
    expectError([&] { sampleTopSurface(ball, box(-8.0, -HUGE_VAL, -8.0, 8.0, 8.0, 8.0), 1.0); }, "finite");
    expectError([&] { sampleTopSurface(ball, box(-1e9, -8.0, -1e9, 1e9, 8.0, 1e9), 1.0); }, "too many");
}

} // namespace
