// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/StreamPowerErosion.h>

#include <strata/terrain/FlowRouting.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

using detail::show;

namespace {

void check(bool ok, const char* key, double value, const char* what)
{
    if (!ok) throw Error(ErrorKind::BadInput, std::string(key) + " = " + show(value) + " " + what, {"", 0, key, ""});
}

void checkOptions(const StreamPowerOptions& o)
{
    check(std::isfinite(o.cellSize) && o.cellSize > 0.0, "cell_size", o.cellSize, "must be a finite number > 0");
    check(std::isfinite(o.years) && o.years >= 0.0, "years", o.years, "must be a finite number >= 0");
    check(std::isfinite(o.timeStep) && o.timeStep > 0.0, "time_step", o.timeStep, "must be a finite number > 0");
    // years / time_step can be 1e13 within the keys' ranges: an int of it
    // overflowed (and ran 0 steps, a silently uneroded world).
    const double steps = std::ceil(o.years / o.timeStep - 1e-9);
    if (!(steps <= MAX_EROSION_STEPS)) {
        throw Error(ErrorKind::BadInput,
                    "years / time_step = " + show(o.years) + " / " + show(o.timeStep) + " is " + show(steps) +
                        " steps, more than the " + show(MAX_EROSION_STEPS) +
                        " a run may take: raise time_step or lower years",
                    {"", 0, "time_step", ""});
    }
    check(std::isfinite(o.uplift), "uplift", o.uplift, "must be a finite number");
    check(std::isfinite(o.erodibility) && o.erodibility >= 0.0, "erodibility", o.erodibility,
          "must be a finite number >= 0");
    check(std::isfinite(o.areaExponent) && o.areaExponent >= 0.0 && o.areaExponent <= 2.0, "m", o.areaExponent,
          "must be within [0, 2]");
    check(std::isfinite(o.slopeExponent) && o.slopeExponent > 0.0 && o.slopeExponent <= 4.0, "n",
          o.slopeExponent, "must be within (0, 4]");
    check(std::isfinite(o.diffusivity) && o.diffusivity >= 0.0, "diffusivity", o.diffusivity,
          "must be a finite number >= 0");
}

/// pow(area, m) for the incision, remembered for D8 areas of up to
/// TABLE_CELLS cells: a D8 area is a sum of whole cells, and most cells drain
/// only a few, so nearly every call of the evolution's hottest pow (about a
/// third of a step) is a lookup. Exact: a remembered value is used only where
/// the area is bit for bit the cell count times the cell's area, the very
/// argument it was computed from.
class AreaPower
{
public:
    AreaPower(double cellArea, double exponent)
        : mCellArea(cellArea)
        , mExponent(exponent)
        , mTable(TABLE_CELLS, -1.0)
    {
    }

    double operator()(double area)
    {
        const double cells = std::floor(area / mCellArea + 0.5);
        if (cells >= 1.0 && cells < double(TABLE_CELLS) && cells * mCellArea == area) {
            double& remembered = mTable[std::size_t(cells)];
            if (remembered < 0.0) remembered = dmath::pow(area, mExponent);
            return remembered;
        }
        return dmath::pow(area, mExponent);
    }

private:
    static constexpr std::size_t TABLE_CELLS = 1 << 16;
    double mCellArea, mExponent;
    std::vector<double> mTable; // -1: not computed yet (a power of an area > 0 is >= 0)
};

bool onEdge(int x, int z, int width, int height) { return x == 0 || z == 0 || x == width - 1 || z == height - 1; }

/// The root x in (0, c] of x − c + F·xⁿ = 0 (c > 0, F >= 0): Newton steps
/// from x = c, kept inside a shrinking bracket by bisection.
double solveIncision(double c, double f, double n)
{
    double lo = 0.0, hi = c, x = c;
    for (int i = 0; i < 40; ++i) {
        const double xn = dmath::pow(x, n);
        const double g = x - c + f * xn;
        if (g > 0.0) hi = x;
        else lo = x;
        const double dg = 1.0 + f * n * (x > 0.0 ? xn / x : 0.0);
        double next = x - g / dg;
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - x) <= 1e-12 * c) return next;
        x = next;
    }
    return x;
}

