// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/TerrainField.h>

#include <openvdb/tools/Interpolation.h>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

using namespace strata::terrain;

namespace {

/// Runs `make` and expects a strata::Error whose message contains `key`.
void expectError(const std::function<void()>& make, const std::string& key)
{
    try {
        make();
        ADD_FAILURE() << "no strata::Error for " << key;
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << "message: " << e.what();
    }
}

} // namespace

TEST(TerrainField, DeepUnderTheSurfaceIsRockAndTheSkyIsAir)
{
    const TerrainField field(TerrainOptions{});
    int rockChecked = 0;
    for (double x = -90.0; x <= 90.0; x += 15.0) {
        for (double z = -90.0; z <= 90.0; z += 15.0) {
            const double h = field.height(x, z);
            EXPECT_GT(field.density({x, h + 200.0, z}), 0.0) << "sky at " << x << ", " << z;
            EXPECT_GT(field.density({x, h + 0.5, z}), 0.0) << "just above the ground at " << x << ", " << z;
            const glm::dvec3 deep(x, h - 30.0, z);
            if (field.caveDistance(deep) > 0.0) { // not in a tunnel
                EXPECT_LT(field.density(deep), 0.0) << "deep at " << x << ", " << z;
                ++rockChecked;
            }
        }
    }
    EXPECT_GT(rockChecked, 100);
}

TEST(TerrainField, HeightfieldFollowsTheOptions)
{
    TerrainOptions options;
    options.caves.enabled = false;
    options.height.baseHeight = 10.0;
    const TerrainField field(options);
    double lo = 1e9, hi = -1e9;
    for (double x = -500.0; x <= 500.0; x += 7.0) {
        for (double z = -500.0; z <= 500.0; z += 7.0) {
            const double h = field.height(x, z);
            lo = std::min(lo, h), hi = std::max(hi, h);
            // Without caves the density is the scaled height term, zero on the surface.
            EXPECT_NEAR(field.density({x, h, z}), 0.0, 1e-9);
        }
    }
    EXPECT_GE(lo, 10.0 - options.height.amplitude);
    EXPECT_LE(hi, 10.0 + options.height.amplitude);
    EXPECT_GT(hi - lo, 0.5 * options.height.amplitude) << "hills expected";
}

