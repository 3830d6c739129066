// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/Error.h>
#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/DifferentialErosion.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/SimdTarget.h>
#include <strata/terrain/TerrainField.h>
#include <strata/terrain/Transforms.h>

#include "DefaultSceneTree.h"

#include <tbb/global_control.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <tuple>
#include <vector>

using namespace strata::terrain;

namespace {

void expectError(const std::function<void()>& run, const std::string& key)
{
    try {
        run();
        ADD_FAILURE() << "no strata::Error for " << key;
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << "message: " << e.what();
    }
}

SampleOptions regionOptions(const glm::dvec3& min, const glm::dvec3& max, double voxelSize)
{
    SampleOptions options;
    options.voxelSize = voxelSize;
    options.region.min = min;
    options.region.max = max;
    return options;
}

/// A field that is the same everywhere (every voxel within the band).
class ConstantField final : public DensityField
{
public:
    explicit ConstantField(double value) : mValue(value) {}
    double density(const glm::dvec3&) const override { return mValue; }
    double lipschitz() const override { return 1.0; }

private:
    double mValue;
};

/// Checks every voxel of the region against the field evaluated directly:
/// active exactly where |d| < background (holding float(d)), otherwise
/// inactive ±background with the sign of d. With `closed`, d is the field
/// intersected with the region box, as documented.
void expectMatchesDenseSampling(const DensityField& field, const SampleOptions& options,
                                const openvdb::FloatGrid& grid)
{
    const double vs = options.voxelSize, background = options.halfWidth * vs;
    openvdb::Coord lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = int(std::ceil(options.region.min[a] / vs));
        hi[a] = int(std::ceil(options.region.max[a] / vs)) - 1;
    }
    const glm::dvec3 boxLo = glm::dvec3(lo.x(), lo.y(), lo.z()) * vs + 0.5 * vs;
    const glm::dvec3 boxHi = glm::dvec3(hi.x(), hi.y(), hi.z()) * vs - 0.5 * vs;
    const auto reference = [&](const glm::dvec3& p) {
        const double d = field.density(p);
        if (!options.closed) return d;
        const glm::dvec3 q = glm::abs(p - 0.5 * (boxLo + boxHi)) - 0.5 * (boxHi - boxLo);
        return std::max(d, glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0));
    };

    openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    std::uint64_t voxels = 0, active = 0, wrongSign = 0, wrongState = 0, wrongValue = 0;
    for (int i = lo.x(); i <= hi.x(); ++i)
        for (int j = lo.y(); j <= hi.y(); ++j)
            for (int k = lo.z(); k <= hi.z(); ++k) {
                const openvdb::Coord ijk(i, j, k);
                const double d = reference(glm::dvec3(i, j, k) * vs);
                const float v = acc.getValue(ijk);
                const bool on = acc.isValueOn(ijk);
                ++voxels;
                active += on;
                if ((v < 0.0f) != (d < 0.0)) ++wrongSign;
                // Pruning leaves a 1e-4 relative slack at the band's edge.
                const bool nearEdge = std::abs(std::abs(d) - background) < 1e-3 * background;
                if (on != (std::abs(d) < background) && !nearEdge) ++wrongState;
                if (on ? v != float(d) : std::abs(v) != float(background)) ++wrongValue;
            }
    EXPECT_EQ(wrongSign, 0u) << "of " << voxels << " voxels";
    EXPECT_EQ(wrongState, 0u) << "of " << voxels << " voxels";
    EXPECT_EQ(wrongValue, 0u) << "of " << voxels << " voxels";
    EXPECT_EQ(active, grid.activeVoxelCount());
}

/// Every leaf (origin, mask, values) and every tile (origin, level, value).
using Tile = std::tuple<openvdb::Coord, openvdb::Index, float, bool>;
std::vector<Tile> tilesOf(const openvdb::FloatTree& tree)
{
    std::vector<Tile> tiles;
    for (auto it = tree.cbeginValueAll(); it; ++it) {
        if (!it.isVoxelValue()) tiles.emplace_back(it.getCoord(), it.getDepth(), *it, it.isValueOn());
    }
    return tiles;
}

