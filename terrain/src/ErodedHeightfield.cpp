// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/ErodedHeightfield.h>

#include "ShowValue.h"

#include <strata/ByteBoundedCache.h>
#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>
#include <strata/Stopwatch.h>

#include <glm/common.hpp>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <mutex>

namespace strata::terrain {

using detail::show;

namespace {

constexpr int BLOCK = 16; // corners per side of a bounds block

std::uint64_t mix(std::uint64_t h, std::uint64_t v)
{
    // splitmix64 of the running hash and the next word.
    h ^= v + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    h += 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    return h ^ (h >> 31);
}

std::uint64_t bits(double v)
{
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
}

std::uint64_t hashGrid(std::uint64_t h, const std::vector<double>& values)
{
    h = mix(h, values.size());
    for (const double v : values) h = mix(h, bits(v));
    return h;
}

std::uint64_t hashOptions(const ErodeOptions& o)
{
    const StreamPowerOptions& e = o.evolution;
    const double values[] = {o.min.x, o.min.y, o.max.x, o.max.y, o.riverArea, e.cellSize, e.years, e.timeStep,
                             e.uplift, e.erodibility, e.areaExponent, e.slopeExponent, e.diffusivity};
    std::uint64_t h = 0x5354524154414552ull;
    for (const double v : values) h = mix(h, bits(v));
    return h;
}

/// The process-wide cache of evolutions by key, bounded in bytes by the
/// process's cache limit (strata/CacheMemory.h, --max-memory) and keeping
/// at least the last one. A bake's tiles and a World's chunks build the
/// scene's node tree once each, or rebuild it with the same keys: they all
/// share one evolution.
class ErosionCache
{
public:
    std::shared_ptr<const ErodedGrid> find(std::uint64_t key) { return mGrids.find(key); }
    void add(std::uint64_t key, std::shared_ptr<const ErodedGrid> grid)
    {
        const std::uint64_t bytes = sizeof(ErodedGrid) + grid->heights.capacity() * sizeof(double) +
                                    grid->masks.capacity() * sizeof(glm::vec4) +
                                    (grid->blockLo.capacity() + grid->blockHi.capacity()) * sizeof(double);
        mGrids.insert(key, std::move(grid), bytes);
    }
    void clear() { mGrids.clear(); }
    /// Only one evolution at a time: a second thread waits for it (and then
    /// finds it cached), and two passes never hold their work arrays at once.
    std::mutex& running() { return mRunning; }

private:
    std::mutex mRunning;
    // Its own budget is the whole limit: the process limit bounds it.
    ByteBoundedCache<std::uint64_t, ErodedGrid> mGrids{~std::uint64_t(0), 1};
};

ErosionCache& cache()
{
    static ErosionCache instance;
    return instance;
}

/// Grid corners per axis: enough that the last reaches max.
int cornersAlong(double min, double max, double cell)
{
    return ceilToInt<int>((max - min) / cell - 1e-9) + 1;
}

/// Samples `node` at every corner, row by row in parallel (each row one
/// block evaluation): the same bits on any thread count.
std::vector<double> sampleCorners(const HeightfieldBase& node, int width, int height, glm::dvec2 min, double cell)
{
    std::vector<double> out(std::size_t(width) * std::size_t(height));
    tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> x(static_cast<std::size_t>(width)), z(static_cast<std::size_t>(width));
        for (int row = rows.begin(); row < rows.end(); ++row) {
            for (int i = 0; i < width; ++i) {
                x[std::size_t(i)] = min.x + double(i) * cell;
                z[std::size_t(i)] = min.y + double(row) * cell;
            }
            node.heights(x.data(), z.data(), std::size_t(width), out.data() + std::size_t(row) * std::size_t(width));
        }
    });
    return out;
}

double smoothstep(double e0, double e1, double v) { return dmath::smoothstep01((v - e0) / (e1 - e0)); }

/// Uniform cubic B-spline weights of the four control points around t in [0, 1).
void splineWeights(double t, double w[4])
{
    const double s = 1.0 - t, t2 = t * t, t3 = t2 * t;
    w[0] = s * s * s / 6.0;
    w[1] = (3.0 * t3 - 6.0 * t2 + 4.0) / 6.0;
    w[2] = (-3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0) / 6.0;
    w[3] = t3 / 6.0;
}

/// Where (x, z) falls among the corners: the first of the four control
/// indices per axis (clamped later) and the weights.
struct SplineTap
{
    int i, j;
    double wx[4], wz[4];
};

SplineTap tap(const ErodedGrid& g, double x, double z)
{
    // Clamped to the domain: the edge values continue outside.
    const double u = std::clamp((x - g.min.x) / g.cellSize, 0.0, double(g.width - 1));
    const double v = std::clamp((z - g.min.y) / g.cellSize, 0.0, double(g.height - 1));
    SplineTap t;
    const double fu = std::floor(u), fv = std::floor(v);
    t.i = clampToInt<int>(fu) - 1;
    t.j = clampToInt<int>(fv) - 1;
    splineWeights(u - fu, t.wx);
    splineWeights(v - fv, t.wz);
    return t;
}

