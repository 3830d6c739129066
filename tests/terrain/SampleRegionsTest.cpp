// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Sampling node trees: box by box, far from the origin, under a memory
// budget, renormalised.

#include <strata/Error.h>
#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/LevelSetQuality.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/Transforms.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <iostream>
#include <memory>

using namespace strata::terrain;

namespace {

/// The default scene's kind of tree: warped hills minus worm tunnels; with
/// `terraced`, the hills cut into 7 m terraces and the warp as in the
/// default scene (4 m, 20 m wavelength, one octave).
DensityFieldPtr sceneTree(std::uint64_t seed, const glm::dvec3& offset = glm::dvec3(0.0), bool terraced = false)
{
    DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(deriveSeed(seed, 1), NoiseHeightfieldOptions{});
    WarpOptions warp;
    warp.amplitude = 7.0;
    warp.wavelength = 32.0;
    warp.vertical = 0.0;
    if (terraced) {
        hills = std::make_shared<TerraceField>(hills, 7.0, 4.0);
        warp.amplitude = 4.0;
        warp.wavelength = 20.0;
        warp.noise.octaves = 1;
    }
    DensityFieldPtr land = std::make_shared<WarpField>(hills, deriveSeed(seed, 2), warp);
    WormOptions worms;
    worms.wormsPerCell = 3.0;
    DensityFieldPtr tunnels = std::make_shared<WormCaves>(deriveSeed(seed, 3), worms);
    DensityFieldPtr root =
        std::make_shared<CsgField>(CsgOperation::SUBTRACT, std::vector<DensityFieldPtr>{land, tunnels}, 1.0);
    if (offset != glm::dvec3(0.0)) root = std::make_shared<TranslateField>(root, offset);
    return root;
}

SampleOptions box(const glm::dvec3& lo, const glm::dvec3& hi, double voxel = 1.0, bool closed = true)
{
    SampleOptions o;
    o.voxelSize = voxel;
    o.region = {lo, hi};
    o.closed = closed;
    return o;
}

/// Every voxel value (active or not) of `a` inside index box `b` equals `b`'s.
std::size_t compareIn(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b, const openvdb::CoordBBox& where,
                      double tolerance = 0.0, const openvdb::Coord& shift = openvdb::Coord(0))
{
    std::size_t mismatches = 0;
    auto accA = a.getConstAccessor();
    auto accB = b.getConstAccessor();
    for (auto it = where.begin(); it; ++it) {
        const float va = accA.getValue(*it), vb = accB.getValue(*it + shift);
        if (std::abs(double(va) - double(vb)) > tolerance || accA.isValueOn(*it) != accB.isValueOn(*it + shift)) {
            ++mismatches;
        }
    }
    return mismatches;
}

} // namespace

TEST(SampleRegions, SameBitsOnOneThreadAndManyAndDifferentSeedsDiffer)
{
    const SampleOptions options = box({-40, -30, -40}, {40, 30, 40});
    openvdb::FloatGrid::Ptr one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = sampleLevelSet(*sceneTree(1), options);
    }
    two = sampleLevelSet(*sceneTree(1), options);
    const openvdb::FloatGrid::Ptr other = sampleLevelSet(*sceneTree(2), options);
    ASSERT_EQ(one->activeVoxelCount(), two->activeVoxelCount());
    EXPECT_EQ(compareIn(*one, *two, one->evalActiveVoxelBoundingBox()), 0u);
    EXPECT_GT(compareIn(*one, *other, one->evalActiveVoxelBoundingBox()), 1000u);
}