void expectBitwiseEqual(const openvdb::FloatGrid& a, const openvdb::FloatGrid& b)
{
    ASSERT_EQ(a.tree().leafCount(), b.tree().leafCount());
    ASSERT_EQ(a.activeVoxelCount(), b.activeVoxelCount());
    EXPECT_TRUE(a.tree().hasSameTopology(b.tree()));
    auto la = a.tree().cbeginLeaf();
    auto lb = b.tree().cbeginLeaf();
    for (; la && lb; ++la, ++lb) {
        ASSERT_EQ(la->origin(), lb->origin());
        ASSERT_TRUE(la->getValueMask() == lb->getValueMask()) << la->origin();
        ASSERT_EQ(std::memcmp(la->buffer().data(), lb->buffer().data(), sizeof(float) * la->SIZE), 0)
            << la->origin();
    }
    EXPECT_FALSE(la || lb);
    EXPECT_EQ(tilesOf(a.tree()), tilesOf(b.tree()));
    EXPECT_EQ(a.background(), b.background());
}

} // namespace

TEST(SampleLevelSet, SphereMatchesTheAnalyticDistance)
{
    const glm::dvec3 center(0.3, -0.2, 0.1);
    const double radius = 5.0;
    const SphereField sphere(center, radius);
    const SampleOptions options = regionOptions(glm::dvec3(-8.0), glm::dvec3(8.0), 0.25);
    SampleStats stats;
    const openvdb::FloatGrid::Ptr grid = sampleLevelSet(sphere, options, &stats);

    EXPECT_EQ(grid->getGridClass(), openvdb::GRID_LEVEL_SET);
    EXPECT_FLOAT_EQ(grid->background(), 0.75f);
    EXPECT_DOUBLE_EQ(grid->voxelSize()[0], 0.25);
    EXPECT_TRUE(grid->transform().isLinear());

    // Near the surface the values are the distance (float rounding only).
    ASSERT_GT(grid->activeVoxelCount(), 10000u);
    double worst = 0.0;
    for (auto it = grid->cbeginValueOn(); it; ++it) {
        const openvdb::Vec3d w = grid->indexToWorld(it.getCoord());
        worst = std::max(worst, std::abs(double(*it) - sphere.density({w.x(), w.y(), w.z()})));
        EXPECT_LT(std::abs(*it), 0.75f);
    }
    EXPECT_LT(worst, 1e-5);

    // Signs: the centre is inside, the corners outside.
    openvdb::FloatGrid::ConstAccessor acc = grid->getConstAccessor();
    EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(1, -1, 0)), -0.75f);
    EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(-31, -31, -31)), 0.75f);
    EXPECT_FLOAT_EQ(acc.getValue(openvdb::Coord(1000, 0, 0)), 0.75f); // outside the region
    EXPECT_EQ(stats.activeVoxels, grid->activeVoxelCount());
    EXPECT_GT(stats.tilesSkipped, 0u);
    EXPECT_LE(stats.tilesSkipped, stats.tilesVisited);
    EXPECT_EQ(stats.tilesVisited, 8u * 8u * 8u); // 64 voxels a side

    // And exactly what dense sampling would give, voxel by voxel.
    expectMatchesDenseSampling(sphere, options, *grid);
}

TEST(SampleLevelSet, TerrainMatchesDenseSamplingOpenAndClosed)
{
    // The region cuts through hills and tunnels and is not leaf-aligned:
    // the signs must still be right everywhere inside it.
    const TerrainField field(TerrainOptions{});
    for (const bool closed : {false, true}) {
        SampleOptions options = regionOptions({-30.3, -25.1, -20.7}, {33.9, 20.2, 27.6}, 0.5);
        options.closed = closed;
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(field, options);
        SCOPED_TRACE(closed ? "closed" : "open");
        expectMatchesDenseSampling(field, options, *grid);
        // Outside the region: background (air).
        EXPECT_EQ(grid->tree().getValue(openvdb::Coord(0, -200, 0)), 1.5f);
    }
}

