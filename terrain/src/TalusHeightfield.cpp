// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/TalusHeightfield.h>

#include "ShowValue.h"
#include "WorldBlockCache.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

namespace strata::terrain {

using detail::show;

namespace {

/// Lattice nodes of a block's window, at most, a side: 2048² nodes of a few
/// doubles each is about 170 MiB while one block is computed.
constexpr int MAX_WINDOW = 2048;

/// out[i] = min of in[i + k·stride], |k| <= r, within [0, n): a monotone
/// deque (min selects, so any order gives the same bits).
void slidingMin(const double* in, double* out, int n, int stride, int r)
{
    std::deque<int> window; // indices, values increasing
    int next = 0;
    for (int i = 0; i < n; ++i) {
        for (; next < n && next <= i + r; ++next) {
            while (!window.empty() && in[std::size_t(window.back()) * stride] >= in[std::size_t(next) * stride]) {
                window.pop_back();
            }
            window.push_back(next);
        }
        while (window.front() < i - r) window.pop_front();
        out[std::size_t(i) * stride] = in[std::size_t(window.front()) * stride];
    }
}

/// One cone pass along (dx, dz): out = max over |k| <= reach of
/// in[node + k·(dx, dz)] − penalty[k], for the nodes of columns [x0, x1]
/// and rows [z0, z1] of the w × w window (the reach must stay inside it). Each
/// candidate is computed one way (one subtraction of a fixed penalty) and
/// max selects, so the bits do not depend on the window or on the order:
/// the loops run along rows, where the compiler vectorizes them.
void conePass(const std::vector<double>& in, std::vector<double>& out, int w, int dx, int dz,
              const std::vector<double>& penalty, int x0, int x1, int z0, int z1)
{
    const int reach = int(penalty.size()) - 1;
    const std::ptrdiff_t offset = std::ptrdiff_t(dz) * w + dx;
    const std::size_t count = std::size_t(x1 - x0 + 1);
    for (int j = z0; j <= z1; ++j) {
        const std::size_t row = std::size_t(j) * std::size_t(w) + std::size_t(x0);
        std::copy_n(&in[row], count, &out[row]);
        for (int k = 1; k <= reach; ++k) {
            const double* ahead = &in[row] + k * offset;
            const double* behind = &in[row] - k * offset;
            const double p = penalty[std::size_t(k)];
            double* o = &out[row];
            for (std::size_t i = 0; i < count; ++i) {
                const double a = ahead[i] - p, b = behind[i] - p;
                const double m = a > b ? a : b;
                o[i] = m > o[i] ? m : o[i];
            }
        }
    }
}

} // namespace

/// One block's lattice nodes, (block + 1)² of them, the first at world node
/// (bx·block, bz·block).
struct TalusHeightfield::Block
{
    int size = 0;             ///< nodes per side
    std::vector<double> ground; ///< H, metres
    std::vector<double> cone;   ///< C
    std::vector<double> foot;   ///< L
    std::size_t bytes() const
    {
        return sizeof(*this) + (ground.capacity() + cone.capacity() + foot.capacity()) * sizeof(double);
    }
};

// A block of 256 cells is 257² nodes of three doubles (1.5 MiB): about 40 fit.
class TalusHeightfield::Cache : public detail::WorldBlockCache<Block>
{
public:
    Cache() : WorldBlockCache(std::size_t(64) << 20) {}
};

TalusHeightfield::TalusHeightfield(HeightNodePtr child, const TalusOptions& options)
    : mChild(std::move(child)), mOptions(options), mCache(std::make_unique<Cache>())
{
    auto fail = [](const std::string& key, double value, const std::string& why) {
        throw Error(ErrorKind::BadInput, key + " = " + show(value) + " " + why, {"", 0, key, ""});
    };
    const TalusOptions& o = options;
    if (!(o.angle >= 5.0 && o.angle <= 60.0)) fail("angle", o.angle, "is out of range [5, 60] degrees");
    if (!(o.fill >= 0.0 && o.fill <= 1.0)) fail("fill", o.fill, "is out of range [0, 1]");
    if (!(o.maxHeight > 0.0 && o.maxHeight <= 1e4)) fail("max_height", o.maxHeight, "is out of range (0, 1e4] m");
    if (!(o.cellSize > 0.0 && o.cellSize <= 1e4)) fail("cell_size", o.cellSize, "is out of range (0, 1e4] m");
    if (o.blockCells < 16 || o.blockCells > 1024) fail("block", o.blockCells, "is out of range [16, 1024] cells");
    // An octagonal cone: four passes of slope t along x, z and the diagonals
    // make a cone whose footprint is a regular octagon; between its corners
    // (22.5° off a pass) it is 1 / cos 22.5° steeper. t = tan(angle) · cos
    // 22.5° keeps every direction at most tan(angle).
    const double cos22_5 = 0.5 * std::sqrt(2.0 + std::sqrt(2.0));
    mAxisSlope = dmath::tanDegrees(o.angle) * cos22_5;
    const double reach = std::ceil(o.maxHeight / (mAxisSlope * o.cellSize));
    const double window = double(o.blockCells) + 12.0 * reach + 1.0;
    if (!(window <= MAX_WINDOW)) {
        throw Error(ErrorKind::BadInput,
                    "max_height = " + show(o.maxHeight) + " is too tall for cell_size = " + show(o.cellSize) +
                        ": a cone reaches " + show(reach) + " cells, so a block's window would be " + show(window) +
                        " cells a side (at most " + std::to_string(MAX_WINDOW) +
                        "): use a larger cell_size, a lower max_height or a smaller block",
                    {"", 0, "max_height", ""});
    }
    mReach = int(reach);
    // Bound of |∇h| (see heights()): h = H + w·g, with g = max(0, T − H),
    // T the bilinear talus surface and w = min(1, e / cell), e the bilinear
    // thickness. Per lattice step along an axis, T moves at most m·cell
    // (m = max(s, tan angle), s the child's bound) and e at most (tan + s)
    // · cell, so |∇T| <= √2·m and |∇w| <= √2·(tan + s) / cell; where w < 1,
    // g < cell + √2·s·cell.
    const double s = mChild->slopeBound(), tan = dmath::tanDegrees(o.angle);
    const double root2 = std::sqrt(2.0);
    setSlopeBound(2.0 * s + root2 * std::max(s, tan) + (1.0 + root2 * s) * root2 * (tan + s));
}

TalusHeightfield::~TalusHeightfield() = default;

std::size_t TalusHeightfield::blocksComputed() const { return mCache->computed(); }

std::shared_ptr<const TalusHeightfield::Block> TalusHeightfield::block(std::int64_t bx, std::int64_t bz) const
{
    return mCache->get(bx, bz, [&] { return computeBlock(bx, bz); });
}

std::shared_ptr<const TalusHeightfield::Block> TalusHeightfield::computeBlock(std::int64_t bx, std::int64_t bz) const
{
    const int b = mOptions.blockCells, r = mReach, margin = 6 * r;
    const int w = b + 2 * margin + 1;
    const std::size_t nodes = std::size_t(w) * std::size_t(w);
    const std::int64_t originX = bx * b - margin, originZ = bz * b - margin;
    const double cell = mOptions.cellSize;

    // The ground over the window.
    std::vector<double> x(nodes), z(nodes), ground(nodes);
    for (int j = 0; j < w; ++j) {
        for (int i = 0; i < w; ++i) {
            x[std::size_t(j) * w + i] = double(originX + i) * cell;
            z[std::size_t(j) * w + i] = double(originZ + j) * cell;
        }
    }
    mChild->heights(x.data(), z.data(), nodes, ground.data());
    std::vector<double>().swap(x);
    std::vector<double>().swap(z);

    // L: the lowest ground within 3R (a separable square minimum).
    std::vector<double> rows(nodes), foot(nodes);
    for (int j = 0; j < w; ++j) slidingMin(&ground[std::size_t(j) * w], &rows[std::size_t(j) * w], w, 1, 3 * r);
    for (int i = 0; i < w; ++i) slidingMin(&rows[std::size_t(i)], &foot[std::size_t(i)], w, w, 3 * r);

    // S: how high the debris shed from each node piles.
    std::vector<double>& source = rows;
    for (std::size_t c = 0; c < nodes; ++c) {
        const double relief = ground[c] - foot[c];
        source[c] = foot[c] + std::min(mOptions.fill * relief, mOptions.maxHeight);
    }

    // C: the cones, one pass per direction.
    std::vector<double> axis(std::size_t(r) + 1), diagonal(std::size_t(r) + 1);
    const double step = mAxisSlope * cell, diagonalStep = mAxisSlope * (cell * std::sqrt(2.0));
    for (int k = 0; k <= r; ++k) {
        axis[std::size_t(k)] = double(k) * step;
        diagonal[std::size_t(k)] = double(k) * diagonalStep;
    }
    // Each pass only where the next ones read: the last on the block's
    // nodes (6R in from the window's edge), each one before it a reach
    // further out along its successor's direction; the first reads S 3R in
    // from the edge, where L saw its whole square.
    std::vector<double> cones(nodes);
    auto pass = [&](const std::vector<double>& in, std::vector<double>& out, int dx, int dz,
                    const std::vector<double>& penalty, int inX, int inZ) {
        conePass(in, out, w, dx, dz, penalty, inX * r, w - 1 - inX * r, inZ * r, w - 1 - inZ * r);
    };
    pass(source, cones, 1, 0, axis, 4, 3);
    pass(cones, source, 0, 1, axis, 4, 4);
    pass(source, cones, 1, 1, diagonal, 5, 5);
    pass(cones, source, 1, -1, diagonal, 6, 6);
    const std::vector<double>& cone = source;

    auto out = std::make_shared<Block>();
    out->size = b + 1;
    const std::size_t n = std::size_t(out->size);
    out->ground.resize(n * n);
    out->cone.resize(n * n);
    out->foot.resize(n * n);
    for (std::size_t j = 0; j < n; ++j) {
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t c = (j + std::size_t(margin)) * std::size_t(w) + i + std::size_t(margin);
            out->ground[j * n + i] = ground[c];
            out->cone[j * n + i] = cone[c];
            out->foot[j * n + i] = foot[c];
        }
    }
    return out;
}

