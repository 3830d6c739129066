// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/LevelSetQuality.h>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

SdfQuality measureSdfQuality(const openvdb::FloatGrid& grid, double bandFraction)
{
    SdfQuality q;
    const double h = grid.voxelSize()[0];
    const double limit = bandFraction * double(grid.background());
    openvdb::FloatGrid::ConstAccessor acc = grid.getConstAccessor();
    double sum = 0.0, sumGradient = 0.0;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue() || std::abs(*it) >= limit) continue;
        const openvdb::Coord c = it.getCoord();
        float v[6];
        bool ok = true;
        const openvdb::Coord offsets[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (int i = 0; i < 6 && ok; ++i) ok = acc.probeValue(c + offsets[i], v[i]);
        if (!ok) continue;
        const double gx = (double(v[0]) - v[1]) / (2.0 * h), gy = (double(v[2]) - v[3]) / (2.0 * h),
                     gz = (double(v[4]) - v[5]) / (2.0 * h);
        const double g = std::sqrt(gx * gx + gy * gy + gz * gz);
        const double e = std::abs(g - 1.0);
        sum += e;
        sumGradient += g;
        q.maxError = std::max(q.maxError, e);
        ++q.voxels;
    }
    if (q.voxels > 0) {
        q.meanError = sum / double(q.voxels);
        q.meanGradient = sumGradient / double(q.voxels);
    }
    return q;
}

} // namespace strata::terrain
