#include <strata/terrain/Primitives.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace strata::terrain {

Interval convexBounds(const DensityField& field, const WorldBox& box)
{
    double hi = -HUGE_VAL;
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                           (corner & 4) ? box.max.z : box.min.z);
        hi = std::max(hi, field.density(p));
    }
    return {field.density(box.centre()) - box.radius(), hi};
}

BoxField::BoxField(const glm::dvec3& center, const glm::dvec3& halfSize, double rounding)
    : mCenter(center), mHalf(halfSize - rounding), mRounding(rounding)
{
    assert(rounding >= 0.0 && rounding <= std::min({halfSize.x, halfSize.y, halfSize.z}));
}

double BoxField::density(const glm::dvec3& p) const
{
    const glm::dvec3 q = glm::abs(p - mCenter) - mHalf;
    return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0) - mRounding;
}

CapsuleField::CapsuleField(const glm::dvec3& a, const glm::dvec3& b, double radius)
    : mA(a), mB(b), mRadius(radius)
{
}

double CapsuleField::density(const glm::dvec3& p) const
{
    const glm::dvec3 ab = mB - mA, ap = p - mA;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(ap, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(ap - t * ab) - mRadius;
}

PlaneField::PlaneField(const glm::dvec3& normal, double offset)
    : mNormal(glm::normalize(normal)), mOffset(offset)
{
    assert(glm::length(normal) > 0.0);
}

double PlaneField::density(const glm::dvec3& p) const
{
    return glm::dot(mNormal, p) - mOffset;
}

} // namespace strata::terrain

namespace strata::terrain {

Interval PlaneField::bounds(const WorldBox& box) const
{
    const glm::dvec3 half = 0.5 * (box.max - box.min);
    const double d = density(box.centre());
    const double reach = glm::dot(glm::abs(mNormal), half);
    return {d - reach, d + reach};
}

} // namespace strata::terrain