double TalusHeightfield::height(double x, double z) const
{
    double ground, out;
    surface(&x, &z, 1, &ground, &out);
    return out;
}

void TalusHeightfield::heights(const double* x, const double* z, std::size_t n, double* out) const
{
    std::vector<double> ground(n);
    surface(x, z, n, ground.data(), out);
}

void TalusHeightfield::thickness(const double* x, const double* z, std::size_t n, double* out) const
{
    std::vector<double> ground(n);
    surface(x, z, n, ground.data(), out);
    for (std::size_t k = 0; k < n; ++k) out[k] = std::max(0.0, out[k] - ground[k]);
}

/// The lattice cell holding world column (x, z): its block and the bilinear
/// weights of its four corners. False beyond ±2^62 cells or at NaN, where
/// no node index fits an int64.
struct TalusHeightfield::Corners
{
    std::shared_ptr<const Block> block;
    std::size_t c = 0, s = 0; ///< corner (0, 0), nodes per row
    double fx = 0.0, fz = 0.0;
    template<typename F>
    double bilinear(F&& at) const
    {
        return (at(c) * (1 - fx) + at(c + 1) * fx) * (1 - fz) + (at(c + s) * (1 - fx) + at(c + s + 1) * fx) * fz;
    }
};

bool TalusHeightfield::corners(double x, double z, Corners& out) const
{
    const double u = x / mOptions.cellSize, v = z / mOptions.cellSize;
    constexpr double MAX_CELLS = 4611686018427387904.0; // 2^62
    if (!(std::abs(u) < MAX_CELLS && std::abs(v) < MAX_CELLS)) return false;
    const std::int64_t size = mOptions.blockCells;
    const std::int64_t i = floorToInt<std::int64_t>(u), j = floorToInt<std::int64_t>(v);
    const std::int64_t bx = floorDiv(i, size), bz = floorDiv(j, size);
    out.block = block(bx, bz);
    out.s = std::size_t(out.block->size);
    out.c = std::size_t(j - bz * size) * out.s + std::size_t(i - bx * size);
    out.fx = u - double(i);
    out.fz = v - double(j);
    return true;
}

