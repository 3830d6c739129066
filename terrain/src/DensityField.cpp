#include <strata/terrain/DensityField.h>

#include <glm/geometric.hpp>

namespace strata::terrain {

double DensityField::distanceBound(const glm::dvec3& p) const
{
    return density(p) / lipschitz();
}

double SphereField::density(const glm::dvec3& p) const
{
    return glm::length(p - mCenter) - mRadius;
}

} // namespace strata::terrain
