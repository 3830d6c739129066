// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Cave shapes, to be subtracted from rock (CsgField SUBTRACT): each is a
/// density field that is negative inside the air pocket. Three kinds:
/// tunnel networks of noise-guided worms (exact distances), cheese caverns
/// (3D noise above a threshold) and spaghetti tunnels (two noise fields
/// both near zero).

#include <strata/terrain/DensityField.h>
#include <strata/terrain/FractalNoise.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace strata::terrain {

/// Spaghetti: where two independent 3D fractal fields n1, n2, evaluated at
/// (x, y·verticalSquash, z) / wavelength, are both near zero.
/// density = (√(n1² + n2²) − r) · wavelength / g, with g the typical
/// |∇n| across a tunnel (calibrated so the mean tunnel radius is `radius`):
/// close to the distance to the tunnel wall near it, gradient bound
/// √2·L_n·max(1, squash)/g (about 11 with the defaults); the distance bound
/// is the density over that bound.
struct SpaghettiOptions
{
    double wavelength = 56.0;    ///< metres, > 0: size of the meanders
    double radius = 4.5;         ///< mean horizontal tunnel radius, metres, > 0
    double verticalSquash = 1.6; ///< > 0; > 1 makes tunnels run more horizontally
    double maxHeight = 1e30;     ///< no tunnels above this height, metres
    FractalOptions noise{NoiseType::GRADIENT, FractalType::FBM, 2, 2.0, 0.5};
};

class SpaghettiCaves final : public DensityField
{
public:
    /// Throws strata::Error naming the option.
    SpaghettiCaves(std::uint64_t seed, const SpaghettiOptions& options);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return mLipschitz; }
    double distanceBound(const glm::dvec3& p) const override;
    double minDensity() const override { return -mNoiseRadius * mGain; }
    double minDistanceBound() const override { return -mNoiseRadius * mGain / mLipschitz; }

private:
    double tube(const glm::dvec3& p) const; ///< √(n1² + n2²) − r, noise units

    SpaghettiOptions mOptions;
    FractalNoise mA, mB;
    double mNoiseRadius = 0.0, mGain = 1.0, mLipschitz = 1.0;
};

/// Cheese: caverns where a 3D fractal field at (x, y·verticalSquash, z) /
/// wavelength exceeds `threshold` (or falls below it with `invert`, which
/// suits cellular_f1: round caverns around the feature points).
/// density = (threshold − n)·wavelength / (L_n / 3): about the distance near
/// the wall for gradient noise; gradient bound 3·max(1, squash).
struct CheeseOptions
{
    double wavelength = 40.0;   ///< metres, > 0
    double threshold = 0.35;    ///< in noise units, about [−1, 1]; higher = fewer, smaller caverns
    double verticalSquash = 1.0; ///< > 0
    bool invert = false;
    double maxHeight = 1e30;    ///< no caverns above this height, metres
    FractalOptions noise{NoiseType::GRADIENT, FractalType::FBM, 3, 2.0, 0.5};
};

class CheeseCaves final : public DensityField
{
public:
    CheeseCaves(std::uint64_t seed, const CheeseOptions& options);
    double density(const glm::dvec3& p) const override;
    double lipschitz() const override { return mLipschitz; }
    double distanceBound(const glm::dvec3& p) const override;

private:
    double excess(const glm::dvec3& p) const; ///< threshold − n (signed for invert), noise units

    CheeseOptions mOptions;
    FractalNoise mNoise;
    double mBoundScale = 1.0, mScale = 1.0, mLipschitz = 1.0;
};

/// Tunnel networks: worms that crawl from hashed start points, one set per
/// `cellSize` square of the XZ plane, steered by 1D gradient noise (yaw
/// turns, pitch within ±maxPitch) with a noise-varying radius. Each worm is
/// a chain of round cones (spheres swept along a segment with linearly
/// varying radius), and density is the exact signed distance to their union,
/// capped at CAP metres (so it is 1-Lipschitz and its own distance bound).
///
/// Segments are gathered lazily into 8 m buckets, built a region of 4³
/// buckets at a time and kept in thread-safe caches bounded in bytes
/// (REGION_CACHE_BYTES of regions, CELL_CACHE_BYTES of spawn cells, and the
/// process's cache limit, strata/CacheMemory.h; the least recently used
/// go first). The contents of a bucket depend only on its position, so
/// eviction costs only a rebuild and results are the same on any thread
/// count and in any order of evaluation. Any region can be evaluated; memory
/// stays within those bytes however large it is.
namespace detail {
class WormCavesInspector;
}