/// One backward-Euler step of x' = k·x'' along a line of n values (stride
/// apart), the ends fixed: solves (1 + 2k)·δ_i − k·(δ_{i−1} + δ_{i+1}) =
/// k·(h_{i−1} − 2h_i + h_{i+1}) for the change δ (δ = 0 at the ends) by the
/// Thomas algorithm (diagonally dominant: no pivoting), then adds it. In
/// this increment form flat ground stays exactly flat and heights far from
/// zero lose no precision.
void implicitLine(double* h, std::size_t stride, int n, double k, std::vector<double>& c, std::vector<double>& d)
{
    if (n < 3) return;
    auto at = [&](int i) -> double& { return h[std::size_t(i) * stride]; };
    c.assign(std::size_t(n), 0.0);
    d.assign(std::size_t(n), 0.0);
    for (int i = 1; i <= n - 2; ++i) {
        const double pivot = 1.0 + 2.0 * k + k * c[std::size_t(i - 1)];
        const double rhs = k * ((at(i - 1) - at(i)) + (at(i + 1) - at(i)));
        c[std::size_t(i)] = -k / pivot;
        d[std::size_t(i)] = (rhs + k * d[std::size_t(i - 1)]) / pivot;
    }
    double next = d[std::size_t(n - 2)];
    std::vector<double>& delta = d; // overwritten from the end: d[i] is read before delta[i] is written
    delta[std::size_t(n - 2)] = next;
    for (int i = n - 3; i >= 1; --i) {
        next = d[std::size_t(i)] - c[std::size_t(i)] * next;
        delta[std::size_t(i)] = next;
    }
    for (int i = 1; i <= n - 2; ++i) at(i) += delta[std::size_t(i)];
}

/// Hillslope creep over dt: ∂h/∂t = D∇²h by backward Euler along x, then
/// along z (k = D·dt/dx²): unconditionally stable at any cell size and
/// step, O(n). Lines in parallel, each solved alone: the same bits on any
/// thread count. The edge stays fixed.
void diffuse(std::vector<double>& h, int width, int height, double k)
{
    const std::size_t w = std::size_t(width);
    tbb::parallel_for(tbb::blocked_range<int>(1, height - 1, 16), [&](const tbb::blocked_range<int>& rows) {
        std::vector<double> c, d;
        for (int z = rows.begin(); z < rows.end(); ++z) implicitLine(h.data() + std::size_t(z) * w, 1, width, k, c, d);
    });
    tbb::parallel_for(tbb::blocked_range<int>(1, width - 1, 16), [&](const tbb::blocked_range<int>& columns) {
        std::vector<double> c, d;
        for (int x = columns.begin(); x < columns.end(); ++x) implicitLine(h.data() + std::size_t(x), w, height, k, c, d);
    });
}

} // namespace

