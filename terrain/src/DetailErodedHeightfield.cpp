// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/DetailErodedHeightfield.h>

#include "ShowValue.h"
#include "WorldBlockCache.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

using detail::show;

/// One block's displacement over its patch: (block + 2·halo + 1)² corners,
/// the first at world cell (bx·block − halo, bz·block − halo).
struct DetailErodedHeightfield::Block
{
    std::int64_t originX = 0, originZ = 0; ///< world cell of corner (0, 0)
    int size = 0;                          ///< corners per side
    std::vector<float> change;             ///< metres
    std::size_t bytes() const { return sizeof(*this) + change.capacity() * sizeof(float); }
};

// Bounded in bytes, not blocks: a block of 64 cells with the default halo of
// 24 is 113² floats (50 KiB: about 1,300 fit in the 64 MiB, fewer while the
// process's caches are over --max-memory), one of 1024 cells up to 2049²
// (16 MiB: four exceed the 64 MiB, but WorldBlockCache always keeps its 4
// most recent, as many as a query blends).
class DetailErodedHeightfield::Cache : public detail::WorldBlockCache<Block>
{
public:
    Cache() : WorldBlockCache(std::size_t(64) << 20) {}
};

DetailErodedHeightfield::DetailErodedHeightfield(HeightNodePtr child, std::uint64_t seed,
                                                 const DetailErodeOptions& options)
    : mChild(std::move(child)), mSeed(seed), mOptions(options), mCache(std::make_unique<Cache>())
{
    checkDetailErosionOptions(options.erosion);
    if (options.blockCells < 8 || options.blockCells > 1024) {
        throw Error(ErrorKind::BadInput, "block = " + std::to_string(options.blockCells) + " is out of range [8, 1024]",
                    {"", 0, "block", ""});
    }
    if (mOptions.halo == 0) mOptions.halo = std::min(options.erosion.dropletSteps, options.blockCells / 2);
    if (mOptions.halo < 1 || mOptions.halo > options.blockCells / 2) {
        throw Error(ErrorKind::BadInput,
                    "halo = " + std::to_string(mOptions.halo) + " is out of range [1, block / 2 = " +
                        std::to_string(options.blockCells / 2) + "]",
                    {"", 0, "halo", ""});
    }
    // |∇h| <= |∇child| + |∇(Σ w·d / Σ w)|: each block's bilinear d moves at
    // most 2·maxDepth per cell along an axis; the weights (a product of two
    // smoothsteps over half the halo, at most 4 of them non-zero, Σ w >= 1)
    // each add |∇w|·2·maxDepth.
    const double cell = options.erosion.cellSize, depth = options.erosion.maxDepth;
    const double ownSlope = std::sqrt(2.0) * 2.0 * depth / cell;
    const double weightSlope = std::sqrt(2.0) * 1.5 / (0.5 * mOptions.halo * cell);
    setSlopeBound(mChild->slopeBound() + ownSlope + 4.0 * weightSlope * 2.0 * depth);
}

DetailErodedHeightfield::~DetailErodedHeightfield() = default;

std::size_t DetailErodedHeightfield::blocksComputed() const { return mCache->computed(); }

std::shared_ptr<const DetailErodedHeightfield::Block> DetailErodedHeightfield::block(std::int64_t bx,
                                                                                   std::int64_t bz) const
{
    return mCache->get(bx, bz, [&] { return computeBlock(bx, bz); });
}

