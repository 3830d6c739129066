// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Caves.h>

#include <strata/ByteBoundedCache.h>

#include "WormSimd.h"

#include "NodeRegistrations.h"
#include <strata/Format.h>
#include <strata/terrain/NodeRegistry.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include "NoiseHash.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <map>
#include <mutex>

namespace strata::terrain {

namespace {

using namespace detail;

void requirePositive(const char* key, double v)
{
    if (!(std::isfinite(v) && v > 0.0)) throw Error(ErrorKind::BadInput, std::string(key) + " = " + show(v) + " must be a finite number > 0");
}

void requireRange(const char* key, double v, double lo, double hi)
{
    if (!(std::isfinite(v) && v >= lo && v <= hi)) {
        throw Error(ErrorKind::BadInput, std::string(key) + " = " + show(v) + " is out of range [" + show(lo) + ", " + show(hi) + "]");
    }
}

/// Typical |∇n| across a spaghetti tunnel, per noise unit (calibrated in
/// TerrainField: the mean horizontal radius then matches `radius`).
constexpr double SPAGHETTI_TYPICAL_GRADIENT = 1.0;
/// Cheese: the typical gradient of a fractal field is about a third of its bound.
constexpr double CHEESE_TYPICAL_FRACTION = 1.0 / 3.0;

inline double unit(std::uint64_t h)
{
    return double(h >> 11) * 0x1.0p-53;
}

} // namespace

// ---- spaghetti ---------------------------------------------------------------

SpaghettiCaves::SpaghettiCaves(std::uint64_t seed, const SpaghettiOptions& options)
    : mOptions(options), mA(deriveSeed(seed, 2), options.noise), mB(deriveSeed(seed, 3), options.noise)
{
    requirePositive("wavelength", options.wavelength);
    requirePositive("radius", options.radius);
    requirePositive("vertical_squash", options.verticalSquash);
    if (std::isnan(options.maxHeight)) throw Error(ErrorKind::BadInput, "max_height = nan must be a number");
    mNoiseRadius = options.radius * SPAGHETTI_TYPICAL_GRADIENT / options.wavelength;
    mGain = options.wavelength / SPAGHETTI_TYPICAL_GRADIENT; // metres per noise unit
    // |∇ tube| <= √2·L_n·max(1, squash) / wavelength per metre.
    const double tubeSlope = std::sqrt(2.0) * mA.lipschitz(3) * std::max(1.0, options.verticalSquash) / options.wavelength;
    mLipschitz = std::max(1.0, tubeSlope * mGain);
}

double SpaghettiCaves::tube(const glm::dvec3& p) const
{
    const glm::dvec3 q(p.x / mOptions.wavelength, p.y * mOptions.verticalSquash / mOptions.wavelength,
                       p.z / mOptions.wavelength);
    const double n1 = mA(q), n2 = mB(q);
    return std::sqrt(n1 * n1 + n2 * n2) - mNoiseRadius;
}

double SpaghettiCaves::density(const glm::dvec3& p) const
{
    return std::max(tube(p) * mGain, p.y - mOptions.maxHeight);
}

double SpaghettiCaves::distanceBound(const glm::dvec3& p) const
{
    return std::max(tube(p) * mGain / mLipschitz, p.y - mOptions.maxHeight);
}

// ---- cheese ------------------------------------------------------------------

CheeseCaves::CheeseCaves(std::uint64_t seed, const CheeseOptions& options)
    : mOptions(options), mNoise(deriveSeed(seed, 4), options.noise)
{
    requirePositive("wavelength", options.wavelength);
    requireRange("threshold", options.threshold, -2.0, 2.0);
    requirePositive("vertical_squash", options.verticalSquash);
    if (std::isnan(options.maxHeight)) throw Error(ErrorKind::BadInput, "max_height = nan must be a number");
    const double slope = mNoise.lipschitz(3) * std::max(1.0, options.verticalSquash) / options.wavelength;
    mBoundScale = 1.0 / slope;
    mScale = mBoundScale / CHEESE_TYPICAL_FRACTION;
    mLipschitz = 1.0 / CHEESE_TYPICAL_FRACTION;
}

double CheeseCaves::excess(const glm::dvec3& p) const
{
    const glm::dvec3 q(p.x / mOptions.wavelength, p.y * mOptions.verticalSquash / mOptions.wavelength,
                       p.z / mOptions.wavelength);
    const double n = mNoise(q);
    return mOptions.invert ? n - mOptions.threshold : mOptions.threshold - n;
}

double CheeseCaves::density(const glm::dvec3& p) const
{
    return std::max(excess(p) * mScale, p.y - mOptions.maxHeight);
}

double CheeseCaves::distanceBound(const glm::dvec3& p) const
{
    return std::max(excess(p) * mBoundScale, p.y - mOptions.maxHeight);
}

// ---- worms -------------------------------------------------------------------

double roundConeDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, double ra, double rb)
{
    const glm::dvec3 v = b - a, w = p - a;
    const double len2 = glm::dot(v, v);
    const double len = std::sqrt(len2);
    const double slope = len > 0.0 ? (rb - ra) / len : 2.0;
    if (!(std::abs(slope) < 1.0)) {
        // One end sphere contains the whole cone.
        return std::min(glm::length(w) - ra, glm::length(p - b) - rb);
    }
    const double along = glm::dot(w, v) / len; // metres from a along the axis
    const double h = glm::length(w - (along / len) * v);
    // Minimise g(u) = √(h² + u²) − slope·u over the axis offset u from the
    // foot of the perpendicular: u = slope·h/√(1 − slope²); g is convex, so
    // clamping to the segment gives the minimum over it.
    const double u = slope * h / std::sqrt(1.0 - slope * slope);
    const double t = std::clamp((along + u) / len, 0.0, 1.0);
    return glm::length(p - (a + t * v)) - (ra + t * (rb - ra));
}