TEST(TerrainField, DensityIsOneLipschitz)
{
    // |d(a) − d(b)| <= |a − b| for random pairs, at several distances: this
    // is what lets sampling skip tiles.
    TerrainOptions options;
    options.caves.maxHeight = 5.0; // exercise the ramp above maxHeight too
    for (const bool caves : {true, false}) {
        options.caves.enabled = caves;
        const TerrainField field(options);
        std::uint64_t state = 99;
        const auto uniform = [&state](double lo, double hi) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            return lo + (hi - lo) * double(state >> 11) * 0x1.0p-53;
        };
        double worst = 0.0;
        for (int i = 0; i < 100000; ++i) {
            const glm::dvec3 a(uniform(-200, 200), uniform(-40, 40), uniform(-200, 200));
            const double step = i % 3 == 0 ? 0.01 : (i % 3 == 1 ? 0.5 : 4.0);
            const glm::dvec3 b = a + step * glm::normalize(glm::dvec3(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
            const double distance = glm::length(b - a);
            worst = std::max(worst, std::abs(field.density(a) - field.density(b)) / distance);
            worst = std::max(worst, std::abs(field.caveDistance(a) - field.caveDistance(b)) / distance);
        }
        std::cout << "measured Lipschitz ratio (caves " << caves << "): " << worst << "\n";
        // Float noise values round at about 1e-7 of the amplitude.
        EXPECT_LE(worst, 1.0 + 1e-3) << "caves " << caves;
    }
}

TEST(TerrainField, IsDeterministicAndSeeded)
{
    TerrainOptions a, b;
    b.seed = 2;
    const TerrainField fa(a), fa2(a), fb(b);
    int differ = 0;
    for (int i = 0; i < 100; ++i) {
        const glm::dvec3 p(3.1 * i - 150.0, 0.37 * i - 20.0, 150.0 - 2.9 * i);
        EXPECT_EQ(fa.density(p), fa2.density(p));
        differ += fa.density(p) != fb.density(p);
    }
    EXPECT_GT(differ, 95);
}

TEST(TerrainField, CavesCanBeDisabledAndCapped)
{
    TerrainOptions options;
    const TerrainField withCaves(options);
    options.caves.enabled = false;
    const TerrainField without(options);
    options.caves.enabled = true;
    options.caves.maxHeight = -10.0;
    const TerrainField capped(options);

    int tunnelPoints = 0;
    for (double x = -96.0; x < 96.0; x += 2.0) {
        for (double y = -40.0; y < 40.0; y += 2.0) {
            for (double z = -96.0; z < 96.0; z += 8.0) {
                const glm::dvec3 p(x, y, z);
                // density = max(ground, −cave), and caves only remove rock.
                EXPECT_EQ(withCaves.density(p), std::max(without.density(p), -withCaves.caveDistance(p)));
                EXPECT_GE(withCaves.density(p), without.density(p));
                if (y > -10.0) {
                    // Above maxHeight no tunnel: rock stays rock (values near
                    // maxHeight change: the cap is a 1-Lipschitz ramp).
                    EXPECT_EQ(capped.density(p) < 0.0, without.density(p) < 0.0) << "no tunnel above maxHeight";
                    EXPECT_GE(capped.caveDistance(p), y + 10.0);
                }
                tunnelPoints += withCaves.caveDistance(p) < 0.0;
            }
        }
    }
    EXPECT_GT(tunnelPoints, 100);
}

TEST(TerrainField, DefaultSceneHasTunnelOpeningsButIsNotSwissCheese)
{
    // The lead's default scene: x, z in [−96, 96], y in [−40, 40], seed 1.
    const TerrainField field(TerrainOptions{});
    const int n = 192;
    std::vector<int> open(n * n, 0);
    for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
            const double x = -96.0 + i + 0.5, z = -96.0 + k + 0.5;
            // Half a metre under the surface is air: a tunnel cuts the ground here.
            open[i * n + k] = field.density({x, field.height(x, z) - 0.5, z}) > 0.0;
        }
    }
    // Count connected openings (4-neighbour flood fill).
    int openings = 0;
    std::vector<int> stack;
    for (int s = 0; s < n * n; ++s) {
        if (open[s] != 1) continue;
        ++openings;
        open[s] = 2;
        stack.push_back(s);
        while (!stack.empty()) {
            const int c = stack.back();
            stack.pop_back();
            const int i = c / n, k = c % n;
            const int neighbours[4][2] = {{i + 1, k}, {i - 1, k}, {i, k + 1}, {i, k - 1}};
            for (const auto& nb : neighbours) {
                if (nb[0] < 0 || nb[1] < 0 || nb[0] >= n || nb[1] >= n || open[nb[0] * n + nb[1]] != 1) continue;
                open[nb[0] * n + nb[1]] = 2;
                stack.push_back(nb[0] * n + nb[1]);
            }
        }
    }
    // Fraction of the rock (below the surface) that is tunnel.
    int rock = 0, tunnel = 0;
    for (double x = -95.0; x < 96.0; x += 2.0)
        for (double y = -39.0; y < 40.0; y += 2.0)
            for (double z = -95.0; z < 96.0; z += 2.0) {
                if (y >= field.height(x, z)) continue;
                ++rock;
                tunnel += field.density({x, y, z}) > 0.0;
            }
    const double fraction = double(tunnel) / rock;
    std::cout << "default scene: " << openings << " tunnel openings, tunnels are " << 100.0 * fraction
              << "% of the rock\n";
    EXPECT_GE(openings, 5);
    EXPECT_GT(fraction, 0.01);
    EXPECT_LT(fraction, 0.08);
}

TEST(TerrainField, TunnelAxisBelowTheSurfaceIsAirAndSamplingAgrees)
{
    const TerrainField field(TerrainOptions{});
    // Search voxel centres well below the surface for the deepest cave value.
    const double voxel = 0.5;
    glm::dvec3 best(0.0);
    double bestCave = std::numeric_limits<double>::infinity();
    for (double x = -64.0; x <= 64.0; x += 2.0 * voxel)
        for (double z = -64.0; z <= 64.0; z += 2.0 * voxel) {
            const double h = field.height(x, z);
            for (double y = std::floor((h - 25.0) / voxel) * voxel; y < h - 10.0; y += voxel) {
                const double c = field.caveDistance({x, y, z});
                if (c < bestCave) bestCave = c, best = glm::dvec3(x, y, z);
            }
        }
    // On a tunnel axis the cave term is only about −0.27 m with the default
    // options (it underestimates the distance to the wall, see CaveOptions).
    ASSERT_LT(bestCave, -0.2) << "no tunnel axis found 10-25 m below the surface";
    EXPECT_LT(best.y, field.height(best.x, best.z) - 10.0);
    EXPECT_GT(field.density(best), 0.0) << "a tunnel is air";

    // Sample a box around it and read the grid there.
    SampleOptions options;
    options.voxelSize = voxel;
    options.region.min = best - glm::dvec3(16.0);
    options.region.max = best + glm::dvec3(16.0);
    const openvdb::FloatGrid::Ptr grid = sampleLevelSet(field, options);
    const openvdb::Coord ijk = openvdb::Coord::round(openvdb::Vec3d(best.x, best.y, best.z) / voxel);
    EXPECT_GT(grid->tree().getValue(ijk), 0.0f) << "the grid says rock inside the tunnel";
    const openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
    EXPECT_GT(sampler.wsSample(openvdb::Vec3d(best.x, best.y, best.z)), 0.0f);
}

