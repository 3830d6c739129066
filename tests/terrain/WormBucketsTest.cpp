// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Worm buckets are built a region of them at a time (one pass over the
// cells within reach). These tests hold them to the rule a bucket had when
// it was built on its own: the same segments in the same order, so the same
// density bits.

#include <strata/terrain/Caves.h>
#include <strata/terrain/Noise.h>

#include "NoiseHash.h"
#include "WormCavesInspector.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <vector>

using namespace strata::terrain;

namespace {

using detail::WormCavesInspector;
using Segment = WormCavesInspector::Segment;
using Key = WormCavesInspector::Key;

double reachOf(const WormOptions& o)
{
    return o.segments * o.segmentLength + o.radius * (1.0 + o.radiusVariation);
}

std::int64_t saturated(double floorX)
{
    constexpr double LIMIT = 4611686018427387904.0; // 2^62, as detail::latticeIndex
    if (std::abs(floorX) < LIMIT) return std::int64_t(floorX);
    return floorX > 0.0 ? std::int64_t(LIMIT) : -std::int64_t(LIMIT);
}

/// The per-bucket rule, as it was before regions: every segment of the
/// cells within reach + CAP (cx outer, cz inner), kept when its box comes
/// within CAP of the bucket's box.
std::vector<Segment> perBucketRule(const WormCaves& worms, const WormOptions& o, const Key& key)
{
    const double CAP = WormCaves::CAP, SIZE = WormCaves::BUCKET_SIZE;
    const glm::dvec3 lo = SIZE * glm::dvec3(double(key[0]), double(key[1]), double(key[2]));
    const glm::dvec3 hi = lo + SIZE;
    std::vector<Segment> kept;
    const double margin = reachOf(o) + CAP;
    if (!(hi.y > o.minY - margin && lo.y < o.maxY + margin)) return kept;
    const auto cellOf = [&](double v) { return saturated(std::floor(v / o.cellSize)); };
    for (std::int64_t cx = cellOf(lo.x - margin); cx <= cellOf(hi.x + margin); ++cx)
        for (std::int64_t cz = cellOf(lo.z - margin); cz <= cellOf(hi.z + margin); ++cz)
            for (const Segment& s : WormCavesInspector::wormsOfCell(worms, cx, cz)) {
                const double r = std::max(s.ra, s.rb);
                const glm::dvec3 smin = glm::min(s.a, s.b) - r, smax = glm::max(s.a, s.b) + r;
                const glm::dvec3 gap = glm::max(glm::max(smin - hi, lo - smax), 0.0);
                if (glm::length(gap) < CAP) kept.push_back(s);
            }
    return kept;
}

/// distanceAmong() over the rule's segments, in their order (the bucket's
/// mid and reach as WormCaves computes them).
double referenceDensity(const std::vector<Segment>& segments, const glm::dvec3& p)
{
    double d = WormCaves::CAP;
    for (const Segment& s : segments) {
        const glm::dvec3 mid = 0.5 * (s.a + s.b);
        const double reach = 0.5 * glm::length(s.b - s.a) + std::max(s.ra, s.rb);
        const glm::dvec3 v = p - mid;
        const double far = d + reach;
        if (glm::dot(v, v) >= far * far) continue;
        d = std::min(d, roundConeDistance(p, s.a, s.b, s.ra, s.rb));
    }
    return d;
}

bool sameBits(double a, double b)
{
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool sameSegment(const Segment& a, const Segment& b)
{
    return sameBits(a.a.x, b.a.x) && sameBits(a.a.y, b.a.y) && sameBits(a.a.z, b.a.z) && sameBits(a.b.x, b.b.x) &&
           sameBits(a.b.y, b.b.y) && sameBits(a.b.z, b.b.z) && sameBits(a.ra, b.ra) && sameBits(a.rb, b.rb);
}

struct Stats
{
    std::size_t buckets = 0, nonEmpty = 0, segments = 0, points = 0, inside = 0;
};

/// Every bucket of the box of keys [from, from + size) against the rule, and
/// densities at points inside each (density() and the block path).
void checkBuckets(const WormCaves& worms, const WormOptions& o, const Key& from, const Key& size, Stats& stats,
                  std::uint64_t seed)
{
    std::uint64_t state = seed;
    const auto unit = [&state]() {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(state >> 11) * 0x1.0p-53;
    };
    for (std::int64_t i = 0; i < size[0]; ++i)
        for (std::int64_t j = 0; j < size[1]; ++j)
            for (std::int64_t k = 0; k < size[2]; ++k) {
                const Key key{from[0] + i, from[1] + j, from[2] + k};
                const std::vector<Segment> expected = perBucketRule(worms, o, key);
                const std::vector<Segment> got = WormCavesInspector::bucketSegments(worms, key);
                ++stats.buckets;
                stats.nonEmpty += !expected.empty();
                stats.segments += expected.size();
                ASSERT_EQ(got.size(), expected.size()) << "bucket " << key[0] << " " << key[1] << " " << key[2];
                for (std::size_t n = 0; n < got.size(); ++n)
                    ASSERT_TRUE(sameSegment(got[n], expected[n]))
                        << "bucket " << key[0] << " " << key[1] << " " << key[2] << ", segment " << n;
                // Points inside the bucket (lo + [0.001, 7.999] m per axis).
                const glm::dvec3 lo = WormCaves::BUCKET_SIZE * glm::dvec3(double(key[0]), double(key[1]), double(key[2]));
                constexpr std::size_t N = 24;
                double x[N], y[N], z[N], out[N];
                for (std::size_t n = 0; n < N; ++n) {
                    x[n] = lo.x + 0.001 + 7.998 * unit();
                    y[n] = lo.y + 0.001 + 7.998 * unit();
                    z[n] = lo.z + 0.001 + 7.998 * unit();
                }
                PointBlock block{x, y, z, N, {}};
                block.box = spannedBox(block);
                worms.densities(block, out);
                for (std::size_t n = 0; n < N; ++n) {
                    const glm::dvec3 p(x[n], y[n], z[n]);
                    const double want = referenceDensity(expected, p);
                    ASSERT_TRUE(sameBits(worms.density(p), want)) << p.x << " " << p.y << " " << p.z;
                    ASSERT_TRUE(sameBits(out[n], want)) << "block path at " << p.x << " " << p.y << " " << p.z;
                    ++stats.points;
                    stats.inside += want < 0.0;
                }
            }
}

Key bucketOf(double x, double y, double z)
{
    const double s = WormCaves::BUCKET_SIZE;
    return {saturated(std::floor(x / s)), saturated(std::floor(y / s)), saturated(std::floor(z / s))};
}

} // namespace

TEST(WormBuckets, RegionsHoldTheSegmentsOfThePerBucketRuleInItsOrder)
{
    WormOptions world4k; // examples/worlds/world4k.toml's tunnels
    world4k.wormsPerCell = 3.0;
    world4k.minY = -24.0;
    world4k.maxY = 8.0;
    world4k.radius = 3.2;
    WormOptions smallCells; // many cells per bucket: each bucket's own cell range matters
    smallCells.cellSize = 5.0;
    smallCells.wormsPerCell = 0.3;
    smallCells.segments = 6;
    for (const WormOptions& o : {WormOptions{}, world4k, smallCells}) {
        const WormCaves worms(17, o);
        Stats stats;
        const double margin = reachOf(o) + WormCaves::CAP;
        // Around the origin, across region borders (regions are 4³ buckets).
        checkBuckets(worms, o, bucketOf(-20.0, -30.0, -28.0), {6, 6, 6}, stats, 1);
        // Far from the origin: 1e7 m and 2^30 m.
        checkBuckets(worms, o, bucketOf(1e7 - 12.0, -10.0, -1e7 - 20.0), {5, 3, 5}, stats, 2);
        checkBuckets(worms, o, bucketOf(0x1.0p30, -20.0, 0x1.0p30 - 8.0), {5, 4, 3}, stats, 3);
        // Where the y range ends, on both sides of the last buckets that
        // can hold a segment.
        checkBuckets(worms, o, bucketOf(-30.0, o.minY - margin - 24.0, 40.0), {5, 6, 3}, stats, 4);
        checkBuckets(worms, o, bucketOf(-30.0, o.maxY + margin - 24.0, 40.0), {3, 6, 5}, stats, 5);
        // Far enough that 8 m buckets collapse in doubles (every bucket of
        // a region is tested there): the rule holds too.
        checkBuckets(worms, o, bucketOf(1e18, -8.0, -1e18), {3, 2, 3}, stats, 6);
        std::cout << "cell " << o.cellSize << " m: " << stats.buckets << " buckets (" << stats.nonEmpty
                  << " with segments, " << stats.segments << " segments), " << stats.points << " points, "
                  << stats.inside << " inside a tunnel\n";
        EXPECT_GT(stats.nonEmpty, stats.buckets / 4) << "the regions should hold tunnels";
        EXPECT_GT(stats.inside, 0u) << "some points should fall inside a tunnel";
    }
}

TEST(WormBuckets, TheSameBitsFromAnyRegionOrder)
{
    // Buckets visited in a different order (other regions first, the cache
    // emptied in between) hold the same segments.
    WormOptions o;
    o.wormsPerCell = 2.0;
    const WormCaves forward(5, o), backward(5, o);
    std::vector<Key> keys;
    for (std::int64_t i = -9; i < 9; ++i)
        for (std::int64_t j = -4; j < 1; ++j)
            for (std::int64_t k = -9; k < 9; k += 3) keys.push_back({i, j, k});
    std::vector<std::vector<Segment>> first;
    for (const Key& key : keys) first.push_back(WormCavesInspector::bucketSegments(forward, key));
    for (std::size_t n = keys.size(); n-- > 0;) {
        const std::vector<Segment> got = WormCavesInspector::bucketSegments(backward, keys[n]);
        ASSERT_EQ(got.size(), first[n].size());
        for (std::size_t m = 0; m < got.size(); ++m) ASSERT_TRUE(sameSegment(got[m], first[n][m]));
    }
}

TEST(WormBuckets, WormStartsDrawTheirCoordinatesInAFixedOrder)
{
    // The start of a worm takes three draws from its hash stream: z, then
    // y, then x. They were once the three arguments of one constructor, so
    // their order was the compiler's and clang built other worlds than gcc
    // (issue 39). The start is recomputed here from the stream itself.
    const std::uint64_t seed = 77;
    WormOptions options;
    options.wormsPerCell = 1.0;
    const WormCaves worms(seed, options);
    const std::uint64_t step = 0x9e3779b97f4a7c15ULL;
    const auto unit = [](std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; };
    int checked = 0;
    for (const std::int64_t cx : {-3, 0, 5})
        for (const std::int64_t cz : {-1, 2}) {
            const std::vector<Segment> segments = WormCavesInspector::wormsOfCell(worms, cx, cz);
            ASSERT_EQ(segments.size(), std::size_t(options.segments)) << "one worm per cell";
            const std::uint64_t cell =
                strata::terrain::detail::hashCombine(
                    strata::terrain::detail::hashCombine(strata::terrain::detail::seedHash(deriveSeed(seed, 5)), cx), cz);
            std::uint64_t h = strata::terrain::detail::mix64(cell + step);
            double draws[3];
            for (double& d : draws) {
                h = strata::terrain::detail::mix64(h + step);
                d = unit(h);
            }
            const glm::dvec3 expected((double(cx) + draws[2]) * options.cellSize,
                                      options.minY + draws[1] * (options.maxY - options.minY),
                                      (double(cz) + draws[0]) * options.cellSize);
            EXPECT_EQ(segments.front().a.x, expected.x) << cx << ", " << cz;
            EXPECT_EQ(segments.front().a.y, expected.y) << cx << ", " << cz;
            EXPECT_EQ(segments.front().a.z, expected.z) << cx << ", " << cz;
            ++checked;
        }
    EXPECT_EQ(checked, 6);
}