template <typename T, typename Get>
T evaluateSpline(const ErodedGrid& g, const SplineTap& t, Get get)
{
    T sum{};
    for (int b = 0; b < 4; ++b) {
        const int zz = std::clamp(t.j + b, 0, g.height - 1);
        T row{};
        for (int a = 0; a < 4; ++a) {
            const int xx = std::clamp(t.i + a, 0, g.width - 1);
            row += get(std::size_t(zz) * std::size_t(g.width) + std::size_t(xx)) * t.wx[a];
        }
        sum += row * t.wz[b];
    }
    return sum;
}

std::shared_ptr<ErodedGrid> evolve(const std::vector<double>& input, const std::vector<double>& uplift, int width,
                                   int height, const ErodeOptions& o, const std::function<bool(double)>& progress)
{
    Stopwatch clock;
    StreamPowerResult run = evolveLandscape(input, width, height, uplift, o.evolution, progress);
    auto g = std::make_shared<ErodedGrid>();
    g->width = width;
    g->height = height;
    g->min = o.min;
    g->cellSize = o.evolution.cellSize;
    g->heights = std::move(run.heights);
    const std::size_t count = g->heights.size();
    g->masks.resize(count);
    const double river = dmath::log10(o.riverArea);
    for (std::size_t i = 0; i < count; ++i) {
        const double flow = dmath::log10(run.flowArea[i]);
        const double water = std::max(smoothstep(river - 0.25, river + 0.25, flow), smoothstep(0.0, 0.5, run.lakeDepth[i]));
        g->masks[i] = glm::vec4(float(flow), float(run.wear[i]), float(run.sediment[i]), float(water));
    }
    // Bounds: the B-spline lies within its control values and its slope
    // within the steepest difference along each axis.
    double steepX = 0.0, steepZ = 0.0;
    g->lo = HUGE_VAL;
    g->hi = -HUGE_VAL;
    g->blocksX = (width + BLOCK - 1) / BLOCK;
    const int blocksZ = (height + BLOCK - 1) / BLOCK;
    g->blockLo.assign(std::size_t(g->blocksX) * std::size_t(blocksZ), HUGE_VAL);
    g->blockHi.assign(g->blockLo.size(), -HUGE_VAL);
    for (int z = 0; z < height; ++z) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(z) * std::size_t(width) + std::size_t(x);
            const double h = g->heights[i];
            if (x + 1 < width) steepX = std::max(steepX, std::abs(g->heights[i + 1] - h));
            if (z + 1 < height) steepZ = std::max(steepZ, std::abs(g->heights[i + std::size_t(width)] - h));
            const std::size_t b = std::size_t(z / BLOCK) * std::size_t(g->blocksX) + std::size_t(x / BLOCK);
            g->blockLo[b] = std::min(g->blockLo[b], h);
            g->blockHi[b] = std::max(g->blockHi[b], h);
            g->lo = std::min(g->lo, h);
            g->hi = std::max(g->hi, h);
        }
    }
    g->slopeBound = dmath::hypot(steepX, steepZ) / g->cellSize;
    run.area.clear();
    run.flowArea.clear();
    run.wear.clear();
    run.sediment.clear();
    run.lakeDepth.clear();
    g->budget = std::move(run);
    g->seconds = clock.seconds();
    return g;
}

} // namespace

std::size_t ErodedHeightfield::cellCount(const ErodeOptions& o)
{
    const double c = o.evolution.cellSize;
    if (!(c > 0.0) || !(o.max.x > o.min.x) || !(o.max.y > o.min.y)) return 0;
    const double w = std::ceil((o.max.x - o.min.x) / c) + 1.0, h = std::ceil((o.max.y - o.min.y) / c) + 1.0;
    return w * h > 1e18 ? std::size_t(-1) : std::size_t(w * h);
}

std::size_t ErodedHeightfield::peakBytes(const ErodeOptions& o)
{
    // The evolution's working set (heights, routing, area, flux, budgets,
    // the priority queue) is about 120 bytes a cell; the result keeps 24.
    const std::size_t cells = cellCount(o);
    return cells > std::size_t(-1) / 160 ? std::size_t(-1) : cells * 144;
}