TEST(SampleRegions, AdjacentBoxesAgreeOnSharedVoxels)
{
    // Open boxes (chunks) that overlap by a slab of voxels, and a box that
    // holds both: every shared voxel has the same value and state.
    const DensityFieldPtr field = sceneTree(4);
    const auto left = sampleLevelSet(*field, box({-40, -30, -20}, {4.5, 30, 20}, 0.5, false));
    const auto right = sampleLevelSet(*field, box({-3, -30, -20}, {40, 30, 20}, 0.5, false));
    const auto whole = sampleLevelSet(*field, box({-40, -30, -20}, {40, 30, 20}, 0.5, false));
    const openvdb::CoordBBox shared(openvdb::Coord(-6, -60, -40), openvdb::Coord(8, 59, 39));
    EXPECT_EQ(compareIn(*left, *right, shared), 0u);
    EXPECT_EQ(compareIn(*left, *whole, openvdb::CoordBBox({-80, -60, -40}, {8, 59, 39})), 0u);
    EXPECT_EQ(compareIn(*right, *whole, openvdb::CoordBBox({-6, -60, -40}, {79, 59, 39})), 0u);
    EXPECT_GT(left->activeVoxelCount(), 1000u);
}

TEST(SampleRegions, WorldOffsetFarFromTheOriginGivesTheSameGrid)
{
    // The whole world moved by (1e6, 0, −1e6): the same values after
    // translation (1e6 is a whole number of voxels).
    const glm::dvec3 offset(1e6, 0.0, -1e6);
    const auto here = sampleLevelSet(*sceneTree(6), box({-24, -30, -24}, {24, 30, 24}, 0.5));
    const auto there = sampleLevelSet(*sceneTree(6, offset), box(glm::dvec3(-24, -30, -24) + offset,
                                                                 glm::dvec3(24, 30, 24) + offset, 0.5));
    EXPECT_EQ(here->activeVoxelCount(), there->activeVoxelCount());
    const openvdb::Coord shift(2000000, 0, -2000000);
    EXPECT_EQ(compareIn(*here, *there, openvdb::CoordBBox({-50, -62, -50}, {50, 62, 50}), 1e-4 * 0.5, shift), 0u);
}

TEST(SampleRegions, TerracedSceneIsTheSameOnAnyThreadInAnyBoxAndFarOut)
{
    // The default scene's tree prunes 4³ and 2³ sub-blocks by interval
    // bounds through terraces and the warp: still the same bits on any
    // thread count, the same shared voxels in adjacent open boxes, and the
    // same grid 1e6 m out.
    const DensityFieldPtr field = sceneTree(7, glm::dvec3(0.0), true);
    const SampleOptions options = box({-30, -25, -30}, {30, 25, 30}, 0.5);
    openvdb::FloatGrid::Ptr one, many;
    SampleStats oneStats, manyStats;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = sampleLevelSet(*field, options, &oneStats);
    }
    many = sampleLevelSet(*field, options, &manyStats);
    ASSERT_GT(one->activeVoxelCount(), 50000u);
    ASSERT_EQ(one->activeVoxelCount(), many->activeVoxelCount());
    EXPECT_EQ(compareIn(*one, *many, openvdb::CoordBBox({-60, -50, -60}, {59, 49, 59})), 0u);
    EXPECT_EQ(oneStats.evaluatedPoints, manyStats.evaluatedPoints);
    EXPECT_EQ(oneStats.boundEvaluations, manyStats.boundEvaluations);
    EXPECT_GT(oneStats.boundEvaluations, 0u);
    EXPECT_LT(oneStats.boundEvaluations, oneStats.evaluatedPoints);

    const auto left = sampleLevelSet(*field, box({-30, -25, -20}, {4.5, 25, 20}, 0.5, false));
    const auto right = sampleLevelSet(*field, box({-3, -25, -20}, {30, 25, 20}, 0.5, false));
    EXPECT_EQ(compareIn(*left, *right, openvdb::CoordBBox({-6, -50, -40}, {8, 49, 39})), 0u);
    EXPECT_GT(left->activeVoxelCount(), 1000u);

    const glm::dvec3 offset(1e6, 0.0, -1e6);
    const auto here = sampleLevelSet(*field, box({-16, -25, -16}, {16, 25, 16}, 0.5));
    const auto there = sampleLevelSet(*sceneTree(7, offset, true),
                                      box(glm::dvec3(-16, -25, -16) + offset, glm::dvec3(16, 25, 16) + offset, 0.5));
    EXPECT_EQ(here->activeVoxelCount(), there->activeVoxelCount());
    EXPECT_EQ(compareIn(*here, *there, openvdb::CoordBBox({-34, -52, -34}, {34, 52, 34}), 1e-4 * 0.5,
                        openvdb::Coord(2000000, 0, -2000000)),
              0u);
}