namespace {

constexpr double BUCKET_SIZE = WormCaves::BUCKET_SIZE;
std::atomic<std::uint64_t> gNextWormId{1};

/// Per thread, the last few buckets used, direct-mapped by key: the sampler
/// and the bounds pass hop between neighbouring buckets, and the shared
/// cache costs a lock per miss.
struct WormThreadCache
{
    static constexpr std::size_t SLOTS = 16;
    struct Slot
    {
        std::uint64_t id = 0;
        std::array<std::int64_t, 3> key{};
        std::shared_ptr<const void> bucket;
    };
    Slot slots[SLOTS];
    Slot& slotFor(const std::array<std::int64_t, 3>& key)
    {
        const std::uint64_t h = std::uint64_t(key[0]) * 0x9e3779b97f4a7c15ULL ^ std::uint64_t(key[1]) * 0xbf58476d1ce4e5b9ULL ^
                                std::uint64_t(key[2]) * 0x94d049bb133111ebULL;
        return slots[(h >> 40) % SLOTS];
    }
};
thread_local WormThreadCache tWormCache;

/// Smooth 1D noise along a worm: 2D gradient noise on a line off the lattice.
inline double wander(std::uint64_t hashedSeed, double t)
{
    return noise2(hashedSeed, glm::dvec2(t, 0.37));
}

/// A key's shard in the worm caches (ShardedByteBoundedCache).
struct ShardOfKey
{
    template <std::size_t N>
    std::size_t operator()(const std::array<std::int64_t, N>& key) const
    {
        std::uint64_t h = 0x2545f4914f6cdd1dULL;
        for (const std::int64_t k : key) h = hashCombine(h, k);
        return std::size_t(mix64(h));
    }
};

} // namespace

struct WormCaves::Cache
{
    ShardedByteBoundedCache<Key, Region, 16, ShardOfKey> regions{REGION_CACHE_BYTES};
    ShardedByteBoundedCache<std::array<std::int64_t, 2>, std::vector<Segment>, 64, ShardOfKey> cells{CELL_CACHE_BYTES};
};