ErodedHeightfield::ErodedHeightfield(HeightNodePtr input, HeightNodePtr upliftMap, const ErodeOptions& o,
                                     const std::function<bool(double)>& progress)
    : mOptions(o)
{
    for (int a = 0; a < 2; ++a) {
        if (!(o.max[a] > o.min[a])) {
            throw Error(ErrorKind::BadInput,
                        std::string("max must be greater than min on both axes (") + show(o.min[a]) +
                            " >= " + show(o.max[a]) + " along " + (a == 0 ? "x" : "z") + ")",
                        {"", 0, "max", ""});
        }
    }
    const double c = o.evolution.cellSize;
    if (!(std::isfinite(c) && c > 0.0)) {
        throw Error(ErrorKind::BadInput, "cell_size = " + show(c) + " must be a finite number > 0", {"", 0, "cell_size", ""});
    }
    if (cellCount(o) > MAX_CELLS) {
        throw Error(ErrorKind::BadInput,
                    "cell_size = " + show(c) + " makes " + std::to_string(cellCount(o)) +
                        " cells over the domain, more than the 8193 x 8193 an erode node may have",
                    {"", 0, "cell_size", ""});
    }
    if (!(std::isfinite(o.riverArea) && o.riverArea > 0.0)) {
        throw Error(ErrorKind::BadInput, "river_area = " + show(o.riverArea) + " must be a finite number > 0",
                    {"", 0, "river_area", ""});
    }
    const int width = cornersAlong(o.min.x, o.max.x, c), height = cornersAlong(o.min.y, o.max.y, c);
    // Corners must be distinct numbers: cells far below the coordinates'
    // precision would collapse.
    if (!(o.min.x + c > o.min.x && o.min.y + c > o.min.y)) {
        throw Error(ErrorKind::BadInput,
                    "cell_size = " + show(c) + " is below the precision of coordinates near min = [" +
                        show(o.min.x) + ", " + show(o.min.y) + "]",
                    {"", 0, "cell_size", ""});
    }
    const std::vector<double> heights = sampleCorners(*input, width, height, o.min, c);
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (!std::isfinite(heights[i])) throw Error(ErrorKind::BadInput, "height: the input is not finite at a domain corner", {"", 0, "height", ""});
    }
    std::vector<double> uplift;
    if (upliftMap) uplift = sampleCorners(*upliftMap, width, height, o.min, c);
    std::uint64_t key = hashOptions(o);
    key = hashGrid(key, heights);
    key = hashGrid(key, uplift);

    mGrid = cache().find(key);
    mCached = mGrid != nullptr;
    if (!mGrid) {
        std::lock_guard<std::mutex> one(cache().running());
        mGrid = cache().find(key); // another thread may have run it meanwhile
        mCached = mGrid != nullptr;
        if (!mGrid) {
            mGrid = evolve(heights, uplift, width, height, o, progress);
            cache().add(key, mGrid);
        }
    }
    setSlopeBound(mGrid->slopeBound);
}

void ErodedHeightfield::clearCache()
{
    cache().clear();
}

double ErodedHeightfield::height(double x, double z) const
{
    const ErodedGrid& g = *mGrid;
    return evaluateSpline<double>(g, tap(g, x, z), [&](std::size_t i) { return g.heights[i]; });
}

void ErodedHeightfield::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    for (std::size_t i = 0; i < n; ++i) out[i] = height(x[i], z[i]);
}

void ErodedHeightfield::landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const
{
    const ErodedGrid& g = *mGrid;
    for (std::size_t k = 0; k < n; ++k) {
        const glm::dvec4 m = evaluateSpline<glm::dvec4>(g, tap(g, x[k], z[k]),
                                                        [&](std::size_t i) { return glm::dvec4(g.masks[i]); });
        out[k] = glm::vec4(glm::max(m, glm::dvec4(0.0)));
    }
}

Interval ErodedHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // The control points that reach the rectangle, by 16×16 blocks (a
    // superset: exact enough, and bounded cost).
    const ErodedGrid& g = *mGrid;
    const double u0 = std::clamp((min.x - g.min.x) / g.cellSize, 0.0, double(g.width - 1));
    const double u1 = std::clamp((max.x - g.min.x) / g.cellSize, 0.0, double(g.width - 1));
    const double v0 = std::clamp((min.y - g.min.y) / g.cellSize, 0.0, double(g.height - 1));
    const double v1 = std::clamp((max.y - g.min.y) / g.cellSize, 0.0, double(g.height - 1));
    const int i0 = std::max(0, floorToInt<int>(u0) - 1), i1 = std::min(g.width - 1, floorToInt<int>(u1) + 2);
    const int j0 = std::max(0, floorToInt<int>(v0) - 1), j1 = std::min(g.height - 1, floorToInt<int>(v1) + 2);
    Interval out{HUGE_VAL, -HUGE_VAL};
    for (int bz = j0 / BLOCK; bz <= j1 / BLOCK; ++bz) {
        for (int bx = i0 / BLOCK; bx <= i1 / BLOCK; ++bx) {
            const std::size_t b = std::size_t(bz) * std::size_t(g.blocksX) + std::size_t(bx);
            out.lo = std::min(out.lo, g.blockLo[b]);
            out.hi = std::max(out.hi, g.blockHi[b]);
        }
    }
    // Rounding of the weighted sum: a relative 1e-12 of the magnitude.
    const double slack = 1e-12 * (std::abs(out.lo) + std::abs(out.hi)) + 1e-12;
    return {out.lo - slack, out.hi + slack};
}

} // namespace strata::terrain