TEST(SampleLevelSet, TerracedWarpedSceneMatchesDenseSamplingOpenAndClosed)
{
    // The default scene's tree (terraced hills, warped sideways, minus worm
    // tunnels): pruning 8³ tiles, 4³ and 2³ sub-blocks by interval bounds
    // must give exactly the dense result, voxel by voxel, and evaluate
    // little beyond the band (bounds() calls counted).
    const DensityFieldPtr tree = strata::test::defaultSceneTree(true);
    const DensityField& field = *tree;
    for (const bool closed : {false, true}) {
        SampleOptions options = regionOptions({-22.3, -25.1, -18.7}, {21.9, 19.2, 23.6}, 0.5);
        options.closed = closed;
        SampleStats stats;
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(field, options, &stats);
        SCOPED_TRACE(closed ? "closed" : "open");
        expectMatchesDenseSampling(field, options, *grid);
        const double ratio = double(stats.evaluatedPoints) / double(stats.activeVoxels);
        std::cout << (closed ? "closed" : "open") << ": " << stats.activeVoxels << " active, "
                  << stats.evaluatedPoints << " evaluated (" << stats.boundEvaluations << " bounds), ratio " << ratio
                  << "\n";
        EXPECT_GT(stats.activeVoxels, 50000u);
        EXPECT_LT(ratio, 3.5); // 3.1: mixed 4³ blocks are evaluated whole (SUB_DIMS)
    }
}

TEST(SampleLevelSet, RegionSelectsTheVoxelCentresInside)
{
    // Every voxel is in the band, so the active voxels are exactly the
    // voxel centres i·voxelSize in [min, max).
    const ConstantField field(0.1);
    for (const bool closed : {false, true}) {
        SampleOptions options = regionOptions({-1.0, 0.0, 0.26}, {1.0, 0.75, 3.0}, 0.5);
        options.closed = closed;
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(field, options);
        EXPECT_EQ(grid->evalActiveVoxelBoundingBox(), openvdb::CoordBBox({-2, 0, 1}, {1, 1, 5}));
        EXPECT_EQ(grid->activeVoxelCount(), 4u * 2u * 5u);
    }
}

TEST(SampleLevelSet, SolidRegionIsSignedAndClosedRegionIsCapped)
{
    // The whole region is deep inside a big sphere: nothing to evaluate.
    const SphereField solid(glm::dvec3(0.0), 250.0);
    SampleOptions options = regionOptions(glm::dvec3(-64.0), glm::dvec3(64.0), 0.5);
    options.closed = false;
    SampleStats stats;
    const openvdb::FloatGrid::Ptr open = sampleLevelSet(solid, options, &stats);
    EXPECT_EQ(open->activeVoxelCount(), 0u);
    EXPECT_EQ(open->tree().leafCount(), 0u);
    EXPECT_EQ(stats.tilesSkipped, stats.tilesVisited);
    EXPECT_LT(stats.evaluatedPoints, 100u);
    for (const openvdb::Coord ijk : {openvdb::Coord(0), openvdb::Coord(-128), openvdb::Coord(127, -128, 5)}) {
        EXPECT_EQ(open->tree().getValue(ijk), -1.5f) << ijk;
    }
    EXPECT_EQ(open->tree().getValue(openvdb::Coord(128, 0, 0)), 1.5f) << "outside the region";

    // Closed, the region's faces become the surface.
    options.closed = true;
    options.voxelSize = 1.0;
    const openvdb::FloatGrid::Ptr closed = sampleLevelSet(solid, options);
    EXPECT_GT(closed->activeVoxelCount(), 6u * 120u * 120u);
    expectMatchesDenseSampling(solid, options, *closed);
}