WormCaves::WormCaves(std::uint64_t seed, const WormOptions& options)
    : mSeed(seed), mOptions(options), mId(gNextWormId.fetch_add(1)), mCache(std::make_unique<Cache>())
{
    requirePositive("cell_size", options.cellSize);
    requireRange("worms_per_cell", options.wormsPerCell, 0.0, 16.0);
    if (!(std::isfinite(options.minY) && std::isfinite(options.maxY) && options.maxY >= options.minY)) {
        throw Error(ErrorKind::BadInput, "max_y = " + show(options.maxY) + " must be a finite number >= min_y = " + show(options.minY));
    }
    requireRange("segments", options.segments, 1, 256);
    requirePositive("segment_length", options.segmentLength);
    requirePositive("radius", options.radius);
    requireRange("radius_variation", options.radiusVariation, 0.0, 0.9);
    requireRange("turn", options.turn, 0.0, 10.0);
    requireRange("max_pitch", options.maxPitch, 0.0, 1.4);
    mReach = options.segments * options.segmentLength + options.radius * (1.0 + options.radiusVariation);
    if (mReach > 4096.0) throw Error(ErrorKind::BadInput, "segments × segment_length = " + show(mReach) + " m is too long (4096 m at most)");
}

WormCaves::~WormCaves() = default;

std::vector<WormCaves::Segment> WormCaves::wormsOfCell(std::int64_t cx, std::int64_t cz) const
{
    const WormOptions& o = mOptions;
    const std::uint64_t cell = hashCombine(hashCombine(seedHash(deriveSeed(mSeed, 5)), cx), cz);
    const double expected = o.wormsPerCell;
    const int count = floorToInt<int>(expected) + (unit(mix64(cell ^ 0x51)) < expected - std::floor(expected) ? 1 : 0);
    std::vector<Segment> segments;
    for (int w = 0; w < count; ++w) {
        std::uint64_t h = mix64(cell + 0x9e3779b97f4a7c15ULL * std::uint64_t(w + 1));
        const auto next = [&h]() {
            h = mix64(h + 0x9e3779b97f4a7c15ULL);
            return unit(h);
        };
        // One draw a statement: as arguments of one call their order would
        // be the compiler's (gcc drew z first, clang x). This is gcc's order,
        // so the worlds gcc built keep their bytes.
        const double startZ = next();
        const double startY = next();
        const double startX = next();
        glm::dvec3 at((double(cx) + startX) * o.cellSize, o.minY + startY * (o.maxY - o.minY),
                      (double(cz) + startZ) * o.cellSize);
        const double yaw0 = 6.283185307179586 * next();
        const std::uint64_t yawSeed = mix64(h ^ 1), pitchSeed = mix64(h ^ 2), radiusSeed = mix64(h ^ 3);
        const auto radiusAt = [&](int i) {
            return o.radius * (1.0 + o.radiusVariation * std::clamp(1.5 * wander(radiusSeed, 0.21 * i), -1.0, 1.0));
        };
        double ra = radiusAt(0);
        for (int i = 0; i < o.segments; ++i) {
            const double t = 0.13 * (i + 0.5);
            const double yaw = yaw0 + 2.0 * o.turn * wander(yawSeed, t);
            const double pitch = o.maxPitch * std::clamp(1.6 * wander(pitchSeed, t), -1.0, 1.0);
            double sinPitch = 0.0, cosPitch = 1.0, sinYaw = 0.0, cosYaw = 1.0;
            dmath::sinCos(pitch, sinPitch, cosPitch);
            dmath::sinCos(yaw, sinYaw, cosYaw);
            const glm::dvec3 dir(cosPitch * cosYaw, sinPitch, cosPitch * sinYaw);
            const glm::dvec3 to = at + o.segmentLength * dir;
            const double rb = radiusAt(i + 1);
            segments.push_back({at, to, ra, rb});
            at = to;
            ra = rb;
        }
    }
    return segments;
}

std::shared_ptr<const std::vector<WormCaves::Segment>> WormCaves::cell(std::int64_t cx, std::int64_t cz) const
{
    const std::array<std::int64_t, 2> key{cx, cz};
    if (auto found = mCache->cells.find(key)) return found;
    auto segments = std::make_shared<const std::vector<Segment>>(wormsOfCell(cx, cz));
    return mCache->cells.insert(key, segments, sizeof(*segments) + segments->capacity() * sizeof(Segment));
}

