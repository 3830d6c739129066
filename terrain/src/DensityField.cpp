#include <strata/terrain/DensityField.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>

namespace strata::terrain {

double WorldBox::radius() const
{
    return 0.5 * glm::length(max - min);
}

Interval DensityField::bounds(const WorldBox& box) const
{
    // Lipschitz: |d(p) − d(c)| <= L·|p − c| <= L·radius for p in the box;
    // and d >= minDensity() everywhere by that function's contract.
    const double d = density(box.centre());
    const double reach = lipschitz() * box.radius();
    return {std::max(d - reach, minDensity()), d + reach};
}

double DensityField::distanceBound(const glm::dvec3& p) const
{
    return density(p) / lipschitz();
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