TEST(SampleRegions, MemoryBudgetRefusesWithAnEstimate)
{
    SampleOptions options = box({-96, -44, -96}, {96, 44, 96}, 0.5);
    options.maxMemoryBytes = 1 << 20; // 1 MiB
    try {
        sampleLevelSet(*sceneTree(1), options);
        ADD_FAILURE() << "no error";
    } catch (const strata::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("MiB"), std::string::npos) << what;
        EXPECT_NE(what.find("voxel_size"), std::string::npos) << what;
    }
    // The estimate is an upper bound of what the grid then uses.
    options.maxMemoryBytes = 0;
    SampleStats stats;
    const auto grid = sampleLevelSet(*sceneTree(1), box({-48, -44, -48}, {48, 44, 48}, 0.5), &stats);
    EXPECT_GE(stats.estimatedBytes, grid->memUsage());
    EXPECT_LT(stats.estimatedBytes, 4 * grid->memUsage());
}

TEST(SampleRegions, RenormalisationMakesTheBandADistance)
{
    // Spaghetti's density is a rough distance: renormalising fixes |∇φ|.
    DensityFieldPtr ground = std::make_shared<NoiseHeightfield>(1, NoiseHeightfieldOptions{});
    DensityFieldPtr caves = std::make_shared<SpaghettiCaves>(2, SpaghettiOptions{});
    const CsgField field(CsgOperation::SUBTRACT, {ground, caves});
    SampleOptions options = box({-32, -30, -32}, {32, 30, 32}, 0.5);
    const auto before = sampleLevelSet(field, options);
    options.renormalize = true;
    const auto after = sampleLevelSet(field, options);
    const SdfQuality q0 = measureSdfQuality(*before), q1 = measureSdfQuality(*after);
    std::cout << "| |grad phi| - 1 |: before mean " << q0.meanError << " max " << q0.maxError << " (" << q0.voxels
              << " voxels), after mean " << q1.meanError << " max " << q1.maxError << " (" << q1.voxels << ")\n";
    EXPECT_LT(q1.meanError, q0.meanError);
    EXPECT_LT(q1.meanError, 0.1);
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        const auto serial = sampleLevelSet(field, options);
        EXPECT_EQ(compareIn(*serial, *after, after->evalActiveVoxelBoundingBox()), 0u);
    }
}

TEST(SampleRegions, NeighbouringVoxelsDifferByNoMoreThanTheGradientBoundAllows)
{
    const DensityFieldPtr field = sceneTree(7);
    const double h = 0.5;
    const auto grid = sampleLevelSet(*field, box({-32, -30, -32}, {32, 30, 32}, h));
    const double allowed = std::max(1.0, field->lipschitz()) * h * (1.0 + 1e-4) + 1e-5; // float storage
    auto acc = grid->getConstAccessor();
    std::size_t checked = 0;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        for (const openvdb::Coord& step : {openvdb::Coord(1, 0, 0), openvdb::Coord(0, 1, 0), openvdb::Coord(0, 0, 1)}) {
            float next = 0.0f;
            if (!acc.probeValue(it.getCoord() + step, next)) continue;
            ASSERT_LE(std::abs(double(next) - double(*it)), allowed) << it.getCoord();
            ++checked;
        }
    }
    EXPECT_GT(checked, 100000u);
}
