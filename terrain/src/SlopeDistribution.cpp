// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/SlopeDistribution.h>

#include "HeightGridChecks.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace strata::terrain {

namespace {

/// Linear interpolation between the sorted values at ranks ⌊(n − 1)p⌋ and ⌈(n − 1)p⌉.
double percentile(const std::vector<double>& sorted, double p)
{
    const double rank = double(sorted.size() - 1) * p;
    const std::size_t lo = floorToInt<std::size_t>(rank), hi = std::min(sorted.size() - 1, lo + 1);
    const double t = rank - double(lo);
    return t == 0.0 ? sorted[lo] : sorted[lo] + t * (sorted[hi] - sorted[lo]);
}

} // namespace

SlopeDistribution measureSlopeDistribution(const std::vector<double>& heights, int width, int height, double cellSize,
                                           const SlopeDistributionOptions& options)
{
    detail::checkHeightGrid("slope distribution", heights, width, height, cellSize);
    if (!(options.cliffAngle > 0.0 && options.cliffAngle < 90.0))
        throw Error(ErrorKind::BadInput, "slope distribution: cliffAngle = " + formatNumber(options.cliffAngle) +
                                             " degrees must be in (0, 90)");
    const std::size_t W = std::size_t(width), H = std::size_t(height);
    const double toDegrees = 180.0 / std::numbers::pi, twoCells = 2.0 * cellSize;
    std::vector<double> angles;
    angles.reserve((W - 2) * (H - 2));
    std::size_t cliffs = 0;
    double sum = 0.0;
    for (std::size_t z = 1; z + 1 < H; ++z) {
        for (std::size_t x = 1; x + 1 < W; ++x) {
            const std::size_t c = z * W + x;
            const double gx = (heights[c + 1] - heights[c - 1]) / twoCells;
            const double gz = (heights[c + W] - heights[c - W]) / twoCells;
            const double angle = dmath::atan(dmath::hypot(gx, gz)) * toDegrees;
            angles.push_back(angle);
            sum += angle;
            cliffs += angle > options.cliffAngle ? 1 : 0;
        }
    }
    SlopeDistribution s;
    s.cells = angles.size();
    s.mean = sum / double(angles.size());
    s.cliffAngle = options.cliffAngle;
    s.cliffFraction = double(cliffs) / double(angles.size());
    std::sort(angles.begin(), angles.end());
    s.p10 = percentile(angles, 0.1);
    s.median = percentile(angles, 0.5);
    s.p90 = percentile(angles, 0.9);
    return s;
}

} // namespace strata::terrain
