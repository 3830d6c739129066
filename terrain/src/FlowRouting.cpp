// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/FlowRouting.h>

#include <strata/Error.h>
#include <strata/Format.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

namespace strata::terrain {

namespace {

/// The 8 neighbours, (dx, dz), in the fixed order ties are broken in.
constexpr int NEIGHBOUR_DX[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
constexpr int NEIGHBOUR_DZ[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
constexpr double INV_SQRT2 = 0.70710678118654752440;

/// A queued cell: its filled height and index; the queue pops the lowest
/// height first, the lowest index among equal heights (deterministic).
struct QueuedCell
{
    double filled;
    std::uint32_t index;
};

struct PopsLater
{
    bool operator()(const QueuedCell& a, const QueuedCell& b) const
    {
        return a.filled > b.filled || (a.filled == b.filled && a.index > b.index);
    }
};

/// std::nextafter(x, +inf) for a finite x, from its bits (no call into libm).
double nextUp(double x)
{
    if (x == 0.0) return std::numeric_limits<double>::denorm_min();
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(x);
    return std::bit_cast<double>(x > 0.0 ? bits + 1 : bits - 1);
}

void checkInput(const std::vector<double>& heights, int width, int height, double cellSize)
{
    if (width < 1 || height < 1)
        throw Error(ErrorKind::BadInput, "flow routing: the grid is " + std::to_string(width) + " x " + std::to_string(height) +
                    " cells; both sides must be >= 1");
    if (std::uint64_t(width) * std::uint64_t(height) > std::numeric_limits<std::uint32_t>::max())
        throw Error(ErrorKind::BadInput, "flow routing: the grid is " + std::to_string(width) + " x " + std::to_string(height) +
                    " cells, more than 2^32 - 1");
    if (heights.size() != std::size_t(width) * std::size_t(height))
        throw Error(ErrorKind::BadInput, "flow routing: " + std::to_string(heights.size()) + " heights for a " + std::to_string(width) +
                    " x " + std::to_string(height) + " grid (" +
                    std::to_string(std::size_t(width) * std::size_t(height)) + " cells)");
    if (!std::isfinite(cellSize) || cellSize <= 0.0)
        throw Error(ErrorKind::BadInput, "flow routing: cell size = " + formatNumber(cellSize) + " must be a finite number > 0");
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (!std::isfinite(heights[i]))
            throw Error(ErrorKind::BadInput, "flow routing: the height at cell (x " + std::to_string(i % std::size_t(width)) + ", z " +
                        std::to_string(i / std::size_t(width)) + ") is " + formatNumber(heights[i]) +
                        ", not a finite number");
    }
}

} // namespace

FlowRouting routeFlow(const std::vector<double>& heights, int width, int height, double cellSize)
{
    FlowRouting r;
    routeFlow(heights, width, height, cellSize, r);
    return r;
}

void routeFlow(const std::vector<double>& heights, int width, int height, double cellSize, FlowRouting& r)
{
    checkInput(heights, width, height, cellSize);
    const std::size_t n = std::size_t(width) * std::size_t(height);
    r.width = width;
    r.height = height;
    r.filled = heights; // into the existing buffers where they are large enough
    r.receiver.resize(n);
    r.order.clear();
    r.order.reserve(n);
    for (std::size_t i = 0; i < n; ++i) r.receiver[i] = std::uint32_t(i);

    // Edge cells first (index order): they are their own receivers.
    std::vector<std::uint8_t> visited(n, 0);
    std::vector<QueuedCell> seeds;
    seeds.reserve(2 * std::size_t(width + height));
    for (int z = 0; z < height; ++z) {
        const bool edgeRow = z == 0 || z == height - 1;
        for (int x = 0; x < width; x += (edgeRow || x == width - 1) ? 1 : width - 1) {
            const std::uint32_t c = std::uint32_t(std::size_t(z) * std::size_t(width) + std::size_t(x));
            visited[c] = 1;
            r.order.push_back(c);
            seeds.push_back({heights[c], c});
        }
    }
    if (width <= 2 || height <= 2) return; // every cell is an edge cell

    // Priority-flood + epsilon (Barnes, Lehman and Mulla 2014). A cell is
    // pushed above its popped neighbour by at least one representable step,
    // so pops are non-decreasing in `filled` and each interior cell has a
    // strictly lower neighbour (the one that pushed it).
    std::priority_queue<QueuedCell, std::vector<QueuedCell>, PopsLater> open(PopsLater{}, std::move(seeds));
    while (!open.empty()) {
        const QueuedCell top = open.top();
        open.pop();
        const int x = int(top.index % std::uint32_t(width)), z = int(top.index / std::uint32_t(width));
        if (x != 0 && x != width - 1 && z != 0 && z != height - 1) r.order.push_back(top.index);
        const double raised = nextUp(top.filled);
        for (int k = 0; k < 8; ++k) {
            const int nx = x + NEIGHBOUR_DX[k], nz = z + NEIGHBOUR_DZ[k];
            if (nx < 0 || nx >= width || nz < 0 || nz >= height) continue;
            const std::uint32_t nb = std::uint32_t(nz) * std::uint32_t(width) + std::uint32_t(nx);
            if (visited[nb]) continue;
            visited[nb] = 1;
            r.filled[nb] = std::max(heights[nb], raised);
            open.push({r.filled[nb], nb});
        }
    }
    assert(r.order.size() == n);

    // D8 steepest descent on `filled` for the interior cells (all their 8
    // neighbours exist); the first of equally steep neighbours wins.
    for (int z = 1; z < height - 1; ++z) {
        for (int x = 1; x < width - 1; ++x) {
            const std::size_t c = std::size_t(z) * std::size_t(width) + std::size_t(x);
            const double fc = r.filled[c];
            double best = 0.0;
            std::uint32_t to = std::uint32_t(c);
            for (int k = 0; k < 8; ++k) {
                const std::size_t nb =
                    std::size_t(z + NEIGHBOUR_DZ[k]) * std::size_t(width) + std::size_t(x + NEIGHBOUR_DX[k]);
                double slope = fc - r.filled[nb];
                if (NEIGHBOUR_DX[k] != 0 && NEIGHBOUR_DZ[k] != 0) slope *= INV_SQRT2;
                if (slope > best) {
                    best = slope;
                    to = std::uint32_t(nb);
                }
            }
            assert(to != c && "priority-flood + epsilon leaves every interior cell a lower neighbour");
            r.receiver[c] = to;
        }
    }
}

std::vector<double> drainageArea(const FlowRouting& routing, double cellSize)
{
    std::vector<double> area;
    drainageArea(routing, cellSize, area);
    return area;
}

void drainageArea(const FlowRouting& routing, double cellSize, std::vector<double>& area)
{
    const std::size_t n = routing.receiver.size();
    assert(routing.order.size() == n);
    area.assign(n, cellSize * cellSize);
    for (std::size_t i = n; i-- > 0;) {
        const std::uint32_t c = routing.order[i], to = routing.receiver[c];
        if (to != c) area[to] += area[c];
    }
}

std::vector<double> multipleFlowArea(const FlowRouting& routing, double cellSize, int exponent)
{
    if (exponent < 1 || exponent > 8) {
        throw Error(ErrorKind::BadInput, "multiple flow directions: exponent " + std::to_string(exponent) + " is not in 1..8");
    }
    const std::size_t n = routing.receiver.size();
    const int width = routing.width, height = routing.height;
    assert(routing.order.size() == n && routing.filled.size() == n);
    std::vector<double> area(n, cellSize * cellSize);
    // Interior cells from the highest to the lowest: every donor of a cell
    // (strictly higher on `filled`) is done before it.
    for (std::size_t i = n; i-- > 0;) {
        const std::uint32_t c = routing.order[i];
        if (routing.receiver[c] == c) continue; // an edge cell: the outlet
        const int x = int(c % std::uint32_t(width)), z = int(c / std::uint32_t(width));
        if (x < 1 || x >= width - 1 || z < 1 || z >= height - 1) continue;
        double weight[8];
        double total = 0.0;
        for (int k = 0; k < 8; ++k) {
            const std::size_t nb = std::size_t(z + NEIGHBOUR_DZ[k]) * std::size_t(width) + std::size_t(x + NEIGHBOUR_DX[k]);
            double slope = routing.filled[c] - routing.filled[nb];
            if (NEIGHBOUR_DX[k] != 0 && NEIGHBOUR_DZ[k] != 0) slope *= INV_SQRT2;
            double w = 0.0;
            if (slope > 0.0) {
                w = 1.0;
                for (int e = 0; e < exponent; ++e) w *= slope;
                // A drop so small that its power underflows still drains.
                if (!(w > 0.0)) w = std::numeric_limits<double>::min();
            }
            weight[k] = w;
            total += w;
        }
        assert(total > 0.0 && "priority-flood + epsilon leaves every interior cell a lower neighbour");
        for (int k = 0; k < 8; ++k) {
            if (weight[k] == 0.0) continue;
            const std::size_t nb = std::size_t(z + NEIGHBOUR_DZ[k]) * std::size_t(width) + std::size_t(x + NEIGHBOUR_DX[k]);
            area[nb] += area[c] * (weight[k] / total);
        }
    }
    return area;
}

double receiverDistance(const FlowRouting& routing, std::size_t cell, double cellSize)
{
    const std::size_t to = routing.receiver[cell], w = std::size_t(routing.width);
    if (to == cell) return 0.0;
    const bool diagonal = to % w != cell % w && to / w != cell / w;
    return diagonal ? cellSize * std::sqrt(2.0) : cellSize;
}

} // namespace strata::terrain