struct WormOptions
{
    double cellSize = 64.0;       ///< metres, > 0: one spawn cell
    double wormsPerCell = 1.0;    ///< expected worms per cell, 0..16
    double minY = -30.0, maxY = 5.0; ///< start heights, metres
    int segments = 32;            ///< 1..256
    double segmentLength = 4.0;   ///< metres, > 0
    double radius = 3.0;          ///< mean radius, metres, > 0
    double radiusVariation = 0.35; ///< 0..0.9: radius varies within ±this fraction
    double turn = 1.2;            ///< radians: yaw wanders about ±turn over a few segments
    double maxPitch = 0.45;       ///< radians, 0..1.4
};

class WormCaves final : public DensityField
{
public:
    /// Distances above this are returned as CAP (metres). Small keeps the
    /// buckets small (fast); it only has to exceed the narrow band, and
    /// pruning then probes rock far from tunnels at 8³-voxel tiles.
    static constexpr double CAP = 6.0;

    WormCaves(std::uint64_t seed, const WormOptions& options);
    ~WormCaves() override;
    double density(const glm::dvec3& p) const override;
    /// When the block lies in one bucket, its segments that no point can
    /// reach within CAP are dropped once for the block, not per point.
    void densities(const PointBlock& points, double* out) const override;
    double lipschitz() const override { return 1.0; }
    double distanceBound(const glm::dvec3& p) const override { return density(p); }
    double minDensity() const override { return -mOptions.radius * (1.0 + mOptions.radiusVariation); }
    double minDistanceBound() const override { return minDensity(); }
    /// density(c) ± radius, within [minDensity(), CAP]: density is the exact
    /// signed distance capped at CAP, hence 1-Lipschitz.
    Interval bounds(const WorldBox& box) const override;

    /// Side of a bucket, metres: a bucket holds the segments that come
    /// within CAP of its cube.
    static constexpr double BUCKET_SIZE = 8.0;
    /// Buckets are built a region of REGION_SIDE³ at a time: one pass over
    /// the cells within reach fills them all (each segment goes to the
    /// buckets it comes within CAP of), instead of a pass per bucket.
    static constexpr int REGION_SHIFT = 2;
    static constexpr int REGION_SIDE = 1 << REGION_SHIFT;
    static constexpr std::size_t REGION_BUCKETS = std::size_t(REGION_SIDE) * REGION_SIDE * REGION_SIDE;
    /// Budgets of the region and spawn-cell caches, bytes (a region of 64
    /// buckets weighs about 10-100 KB, a cell's worms a few KB).
    static constexpr std::uint64_t REGION_CACHE_BYTES = std::uint64_t(32) << 20;
    static constexpr std::uint64_t CELL_CACHE_BYTES = std::uint64_t(4) << 20;
    /// The bytes the caches hold now (at most their budgets, plus one entry
    /// per shard). Locks the caches.
    std::uint64_t cacheBytes() const;

private:
    /// Reads the buckets and spawn cells below (terrain/src/WormCavesInspector.h,
    /// not installed): the bucket layout is internal, checked against the
    /// per-bucket rule from outside.
    friend class detail::WormCavesInspector;

    struct Segment
    {
        glm::dvec3 a, b;
        double ra, rb;
    };
    using Key = std::array<std::int64_t, 3>; ///< a bucket: floor(p / 8 m)
    /// The segments of all worms spawned in cell (cx, cz), in order.
    std::vector<Segment> wormsOfCell(std::int64_t cx, std::int64_t cz) const;
    /// The segments of bucket `key`, in the order density() visits them.
    std::vector<Segment> bucketSegments(const Key& key) const;

    struct Cone ///< a segment with its bounding sphere, for quick rejection
    {
        Segment s;
        glm::dvec3 mid;
        double reach;
    };
    using Bucket = std::vector<Cone>;
    struct Region; ///< REGION_BUCKETS buckets, built together (Caves.cpp)
    /// The bucket, from its region (built on a miss); shares the region's ownership.
    std::shared_ptr<const Bucket> bucket(const Key& key) const;
    /// The region floor(key / REGION_SIDE), from the cache or built.
    std::shared_ptr<const Region> region(const Key& regionKey) const;
    /// The bucket, through this thread's one-entry cache.
    const Bucket& threadBucket(const Key& key) const;
    /// min(CAP, the cones' round-cone distances at p).
    static double distanceAmong(const glm::dvec3& p, const Cone* cones, std::size_t count);
    std::shared_ptr<const std::vector<Segment>> cell(std::int64_t cx, std::int64_t cz) const;

    std::uint64_t mSeed;
    WormOptions mOptions;
    double mReach = 0.0; ///< farthest any worm surface gets from its start, metres
    std::uint64_t mId;   ///< tells instances apart in the per-thread bucket cache
    struct Cache;        ///< the bounded bucket and cell caches (Caves.cpp)
    std::unique_ptr<Cache> mCache;
};

/// Signed distance to a round cone: the union of spheres centred on segment
/// a–b with radius varying linearly from ra to rb. Exact (the minimum over
/// the segment of |p − c(t)| − r(t), which is convex in t).
double roundConeDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, double ra, double rb);

} // namespace strata::terrain