namespace {

/// The default scene's tree (terraced, warped, tunnelled: cliffs and
/// caves) cut into folded, faulted beds that retreat up to 4 m.
DensityFieldPtr bedsOverTheDefaultScene()
{
    LithologyOptions o;
    o.beds = {{3.0, 0.9}, {4.0, 0.1}, {1.5, 0.6}};
    o.dip = 8.0;
    o.dipDirection = 30.0;
    o.foldAmplitude = 3.0;
    o.foldWavelength = 40.0;
    o.faultThrow = 2.5;
    o.faultPoint = {5.0, 0.0, 0.0};
    o.faultStrike = 100.0;
    DifferentialErosionOptions d;
    d.retreat = 4.0;
    return std::make_shared<DifferentialErosionField>(strata::test::defaultSceneTree(true),
                                                      std::make_shared<Lithology>(3, o), d);
}

} // namespace

TEST(SampleLevelSet, BedsWithOverhangsAndCavesMatchDenseSampling)
{
    // Pruning by the beds' bounds() drops no band voxel: every voxel as
    // dense sampling gives it, open and closed.
    const DensityFieldPtr field = bedsOverTheDefaultScene();
    for (const bool closed : {false, true}) {
        SampleOptions options = regionOptions({-14.3, -17.1, -12.7}, {13.9, 11.2, 15.6}, 0.5);
        options.closed = closed;
        SampleStats stats;
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(*field, options, &stats);
        SCOPED_TRACE(closed ? "closed" : "open");
        EXPECT_GT(stats.activeVoxels, 15000u);
        expectMatchesDenseSampling(*field, options, *grid);
        std::cout << "beds " << (closed ? "closed" : "open") << ": " << stats.activeVoxels << " active, "
                  << double(stats.evaluatedPoints) / double(stats.activeVoxels) << " points per active voxel\n";
    }
}

TEST(SampleLevelSet, BedsAreTheSameBitsInAnyTilingThreadCountAndSimdTarget)
{
    // One open region against 2 × 2 and 3 × 3 tiles of it (every voxel of
    // each tile as the whole grid has it), and the whole on every SIMD target
    // and 1, 2 and 3 threads.
    const DensityFieldPtr field = bedsOverTheDefaultScene();
    const glm::dvec3 lo(-18.0, -20.0, -18.0), hi(18.0, 16.0, 18.0);
    const double vs = 0.5;
    const auto openRegion = [vs](const glm::dvec3& min, const glm::dvec3& max) {
        SampleOptions options = regionOptions(min, max, vs);
        options.closed = false; // tiles that share voxels give them the same values
        return options;
    };
    const openvdb::FloatGrid::Ptr whole = sampleLevelSet(*field, openRegion(lo, hi));
    ASSERT_GT(whole->activeVoxelCount(), 30000u);
    const openvdb::FloatGrid::ConstAccessor all = whole->getConstAccessor();
    for (const int split : {2, 3}) {
        for (int i = 0; i < split; ++i)
            for (int k = 0; k < split; ++k) {
                const double w = (hi.x - lo.x) / split;
                const glm::dvec3 tileLo(lo.x + i * w, lo.y, lo.z + k * w), tileHi(tileLo.x + w, hi.y, tileLo.z + w);
                const openvdb::FloatGrid::Ptr tile = sampleLevelSet(*field, openRegion(tileLo, tileHi));
                const openvdb::FloatGrid::ConstAccessor part = tile->getConstAccessor();
                std::uint64_t differing = 0, compared = 0;
                for (int x = int(std::ceil(tileLo.x / vs)); x < int(std::ceil(tileHi.x / vs)); ++x)
                    for (int y = int(std::ceil(tileLo.y / vs)); y < int(std::ceil(tileHi.y / vs)); ++y)
                        for (int z = int(std::ceil(tileLo.z / vs)); z < int(std::ceil(tileHi.z / vs)); ++z) {
                            const openvdb::Coord c(x, y, z);
                            ++compared;
                            const float a = all.getValue(c), b = part.getValue(c);
                            differing += std::memcmp(&a, &b, sizeof a) != 0 || all.isValueOn(c) != part.isValueOn(c);
                        }
                EXPECT_EQ(differing, 0u) << split << " x " << split << " tile " << i << ", " << k << " of " << compared;
            }
    }
    const std::vector<std::string> targets = availableSimdTargets();
    for (const std::string& target : targets) {
        useSimdTarget(target);
        for (const int threads : {1, 2, 3}) {
            if (target != targets.front() && threads != 2) continue;
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            SCOPED_TRACE(target + ", " + std::to_string(threads) + " threads");
            expectBitwiseEqual(*whole, *sampleLevelSet(*field, openRegion(lo, hi)));
        }
    }
    useSimdTarget("");
}