std::uint64_t WormCaves::cacheBytes() const
{
    return mCache->regions.stats().bytes + mCache->cells.stats().bytes;
}

std::vector<WormCaves::Segment> WormCaves::bucketSegments(const Key& key) const
{
    std::vector<Segment> segments;
    for (const Cone& c : *bucket(key)) segments.push_back(c.s);
    return segments;
}

namespace {

/// floor(v / BUCKET_SIZE) − first: the bucket of coordinate v counted from
/// a region's first bucket along one axis, clamped to [lo, hi] (so the
/// conversion is defined; NaN gives lo).
int clampedOffset(double v, double first, int lo, int hi)
{
    const double t = std::floor(v / BUCKET_SIZE) - first;
    if (!(t > double(lo))) return lo; // also NaN
    if (!(t < double(hi))) return hi;
    return int(t);
}

} // namespace

struct WormCaves::Region
{
    std::array<Bucket, REGION_BUCKETS> buckets; ///< x-major: (i·R + j)·R + k for bucket offsets (i, j, k)
};

std::shared_ptr<const WormCaves::Bucket> WormCaves::bucket(const Key& key) const
{
    constexpr std::int64_t MASK = REGION_SIDE - 1;
    const std::shared_ptr<const Region> built = region({key[0] >> REGION_SHIFT, key[1] >> REGION_SHIFT, key[2] >> REGION_SHIFT});
    const Bucket& b = built->buckets[std::size_t(((key[0] & MASK) * REGION_SIDE + (key[1] & MASK)) * REGION_SIDE + (key[2] & MASK))];
    return std::shared_ptr<const Bucket>(built, &b); // shares the region's ownership
}