TEST(TerrainField, BadOptionsThrowNamingTheKey)
{
    const auto make = [](auto edit) {
        return [edit]() {
            TerrainOptions o;
            edit(o);
            TerrainField field(o);
        };
    };
    expectError(make([](TerrainOptions& o) { o.height.fbm.octaves = 0; }), "height.octaves = 0 is out of range 1..24");
    expectError(make([](TerrainOptions& o) { o.height.fbm.octaves = 100; }), "height.octaves = 100");
    expectError(make([](TerrainOptions& o) { o.caves.fbm.octaves = 25; }), "caves.octaves = 25");
    expectError(make([](TerrainOptions& o) { o.height.wavelength = 0.0; }), "height.wavelength");
    expectError(make([](TerrainOptions& o) { o.height.wavelength = std::nan(""); }), "height.wavelength");
    expectError(make([](TerrainOptions& o) { o.height.amplitude = -1.0; }), "height.amplitude");
    expectError(make([](TerrainOptions& o) { o.height.baseHeight = INFINITY; }), "height.base");
    expectError(make([](TerrainOptions& o) { o.height.fbm.lacunarity = -2.0; }), "height.lacunarity");
    expectError(make([](TerrainOptions& o) { o.height.fbm.gain = -0.5; }), "height.gain");
    expectError(make([](TerrainOptions& o) { o.caves.wavelength = -48.0; }), "caves.wavelength");
    expectError(make([](TerrainOptions& o) { o.caves.radius = 0.0; }), "caves.radius");
    expectError(make([](TerrainOptions& o) { o.caves.verticalSquash = std::nan(""); }), "caves.vertical_squash");
    expectError(make([](TerrainOptions& o) { o.caves.maxHeight = std::nan(""); }), "caves.max_height");
    expectError(make([](TerrainOptions& o) { o.noiseVersion = 3; }), "noise_version = 3 is out of range 1..2");
    // Amplitude 0 is a flat plane, and allowed.
    TerrainOptions flat;
    flat.height.amplitude = 0.0;
    flat.caves.enabled = false;
    EXPECT_DOUBLE_EQ(TerrainField(flat).density({3.0, 2.0, 1.0}), 2.0);
}

TEST(TerrainField, SphereFieldIsTheExactDistance)
{
    const SphereField sphere({1.0, 2.0, 3.0}, 4.0);
    EXPECT_DOUBLE_EQ(sphere.density({1.0, 2.0, 3.0}), -4.0);
    EXPECT_DOUBLE_EQ(sphere.density({1.0, 2.0, 10.0}), 3.0);
    EXPECT_DOUBLE_EQ(sphere.density({5.0, 2.0, 3.0}), 0.0);
    EXPECT_EQ(sphere.lipschitz(), 1.0);
}

TEST(TerrainField, Version2BoxBoundsHoldEveryPointAndBeatTheLipschitzBound)
{
    // Boxes of 0.5 to 8 m across the surface, the tunnels and far from both
    // (1e6 m out too): every point of a 5×5×5 lattice in each lies inside
    // the box's bounds; on average they are tighter than density ± radius.
    TerrainOptions options;
    options.noiseVersion = 2;
    options.caves.maxHeight = 10.0;
    const TerrainField field(options);
    std::uint64_t state = 7;
    const auto unit = [&state] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return double(state >> 11) * 0x1.0p-53;
    };
    double width = 0.0, lipschitzWidth = 0.0;
    int boxes = 0;
    for (const double far : {0.0, 1e6}) {
        for (int i = 0; i < 300; ++i) {
            const double size = 0.5 * std::pow(2.0, 4.0 * unit());
            const glm::dvec3 lo(far + 200.0 * unit() - 100.0, 70.0 * unit() - 45.0, -far + 200.0 * unit() - 100.0);
            const WorldBox box{lo, lo + glm::dvec3(size, 0.7 * size, 1.3 * size)};
            const Interval bounds = field.bounds(box);
            for (int a = 0; a < 5; ++a)
                for (int b = 0; b < 5; ++b)
                    for (int c = 0; c < 5; ++c) {
                        const glm::dvec3 p = box.min + (box.max - box.min) * glm::dvec3(a, b, c) / 4.0;
                        const double d = field.density(p);
                        ASSERT_GE(d, bounds.lo) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
                        ASSERT_LE(d, bounds.hi) << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
                    }
            width += bounds.hi - bounds.lo;
            lipschitzWidth += 2.0 * box.radius();
            ++boxes;
        }
    }
    EXPECT_EQ(boxes, 600);
    EXPECT_LT(width, 0.9 * lipschitzWidth) << "the fBms' box bounds are no tighter than the slope";
}