TEST(SampleLevelSet, SameBitsOnOneThreadAndMany)
{
    const TerrainField field(TerrainOptions{});
    const SampleOptions options = regionOptions({-48.0, -40.0, -40.0}, {40.0, 40.0, 48.0}, 0.5);
    SampleStats many, one;
    const openvdb::FloatGrid::Ptr parallel = sampleLevelSet(field, options, &many);
    openvdb::FloatGrid::Ptr serial;
    {
        tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
        serial = sampleLevelSet(field, options, &one);
    }
    ASSERT_GT(parallel->activeVoxelCount(), 100000u);
    expectBitwiseEqual(*parallel, *serial);
    EXPECT_EQ(many.evaluatedPoints, one.evaluatedPoints);
    EXPECT_EQ(many.tilesSkipped, one.tilesSkipped);
}

TEST(SampleLevelSet, SameBitsOnEverySimdTargetAndThreadCount)
{
    // The default scene's tree (terraces, warp, worm caves) over a corner of
    // the scene, on each instruction set the machine has and on 1, 2 and 3
    // threads: one grid, bit for bit.
    const auto field = strata::test::defaultSceneTree(true);
    const SampleOptions options = regionOptions({-96.0, -40.0, -96.0}, {-40.0, 40.0, -40.0}, 0.5);
    openvdb::FloatGrid::Ptr reference;
    const std::vector<std::string> targets = availableSimdTargets();
    for (const std::string& target : targets) {
        useSimdTarget(target);
        for (const int threads : {1, 2, 3}) {
            if (target != targets.front() && threads != 2) continue; // thread counts: on the best target
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
            const openvdb::FloatGrid::Ptr grid = sampleLevelSet(*field, options);
            SCOPED_TRACE(target + ", " + std::to_string(threads) + " threads");
            if (!reference) {
                reference = grid;
                ASSERT_GT(grid->activeVoxelCount(), 100000u);
            } else {
                expectBitwiseEqual(*reference, *grid);
            }
        }
    }
    useSimdTarget("");
}