std::shared_ptr<const WormCaves::Region> WormCaves::region(const Key& regionKey) const
{
    if (auto found = mCache->regions.find(regionKey)) return found;
    // Build outside the lock (two threads may build the same region; both
    // get the same contents, whichever is stored).
    //
    // Each bucket gets exactly the segments, in exactly the order, of the
    // rule a bucket had when it was built on its own (every segment of the
    // cells within reach + CAP, cx outer and cz inner, kept when its box
    // comes within CAP of the bucket's): the cells of the whole region are
    // walked once in that order, and each segment is appended to every
    // bucket of the region that the same per-bucket tests accept (the same
    // y range, the same cell range, the same box distance, computed with
    // the same expressions). So densities keep their bits.
    auto region = std::make_shared<Region>();
    const double margin = mReach + CAP;
    // Saturating (detail::latticeIndex): a bucket beyond ±2^62 cells converts without undefined behaviour.
    const auto cellOf = [&](double v) { return detail::latticeIndex(std::floor(v / mOptions.cellSize)); };
    struct Target
    {
        glm::dvec3 lo, hi;
        std::int64_t cx0, cx1, cz0, cz1;
        bool live;
    };
    std::array<Target, REGION_BUCKETS> targets;
    std::int64_t cx0 = 0, cx1 = -1, cz0 = 0, cz1 = -1;
    bool any = false;
    const Key first{regionKey[0] * REGION_SIDE, regionKey[1] * REGION_SIDE, regionKey[2] * REGION_SIDE};
    double extent = 0.0;
    for (int i = 0; i < REGION_SIDE; ++i)
        for (int j = 0; j < REGION_SIDE; ++j)
            for (int k = 0; k < REGION_SIDE; ++k) {
                Target& t = targets[std::size_t((i * REGION_SIDE + j) * REGION_SIDE + k)];
                t.lo = BUCKET_SIZE * glm::dvec3(static_cast<double>(first[0] + i), static_cast<double>(first[1] + j),
                                                static_cast<double>(first[2] + k));
                t.hi = t.lo + BUCKET_SIZE;
                t.live = t.hi.y > mOptions.minY - margin && t.lo.y < mOptions.maxY + margin;
                t.cx0 = cellOf(t.lo.x - margin);
                t.cx1 = cellOf(t.hi.x + margin);
                t.cz0 = cellOf(t.lo.z - margin);
                t.cz1 = cellOf(t.hi.z + margin);
                extent = std::max({extent, std::abs(t.lo.x), std::abs(t.lo.y), std::abs(t.lo.z), std::abs(t.hi.x),
                                   std::abs(t.hi.y), std::abs(t.hi.z)});
                if (!t.live) continue;
                cx0 = any ? std::min(cx0, t.cx0) : t.cx0;
                cx1 = any ? std::max(cx1, t.cx1) : t.cx1;
                cz0 = any ? std::min(cz0, t.cz0) : t.cz0;
                cz1 = any ? std::max(cz1, t.cz1) : t.cz1;
                any = true;
            }
    // Near enough to the origin that 8 m buckets are still 8 m apart in
    // doubles, a segment only looks at the buckets its padded box touches;
    // farther out, at every bucket of the region (the exact tests decide
    // either way).
    const bool narrow = extent < 0x1.0p40;
    const glm::dvec3 firstD(static_cast<double>(first[0]), static_cast<double>(first[1]), static_cast<double>(first[2]));
    // The region's box grown by CAP and a metre (far more than the rounding
    // there): a segment whose box misses it comes within CAP of no bucket.
    const glm::dvec3 reachLo = targets.front().lo - (CAP + 1.0), reachHi = targets.back().hi + (CAP + 1.0);
    for (std::int64_t cx = cx0; any && cx <= cx1; ++cx) {
        for (std::int64_t cz = cz0; cz <= cz1; ++cz) {
            // Hold the cell while reading it: the cache may evict it meanwhile.
            const std::shared_ptr<const std::vector<Segment>> segments = cell(cx, cz);
            for (const Segment& s : *segments) {
                const double r = std::max(s.ra, s.rb);
                const glm::dvec3 smin = glm::min(s.a, s.b) - r, smax = glm::max(s.a, s.b) + r;
                int from[3] = {0, 0, 0}, to[3] = {REGION_SIDE - 1, REGION_SIDE - 1, REGION_SIDE - 1};
                if (narrow) {
                    if (smax.x < reachLo.x || smin.x > reachHi.x || smax.z < reachLo.z || smin.z > reachHi.z ||
                        smax.y < reachLo.y || smin.y > reachHi.y)
                        continue;
                    for (int axis = 0; axis < 3; ++axis) {
                        from[axis] = clampedOffset(smin[axis] - CAP, firstD[axis], -2, REGION_SIDE + 1) - 1;
                        to[axis] = clampedOffset(smax[axis] + CAP, firstD[axis], -2, REGION_SIDE + 1) + 1;
                        from[axis] = std::max(from[axis], 0);
                        to[axis] = std::min(to[axis], REGION_SIDE - 1);
                    }
                }
                bool haveCone = false;
                Cone cone;
                for (int i = from[0]; i <= to[0]; ++i)
                    for (int j = from[1]; j <= to[1]; ++j)
                        for (int k = from[2]; k <= to[2]; ++k) {
                            const std::size_t index = std::size_t((i * REGION_SIDE + j) * REGION_SIDE + k);
                            const Target& t = targets[index];
                            if (!t.live || cx < t.cx0 || cx > t.cx1 || cz < t.cz0 || cz > t.cz1) continue;
                            // Box-to-box distance: every point of the cone is at least this far.
                            const glm::dvec3 gap = glm::max(glm::max(smin - t.hi, t.lo - smax), 0.0);
                            if (!(glm::length(gap) < CAP)) continue;
                            if (!haveCone) {
                                const glm::dvec3 mid = 0.5 * (s.a + s.b);
                                cone = {s, mid, 0.5 * glm::length(s.b - s.a) + std::max(s.ra, s.rb)};
                                haveCone = true;
                            }
                            region->buckets[index].push_back(cone);
                        }
            }
        }
    }
    std::uint64_t bytes = sizeof(Region);
    for (const Bucket& b : region->buckets) bytes += b.capacity() * sizeof(Cone);
    return mCache->regions.insert(regionKey, std::move(region), bytes);
}

