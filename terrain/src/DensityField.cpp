// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/DensityField.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>

namespace strata::terrain {

double WorldBox::radius() const
{
    return 0.5 * glm::length(max - min);
}

WorldBox spannedBox(const PointBlock& points)
{
    if (points.count == 0) return {};
    WorldBox box{{points.x[0], points.y[0], points.z[0]}, {points.x[0], points.y[0], points.z[0]}};
    for (std::size_t i = 1; i < points.count; ++i) {
        box.min = glm::min(box.min, glm::dvec3(points.x[i], points.y[i], points.z[i]));
        box.max = glm::max(box.max, glm::dvec3(points.x[i], points.y[i], points.z[i]));
    }
    return box;
}

Interval DensityField::bounds(const WorldBox& box) const
{
    // Lipschitz: |d(p) − d(c)| <= L·|p − c| <= L·radius for p in the box;
    // and d >= minDensity() everywhere by that function's contract.
    const double d = density(box.centre());
    const double reach = lipschitz() * box.radius();
    return {std::max(d - reach, minDensity()), d + reach};
}

void DensityField::densities(const PointBlock& points, double* out) const
{
    for (std::size_t i = 0; i < points.count; ++i) out[i] = density({points.x[i], points.y[i], points.z[i]});
}

double DensityField::distanceBound(const glm::dvec3& p) const
{
    return density(p) / lipschitz();
}

void DensityField::distanceBounds(const PointBlock& points, double* out) const
{
    for (std::size_t i = 0; i < points.count; ++i) out[i] = distanceBound({points.x[i], points.y[i], points.z[i]});
}

double SphereField::density(const glm::dvec3& p) const
{
    return glm::length(p - mCenter) - mRadius;
}

Interval SphereField::bounds(const WorldBox& box) const
{
    // |p − centre| over the box: smallest at the box point nearest the
    // centre (the clamp), largest at the corner farthest from it.
    const glm::dvec3 nearest = glm::clamp(mCenter, box.min, box.max);
    const glm::dvec3 farthest = glm::max(glm::abs(box.min - mCenter), glm::abs(box.max - mCenter));
    return {glm::length(nearest - mCenter) - mRadius, glm::length(farthest) - mRadius};
}

} // namespace strata::terrain