TEST(SampleLevelSet, PruningKeepsTheDefaultSceneCheap)
{
    // The default scene: x, z in [−96, 96], y in [−40, 40], voxel 0.5 m.
    const SampleOptions options = regionOptions({-96.0, -40.0, -96.0}, {96.0, 40.0, 96.0}, 0.5);
    const double dense = 384.0 * 160.0 * 384.0;
    for (const bool caves : {false, true}) {
        TerrainOptions terrain;
        terrain.caves.enabled = caves;
        const TerrainField field(terrain);
        SampleStats stats;
        const auto start = std::chrono::steady_clock::now();
        const openvdb::FloatGrid::Ptr grid = sampleLevelSet(field, options, &stats);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::cout << "default scene, caves " << (caves ? "on" : "off") << ": " << seconds << " s, "
                  << stats.evaluatedPoints << " evaluated (" << 100.0 * stats.evaluatedPoints / dense
                  << "% of dense), " << stats.activeVoxels << " active, evaluated/active "
                  << double(stats.evaluatedPoints) / double(stats.activeVoxels) << ", tiles skipped "
                  << stats.tilesSkipped << "/" << stats.tilesVisited << ", memUsage " << grid->memUsage() / 1024
                  << " KiB\n";
        EXPECT_EQ(stats.activeVoxels, grid->activeVoxelCount());
        // Pruning evaluates little beyond the band itself (1.9 and 1.3 times
        // the active voxels: mixed 4³ blocks are evaluated whole)...
        EXPECT_LT(double(stats.evaluatedPoints), 2.2 * double(stats.activeVoxels));
        // ... and the band is thin for the heightfield alone. The cave term's
        // gradient bound is loose (about tenfold, see CaveOptions), which
        // widens the band around tunnels: more of the volume is evaluated.
        EXPECT_LT(double(stats.evaluatedPoints), (caves ? 0.75 : 0.35) * dense);
    }
}

TEST(SampleLevelSet, ReportsProgressAndStopsWhenAsked)
{
    const SphereField sphere(glm::dvec3(0.0), 20.0);
    SampleOptions options = regionOptions(glm::dvec3(-24.0), glm::dvec3(24.0), 0.25);
    std::vector<double> fractions;
    options.progress = [&fractions](double f) {
        fractions.push_back(f);
        return true;
    };
    sampleLevelSet(sphere, options);
    ASSERT_GE(fractions.size(), 3u);
    EXPECT_EQ(fractions.front(), 0.0);
    EXPECT_EQ(fractions.back(), 1.0);
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));

    int calls = 0;
    options.progress = [&calls](double) { return ++calls < 3; };
    expectError([&] { sampleLevelSet(sphere, options); }, "sampling interrupted");
    EXPECT_EQ(calls, 3);
}

TEST(SampleLevelSet, BadOptionsThrowNamingTheKey)
{
    const SphereField sphere(glm::dvec3(0.0), 2.0);
    const auto run = [&sphere](auto edit) {
        return [&sphere, edit]() {
            SampleOptions o = regionOptions(glm::dvec3(-4.0), glm::dvec3(4.0), 0.5);
            edit(o);
            sampleLevelSet(sphere, o);
        };
    };
    expectError(run([](SampleOptions& o) { o.voxelSize = 0.0; }), "voxel_size = 0 must be a finite number > 0");
    expectError(run([](SampleOptions& o) { o.voxelSize = -1.0; }), "voxel_size = -1");
    expectError(run([](SampleOptions& o) { o.voxelSize = std::nan(""); }), "voxel_size = nan");
    expectError(run([](SampleOptions& o) { o.voxelSize = INFINITY; }), "voxel_size = inf");
    expectError(run([](SampleOptions& o) { o.halfWidth = 1; }), "half_width = 1 is out of range 3..64");
    expectError(run([](SampleOptions& o) { o.halfWidth = 1000; }), "half_width = 1000");
    expectError(run([](SampleOptions& o) { o.region.max.y = o.region.min.y; }), "region is empty: max.y");
    expectError(run([](SampleOptions& o) { o.region.max.x = -10.0; }), "region is empty: max.x");
    expectError(run([](SampleOptions& o) { o.region.min.z = std::nan(""); }), "region min.z");
    expectError(run([](SampleOptions& o) { o.region.max = glm::dvec3(0.1); o.region.min = glm::dvec3(0.05); }),
                "holds no voxel centre");
    expectError(run([](SampleOptions& o) { o.region.max.x = 1e12; }), "too far out");
    expectError(run([](SampleOptions& o) { o.region.min = glm::dvec3(-1e5); o.region.max = glm::dvec3(1e5); }),
                "more than the limit");
}