std::shared_ptr<const DetailErodedHeightfield::Block> DetailErodedHeightfield::computeBlock(std::int64_t bx,
                                                                                          std::int64_t bz) const
{
    const int b = mOptions.blockCells, halo = mOptions.halo;
    auto out = std::make_shared<Block>();
    out->originX = bx * b - halo;
    out->originZ = bz * b - halo;
    out->size = b + 2 * halo + 1;
    const std::size_t n = std::size_t(out->size);
    const double cell = mOptions.erosion.cellSize;
    std::vector<double> x(n * n), z(n * n), h(n * n);
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < n; ++i) {
            x[j * n + i] = double(out->originX + std::int64_t(i)) * cell;
            z[j * n + i] = double(out->originZ + std::int64_t(j)) * cell;
        }
    }
    mChild->heights(x.data(), z.data(), n * n, h.data());
    std::vector<double> eroded = h;
    erodeDetail(eroded, out->size, out->size, out->originX, out->originZ, mSeed, mOptions.erosion);
    out->change.resize(n * n);
    for (std::size_t c = 0; c < n * n; ++c) out->change[c] = float(eroded[c] - h[c]);
    return out;
}

double DetailErodedHeightfield::displacement(const Block& b, double u, double v) const
{
    // Bilinear in the block's corners; (u, v) in world cells.
    const double lu = std::clamp(u - double(b.originX), 0.0, double(b.size - 1));
    const double lv = std::clamp(v - double(b.originZ), 0.0, double(b.size - 1));
    const int i = std::min(int(lu), b.size - 2), j = std::min(int(lv), b.size - 2);
    const double fx = lu - i, fz = lv - j;
    const std::size_t n = std::size_t(b.size), c = std::size_t(j) * n + std::size_t(i);
    return (b.change[c] * (1 - fx) + b.change[c + 1] * fx) * (1 - fz) +
           (b.change[c + n] * (1 - fx) + b.change[c + n + 1] * fx) * fz;
}

double DetailErodedHeightfield::height(double x, double z) const
{
    double out;
    heights(&x, &z, 1, &out);
    return out;
}

void DetailErodedHeightfield::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    mChild->heights(x, z, n, out);
    const double cell = mOptions.erosion.cellSize;
    const std::int64_t size = mOptions.blockCells;
    const double halo = mOptions.halo;
    // The weight of a block at distance e (cells) inside its patch's outer
    // edge: 0 over the outer quarter of the halo, 1 from three quarters on.
    auto ramp = [&](double e) { return dmath::smoothstep01((e - 0.25 * halo) / (0.5 * halo)); };
    for (std::size_t k = 0; k < n; ++k) {
        const double u = x[k] / cell, v = z[k] / cell;
        // Beyond ±2^62 cells (or at NaN) a block index does not fit an
        // int64 (the conversion would be undefined behaviour, found by UBSan
        // on BlockEvaluation's 1e300 m column): no detail there, the child's
        // height alone, the same on the scalar and the block path.
        constexpr double MAX_CELLS = 4611686018427387904.0; // 2^62
        if (!(std::abs(u) < MAX_CELLS && std::abs(v) < MAX_CELLS)) continue;
        const std::int64_t bx0 = floorDiv(floorToInt<std::int64_t>(u - halo), size);
        const std::int64_t bx1 = floorDiv(floorToInt<std::int64_t>(u + halo), size);
        const std::int64_t bz0 = floorDiv(floorToInt<std::int64_t>(v - halo), size);
        const std::int64_t bz1 = floorDiv(floorToInt<std::int64_t>(v + halo), size);
        double sum = 0.0, weights = 0.0;
        for (std::int64_t bz = bz0; bz <= bz1; ++bz) {
            for (std::int64_t bx = bx0; bx <= bx1; ++bx) {
                const double lo = double(bx * size) - halo, hi = double((bx + 1) * size) + halo;
                const double loZ = double(bz * size) - halo, hiZ = double((bz + 1) * size) + halo;
                const double w = ramp(std::min(u - lo, hi - u)) * ramp(std::min(v - loZ, hiZ - v));
                if (w <= 0.0) continue;
                sum += w * displacement(*block(bx, bz), u, v);
                weights += w;
            }
        }
        if (weights > 0.0) out[k] += sum / weights;
    }
}

Interval DetailErodedHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    const Interval c = mChild->heightBounds(min, max);
    const double d = mOptions.erosion.maxDepth;
    return {c.lo - d, c.hi + d};
}

} // namespace strata::terrain