namespace {

/// The bucket of `p`; beyond ±2^62 buckets (BlockEvaluation's 1e300 m
/// column) the index saturates instead of overflowing the conversion
/// (undefined behaviour, found by UBSan over terrain_tests).
std::array<std::int64_t, 3> bucketKey(const glm::dvec3& p) // a WormCaves::Key
{
    return {detail::latticeIndex(std::floor(p.x / BUCKET_SIZE)), detail::latticeIndex(std::floor(p.y / BUCKET_SIZE)),
            detail::latticeIndex(std::floor(p.z / BUCKET_SIZE))};
}

} // namespace

const WormCaves::Bucket& WormCaves::threadBucket(const Key& key) const
{
    WormThreadCache::Slot& cache = tWormCache.slotFor(key);
    if (cache.id != mId || cache.key != key || !cache.bucket) {
        cache.bucket = bucket(key);
        cache.id = mId;
        cache.key = key;
    }
    return *static_cast<const Bucket*>(cache.bucket.get());
}

double WormCaves::distanceAmong(const glm::dvec3& p, const Cone* cones, std::size_t count)
{
    double d = CAP;
    for (std::size_t i = 0; i < count; ++i) {
        const Cone& c = cones[i];
        // Cheap rejection with the segment's bounding sphere: |p − mid| >= d + reach.
        const glm::dvec3 v = p - c.mid;
        const double far = d + c.reach;
        if (glm::dot(v, v) >= far * far) continue;
        d = std::min(d, roundConeDistance(p, c.s.a, c.s.b, c.s.ra, c.s.rb));
    }
    return d;
}

double WormCaves::density(const glm::dvec3& p) const
{
    const Bucket& cones = threadBucket(bucketKey(p));
    return distanceAmong(p, cones.data(), cones.size());
}

void WormCaves::densities(const PointBlock& points, double* out) const
{
    const Key key = bucketKey(points.box.min);
    if (points.count == 0 || bucketKey(points.box.max) != key) {
        DensityField::densities(points, out);
        return;
    }
    // distanceAmong() rejects a cone at p when |p − mid| >= d + reach, and
    // d <= CAP: a cone at least CAP + reach from the whole box (with a
    // millimetre to spare for rounding) is rejected at every point, so
    // dropping it first leaves each point's sequence of minima, and its
    // bits, unchanged.
    const Bucket& all = threadBucket(key);
    thread_local std::vector<detail::LaneCone> near; // a leaf: one per thread is safe
    near.clear();
    for (const Cone& c : all) {
        const glm::dvec3 gap = glm::max(glm::max(points.box.min - c.mid, c.mid - points.box.max), 0.0);
        const double reach = CAP + c.reach + 1e-3;
        if (glm::dot(gap, gap) < reach * reach) {
            detail::LaneCone& l = near.emplace_back();
            l = {c.s.a.x, c.s.a.y, c.s.a.z, c.s.b.x, c.s.b.y, c.s.b.z, c.s.ra, c.s.rb, c.mid.x, c.mid.y, c.mid.z,
                 c.reach, 0, 0, 0, 0, 0, 0};
            detail::deriveLaneCone(l);
        }
    }
    // Then distanceAmong() point by point, a point per SIMD lane.
    detail::wormDistances(near.data(), near.size(), CAP, points.x, points.y, points.z, points.count, out);
}

Interval WormCaves::bounds(const WorldBox& box) const
{
    const double d = density(box.centre()), r = box.radius();
    return {std::max(d - r, minDensity()), std::min(d + r, CAP)};
}

} // namespace strata::terrain