StreamPowerResult evolveLandscape(std::vector<double> heights, int width, int height,
                                  const std::vector<double>& upliftMap, const StreamPowerOptions& options,
                                  const std::function<bool(double)>& progress)
{
    checkOptions(options);
    if (width < 1 || height < 1 || heights.size() != std::size_t(width) * std::size_t(height)) {
        throw Error(ErrorKind::BadInput, "erosion grid: " + std::to_string(heights.size()) + " heights for " + std::to_string(width) +
                    "x" + std::to_string(height) + " cells");
    }
    if (!upliftMap.empty() && upliftMap.size() != heights.size()) {
        throw Error(ErrorKind::BadInput, "erosion grid: the uplift map has " + std::to_string(upliftMap.size()) + " values for " +
                    std::to_string(heights.size()) + " cells");
    }
    const std::size_t count = heights.size();
    const double dx = options.cellSize, cellArea = dx * dx;
    // A cell lies in a lake when the fill raised it by more than this: far
    // above the smallest-step gradient the fill leaves on flats.
    const double lakeTolerance = 1e-4 * dx;

    StreamPowerResult r;
    r.width = width;
    r.height = height;
    r.wear.assign(count, 0.0);
    r.sediment.assign(count, 0.0);
    r.lakeDepth.assign(count, 0.0);

    std::vector<std::uint8_t> edge(count); // bytes: read in the flow order, at random
    for (int z = 0; z < height; ++z) {
        for (int x = 0; x < width; ++x) edge[std::size_t(z) * std::size_t(width) + std::size_t(x)] = onEdge(x, z, width, height);
    }

    const int steps = options.years > 0.0 ? ceilToInt<int>(options.years / options.timeStep - 1e-9) : 0;
    std::vector<double> flux(count), previous(count), area;
    AreaPower areaPower(cellArea, options.areaExponent);
    // receiverDistance() gives one of two distances: their powers once.
    const double straightPower = dmath::pow(dx, options.slopeExponent);
    const double diagonalPower = dmath::pow(dx * std::sqrt(2.0), options.slopeExponent);
    FlowRouting routing;
    for (int step = 0; step < steps; ++step) {
        const double dt = std::min(options.timeStep, options.years - double(step) * options.timeStep);
        routeFlow(heights, width, height, dx, routing);
        drainageArea(routing, dx, area);

        // Uplift, then implicit incision from the outlets upstream: each
        // receiver is already at its new height when its donors are solved.
        previous = heights;
        for (const std::uint32_t i : routing.order) {
            if (edge[i]) continue;
            const double lifted = heights[i] + options.uplift * dt * (upliftMap.empty() ? 1.0 : upliftMap[i]);
            heights[i] = lifted;
            const bool underwater = routing.filled[i] - previous[i] > lakeTolerance;
            const std::uint32_t rcv = routing.receiver[i];
            const double drop = lifted - heights[rcv];
            if (underwater || drop <= 0.0 || options.erodibility == 0.0) continue;
            // An interior cell drains to one of its 8 neighbours (routeFlow).
            const double distancePower = receiverDistance(routing, i, dx) == dx ? straightPower : diagonalPower;
            const double f = options.erodibility * dt * areaPower(area[i]) / distancePower;
            const double x = options.slopeExponent == 1.0 ? drop / (1.0 + f) : solveIncision(drop, f, options.slopeExponent);
            heights[i] = heights[rcv] + x;
        }

        // Sediment: what each cell lost flows down; lakes keep it up to
        // their spill level; what reaches the edge leaves.
        std::fill(flux.begin(), flux.end(), 0.0);
        for (auto it = routing.order.rbegin(); it != routing.order.rend(); ++it) {
            const std::uint32_t i = *it;
            if (edge[i]) {
                r.carriedOut += flux[i];
                continue;
            }
            const double lifted = previous[i] + options.uplift * dt * (upliftMap.empty() ? 1.0 : upliftMap[i]);
            const double eroded = std::max(0.0, lifted - heights[i]);
            r.eroded += eroded * cellArea;
            r.wear[i] += eroded;
            r.sediment[i] = std::max(0.0, r.sediment[i] - eroded);
            flux[i] += eroded * cellArea;
            // Only lakes trap sediment (cells the fill covered at the step's
            // start), never a channel cut below its old level.
            const bool lake = routing.filled[i] - previous[i] > lakeTolerance;
            const double room = (routing.filled[i] - heights[i]) * cellArea;
            if (lake && room > 0.0 && flux[i] > 0.0) {
                const double laid = std::min(flux[i], room);
                heights[i] += laid / cellArea;
                r.sediment[i] += laid / cellArea;
                r.deposited += laid;
                flux[i] -= laid;
            }
            flux[routing.receiver[i]] += flux[i];
        }

        // Hillslope creep.
        if (options.diffusivity > 0.0 && width > 2 && height > 2) {
            previous = heights;
            diffuse(heights, width, height, options.diffusivity * dt / cellArea);
            double inside = 0.0;
            for (std::size_t i = 0; i < count; ++i) {
                const double change = heights[i] - previous[i];
                if (edge[i]) continue;
                inside += change;
                if (change < 0.0) {
                    r.wear[i] -= change;
                    r.sediment[i] = std::max(0.0, r.sediment[i] + change);
                } else {
                    r.sediment[i] += change;
                }
            }
            r.diffusedOut -= inside * cellArea;
        }
        r.steps = step + 1;
        if (progress && !progress(double(step + 1) / double(steps))) throw Error(ErrorKind::Interrupted, "erosion interrupted");
    }

    routeFlow(heights, width, height, dx, routing);
    r.area = drainageArea(routing, dx);
    r.flowArea = multipleFlowArea(routing, dx);
    for (std::size_t i = 0; i < count; ++i) r.lakeDepth[i] = routing.filled[i] - heights[i];
    r.heights = std::move(heights);
    return r;
}

} // namespace strata::terrain
