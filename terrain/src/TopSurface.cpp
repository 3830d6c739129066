// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/TopSurface.h>

#include <strata/Error.h>
#include <strata/Finite.h>
#include <strata/Format.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>

namespace strata::terrain {

namespace {

std::string showPoint(const glm::dvec3& p)
{
    return "(" + formatNumber(p.x) + ", " + formatNumber(p.y) + ", " + formatNumber(p.z) + ")";
}

double checked(double value, const glm::dvec3& p)
{
    if (std::isnan(value)) {
        throw Error(ErrorKind::Internal, "top surface: the density field is NaN at " + showPoint(p));
    }
    return value;
}

/// Columns along one axis: ⌊extent / cell⌋ + 1, rounding of 1e-9 cells forgiven.
double columnsAlong(double extent, double cellSize)
{
    return std::floor(extent / cellSize + 1e-9) + 1.0;
}

/// Bisection on the density from density(above) > 0 >= density(below) down
/// to TOP_SURFACE_TOLERANCE: the bracket's midpoint. `p` gives x and z.
double bisectSurface(const DensityField& field, glm::dvec3 p, double above, double below)
{
    while (above - below > TOP_SURFACE_TOLERANCE) {
        const double middle = 0.5 * (above + below);
        if (!(middle > below && middle < above)) break; // adjacent doubles: cannot halve further
        p.y = middle;
        if (checked(field.density(p), p) <= 0.0) {
            below = middle;
        } else {
            above = middle;
        }
    }
    return 0.5 * (above + below);
}

/// Where the column's sphere trace may start: the top of the highest
/// stretch of [y0, y1] that bounds() cannot prove to be air, halving
/// stretches down to PROVEN_AIR_LEAF metres (y0 when all is proven air).
/// A field's distance bound can be tiny far above its surface (a steep
/// heightfield's is (y − h)/√(1 + S²) for its largest slope S), while its
/// interval bound over a column is the column's own height range: this
/// skips the air in a few dozen bounds() calls instead of hundreds of
/// density evaluations. Nothing proven air can hold rock, so the trace
/// finds the same surface.
constexpr double PROVEN_AIR_LEAF = 0.5;

double firstUnprovenAir(const DensityField& field, double x, double z, double y0, double y1)
{
    double top = y1; // everything above is proven air
    while (top > y0) {
        double bottom = y0;
        // The highest stretch below `top` not proven air, by halving.
        for (;;) {
            const WorldBox box{{x, bottom, z}, {x, top, z}};
            if (field.bounds(box).lo > 0.0) { // air from bottom to top
                top = bottom;
                break;
            }
            if (top - bottom <= PROVEN_AIR_LEAF) return top;
            const double middle = 0.5 * (top + bottom);
            if (!(middle > bottom && middle < top)) return top;
            bottom = middle; // try the upper half first
        }
    }
    return y0;
}

/// The top surface height of the column at (x, z) between y0 and y1 (see the header).
double columnHeight(const DensityField& field, double x, double z, double y0, double y1)
{
    glm::dvec3 p(x, y1, z);
    if (checked(field.density(p), p) <= 0.0) return y1; // rock (or the surface) at the top
    const double start = firstUnprovenAir(field, x, z, y0, y1);
    if (start <= y0) return y0; // air all the way down: no rock in the column
    if (start < y1) {
        p.y = start;
        // Proven air ends at `start`, so it is air; were a field's bounds
        // and density to disagree there, bisect from the checked top.
        if (checked(field.density(p), p) <= 0.0) return bisectSurface(field, p, y1, start);
    }

    // Sphere trace down: no surface lies within distanceBound of an air
    // point, so a step of that size cannot cross one (steps of at least
    // TOP_SURFACE_MIN_STEP can cross a thinner layer, as documented).
    p.y = start;
    double above = start; // air
    double below = y0; // rock once found
    double bound = checked(field.distanceBound(p), p);
    for (;;) {
        // At least the minimum step, and a few doubles' spacing so that far
        // from the origin (|y| beyond about 1e13 m) every step still moves.
        const double least = std::max(TOP_SURFACE_MIN_STEP, 4.0 * std::abs(above) * DBL_EPSILON);
        const double next = std::max(y0, above - std::max(bound, least));
        p.y = next;
        bound = checked(field.distanceBound(p), p);
        if (bound <= 0.0) {
            below = next;
            break;
        }
        if (next <= y0) return y0; // air all the way down: no rock in the column
        above = next;
    }

    return bisectSurface(field, p, above, below);
}

} // namespace

TopSurfaceGrid sampleTopSurface(const DensityField& field, const WorldBox& region, double cellSize,
                                const std::function<bool(double)>& progress)
{
    if (!std::isfinite(cellSize) || cellSize <= 0.0) {
        throw Error(ErrorKind::BadInput, "top surface: the cell size must be finite and > 0 metres, not " + formatNumber(cellSize));
    }
    if (!isFinite(region.min) || !isFinite(region.max) || region.min.x > region.max.x || region.min.y > region.max.y ||
        region.min.z > region.max.z) {
        throw Error(ErrorKind::BadInput, "top surface: the region must be finite with min <= max on every axis, not " +
                    showPoint(region.min) + " to " + showPoint(region.max));
    }
    const double columns = columnsAlong(region.max.x - region.min.x, cellSize);
    const double rows = columnsAlong(region.max.z - region.min.z, cellSize);
    constexpr double MAX_AXIS = double(std::numeric_limits<int>::max());
    constexpr double MAX_CELLS = double(1 << 28);
    if (!(columns <= MAX_AXIS) || !(rows <= MAX_AXIS) || !(columns * rows <= MAX_CELLS)) {
        throw Error(ErrorKind::BadInput, "top surface: " + formatNumber(columns) + " x " + formatNumber(rows) + " columns of " +
                    formatNumber(cellSize) + " m are too many (at most 2^28): use a larger cell or a smaller region");
    }

    TopSurfaceGrid grid;
    grid.width = int(columns);
    grid.height = int(rows);
    grid.cellSize = cellSize;
    grid.origin = {region.min.x, region.min.z};
    grid.heights.assign(std::size_t(grid.width) * std::size_t(grid.height), 0.0);

    const auto report = [&progress](double fraction) {
        if (progress && !progress(fraction)) {
            throw Error(ErrorKind::Interrupted, "top surface sampling interrupted");
        }
    };
    report(0.0);
    // Batches of rows in parallel; progress (and interruption) between
    // batches, from this thread.
    const int batch = std::max(1, grid.height / 32);
    for (int begin = 0; begin < grid.height; begin += batch) {
        const int end = std::min(grid.height, begin + batch);
        tbb::parallel_for(tbb::blocked_range<int>(begin, end), [&](const tbb::blocked_range<int>& range) {
            for (int row = range.begin(); row != range.end(); ++row) {
                const double z = region.min.z + double(row) * cellSize;
                double* out = grid.heights.data() + std::size_t(row) * std::size_t(grid.width);
                for (int column = 0; column < grid.width; ++column) {
                    const double x = region.min.x + double(column) * cellSize;
                    out[column] = columnHeight(field, x, z, region.min.y, region.max.y);
                }
            }
        });
        report(double(end) / double(grid.height));
    }
    for (double h : grid.heights) {
        grid.columnsAtTop += h == region.max.y ? 1 : 0;
        grid.columnsAtBottom += h == region.min.y ? 1 : 0;
    }
    return grid;
}

} // namespace strata::terrain