void TalusHeightfield::surface(const double* x, const double* z, std::size_t n, double* ground, double* out) const
{
    mChild->heights(x, z, n, ground);
    const double cell = mOptions.cellSize;
    Corners k;
    for (std::size_t p = 0; p < n; ++p) {
        out[p] = ground[p];
        if (!corners(x[p], z[p], k)) continue; // far beyond any lattice: the child alone
        const Block& b = *k.block;
        const double thick = k.bilinear([&](std::size_t c) { return std::max(0.0, b.cone[c] - b.ground[c]); });
        if (!(thick > 0.0)) continue;
        // Off the talus the child's own detail; on it (thicker than a cell)
        // the bilinear cones; a blend where it thins out.
        const double weight = std::min(1.0, thick / cell);
        const double top = k.bilinear([&](std::size_t c) { return std::max(b.ground[c], b.cone[c]); });
        out[p] = ground[p] + weight * std::max(0.0, top - ground[p]);
    }
}

void TalusHeightfield::lattice(const double* x, const double* z, std::size_t n, double* ground, double* cone,
                               double* foot) const
{
    Corners k;
    for (std::size_t p = 0; p < n; ++p) {
        if (!corners(x[p], z[p], k)) {
            ground[p] = cone[p] = -HUGE_VAL;
            foot[p] = HUGE_VAL;
            continue;
        }
        const Block& b = *k.block;
        ground[p] = k.bilinear([&](std::size_t c) { return b.ground[c]; });
        cone[p] = k.bilinear([&](std::size_t c) { return b.cone[c]; });
        foot[p] = k.bilinear([&](std::size_t c) { return b.foot[c]; });
    }
}