namespace strata::terrain {

void registerCaveNodes(NodeRegistry& registry)
{
    const WormOptions w;
    NodeType worms{"worms", "tunnel networks: noise-steered worms of round cones; an exact distance (to subtract)", {},
                   {}};
    worms.keys = {numberKey("cell_size", w.cellSize, 1.0, 1e5, "m", "side of one spawn cell"),
                  numberKey("worms_per_cell", w.wormsPerCell, 0.0, 16.0, "", "expected worms per cell"),
                  numberKey("min_y", w.minY, -HUGE_LENGTH, HUGE_LENGTH, "m", "lowest start height"),
                  numberKey("max_y", w.maxY, -HUGE_LENGTH, HUGE_LENGTH, "m", "highest start height"),
                  integerKey("segments", w.segments, 1, 256, "", "segments per worm"),
                  numberKey("segment_length", w.segmentLength, 1e-3, 1e4, "m", "length of one segment"),
                  numberKey("radius", w.radius, 1e-3, 1e4, "m", "mean tunnel radius"),
                  numberKey("radius_variation", w.radiusVariation, 0.0, 0.9, "", "radius varies within this fraction"),
                  numberKey("turn", w.turn, 0.0, 10.0, "rad", "how far the heading wanders"),
                  numberKey("max_pitch", w.maxPitch, 0.0, 1.4, "rad", "steepest tunnel slope"),
                  seedKey()};
    worms.build = [](const NodeArgs& a) -> DensityFieldPtr {
        WormOptions o;
        o.cellSize = a.number("cell_size");
        o.wormsPerCell = a.number("worms_per_cell");
        o.minY = a.number("min_y");
        o.maxY = a.number("max_y");
        if (o.maxY < o.minY) a.fail("max_y", "= " + formatNumber(o.maxY) + " is below min_y = " + formatNumber(o.minY));
        o.segments = int(a.integer("segments"));
        o.segmentLength = a.number("segment_length");
        o.radius = a.number("radius");
        o.radiusVariation = a.number("radius_variation");
        o.turn = a.number("turn");
        o.maxPitch = a.number("max_pitch");
        return std::make_shared<WormCaves>(a.seed(), o);
    };
    registry.add(std::move(worms));

    const CheeseOptions c;
    NodeType cheese{"cheese", "caverns where 3D noise exceeds the threshold (below it with invert)", {}, {}};
    cheese.keys = {numberKey("wavelength", c.wavelength, 1e-3, MAX_LENGTH, "m", "size of the caverns' noise"),
                   numberKey("threshold", c.threshold, -2.0, 2.0, "noise units", "higher: fewer, smaller caverns"),
                   numberKey("vertical_squash", c.verticalSquash, 0.1, 10.0, "", "> 1 flattens caverns"),
                   booleanKey("invert", c.invert, "caverns where the noise is below the threshold"),
                   numberKey("max_height", c.maxHeight, -HUGE_LENGTH, 1e30, "m", "no caverns above this height")};
    addFractalKeys(cheese.keys, c.noise);
    cheese.build = [](const NodeArgs& a) -> DensityFieldPtr {
        CheeseOptions o;
        o.wavelength = a.number("wavelength");
        o.threshold = a.number("threshold");
        o.verticalSquash = a.number("vertical_squash");
        o.invert = a.boolean("invert");
        o.maxHeight = a.number("max_height");
        o.noise = fractalOptions(a);
        return std::make_shared<CheeseCaves>(a.seed(), o);
    };
    registry.add(std::move(cheese));

    const SpaghettiOptions s;
    NodeType spaghetti{"spaghetti", "long winding tubes where two 3D noise fields are both near zero", {}, {}};
    spaghetti.keys = {numberKey("wavelength", s.wavelength, 1e-3, MAX_LENGTH, "m", "size of the meanders"),
                      numberKey("radius", s.radius, 1e-4, 1e6, "m", "mean horizontal tunnel radius"),
                      numberKey("vertical_squash", s.verticalSquash, 0.1, 10.0, "", "> 1 keeps tunnels level"),
                      numberKey("max_height", s.maxHeight, -HUGE_LENGTH, 1e30, "m", "no tunnels above this height")};
    addFractalKeys(spaghetti.keys, s.noise);
    spaghetti.build = [](const NodeArgs& a) -> DensityFieldPtr {
        SpaghettiOptions o;
        o.wavelength = a.number("wavelength");
        o.radius = a.number("radius");
        o.verticalSquash = a.number("vertical_squash");
        o.maxHeight = a.number("max_height");
        o.noise = fractalOptions(a);
        return std::make_shared<SpaghettiCaves>(a.seed(), o);
    };
    registry.add(std::move(spaghetti));
}

} // namespace strata::terrain