bool TalusHeightfield::latticeRange(const glm::dvec2& min, const glm::dvec2& max, LatticeRange& out) const
{
    const double cell = mOptions.cellSize;
    const double u0 = std::floor(min.x / cell), u1 = std::floor(max.x / cell) + 1.0;
    const double v0 = std::floor(min.y / cell), v1 = std::floor(max.y / cell) + 1.0;
    constexpr double MAX_CELLS = 4611686018427387904.0; // 2^62
    for (const double u : {u0, u1, v0, v1}) {
        if (!(std::abs(u) < MAX_CELLS)) return false;
    }
    if (!((u1 - u0 + 1.0) * (v1 - v0 + 1.0) <= 65536.0)) return false;
    const std::int64_t size = mOptions.blockCells;
    bool first = true;
    for (std::int64_t j = std::int64_t(v0); j <= std::int64_t(v1); ++j) {
        const std::int64_t bz = floorDiv(j, size);
        for (std::int64_t i = std::int64_t(u0); i <= std::int64_t(u1); ++i) {
            // A node on a block's far edge is also node 0 of the next block
            // (the same bits); take it from the block that holds i, j.
            const std::int64_t bx = floorDiv(i, size);
            const std::shared_ptr<const Block> b = block(bx, bz);
            const std::size_t c = std::size_t(j - bz * size) * std::size_t(b->size) + std::size_t(i - bx * size);
            const double cone = b->cone[c], foot = b->foot[c];
            if (first) {
                out = {cone, cone, foot, foot};
                first = false;
            } else {
                out.coneLo = std::min(out.coneLo, cone);
                out.coneHi = std::max(out.coneHi, cone);
                out.footLo = std::min(out.footLo, foot);
                out.footHi = std::max(out.footHi, foot);
            }
        }
    }
    return true;
}

Interval TalusHeightfield::heightBounds(const glm::dvec2& min, const glm::dvec2& max) const
{
    // The bilinear surface reads the corners of the cells the rectangle
    // touches: one cell further each way. Every node's cone is at most
    // max_height above the ground there (C <= L + max_height <= H +
    // max_height at nodes within a cone's reach).
    const glm::dvec2 widen(mOptions.cellSize);
    const Interval around = mChild->heightBounds(min - widen, max + widen);
    return {mChild->heightBounds(min, max).lo, around.hi + mOptions.maxHeight};
}

void TalusHeightfield::landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const
{
    if (auto masks = std::dynamic_pointer_cast<const LandformMasks>(mChild)) {
        masks->landformMasks(x, z, n, out);
    } else {
        std::fill(out, out + n, glm::vec4(0.0f));
    }
    std::vector<double> talus(n);
    thickness(x, z, n, talus.data());
    for (std::size_t k = 0; k < n; ++k) out[k].z += float(talus[k]);
}

} // namespace strata::terrain
