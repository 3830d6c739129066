// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/Primitives.h>

#include "NodeRegistrations.h"
#include <strata/Format.h>
#include <strata/terrain/NodeRegistry.h>

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

namespace strata::terrain {

void registerPrimitiveNodes(NodeRegistry& registry)
{
    NodeType sphere{"sphere", "a ball: exact distance", {}, {}};
    sphere.keys = {vec3Key("center", glm::dvec3(0.0), HUGE_LENGTH, "m", "centre"),
                   numberKey("radius", 10.0, 1e-4, MAX_LENGTH, "m", "radius")};
    sphere.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<SphereField>(a.vec3("center"), a.number("radius"));
    };
    registry.add(std::move(sphere));

    NodeType box{"box", "an axis-aligned box, optionally with rounded edges: exact distance", {}, {}};
    box.keys = {vec3Key("center", glm::dvec3(0.0), HUGE_LENGTH, "m", "centre"),
                vec3Key("size", glm::dvec3(10.0), MAX_LENGTH, "m", "edge lengths, each > 0"),
                numberKey("rounding", 0.0, 0.0, MAX_LENGTH, "m", "edge radius, at most half the shortest edge")};
    box.build = [](const NodeArgs& a) -> DensityFieldPtr {
        const glm::dvec3 size = a.vec3("size");
        for (int axis = 0; axis < 3; ++axis) {
            if (!(size[axis] > 0.0)) a.fail("size", "must be positive on every axis");
        }
        const double limit = 0.5 * std::min({size.x, size.y, size.z});
        const double rounding = a.number("rounding");
        if (rounding > limit) {
            a.fail("rounding", "= " + formatNumber(rounding) + " is out of range [0, " + formatNumber(limit) + "]");
        }
        return std::make_shared<BoxField>(a.vec3("center"), 0.5 * size, rounding);
    };
    registry.add(std::move(box));

    NodeType capsule{"capsule", "a segment a..b swept by a ball: exact distance", {}, {}};
    capsule.keys = {vec3Key("a", glm::dvec3(0.0, -5.0, 0.0), HUGE_LENGTH, "m", "one end of the axis"),
                    vec3Key("b", glm::dvec3(0.0, 5.0, 0.0), HUGE_LENGTH, "m", "the other end"),
                    numberKey("radius", 3.0, 1e-4, MAX_LENGTH, "m", "radius")};
    capsule.build = [](const NodeArgs& a) -> DensityFieldPtr {
        return std::make_shared<CapsuleField>(a.vec3("a"), a.vec3("b"), a.number("radius"));
    };
    registry.add(std::move(capsule));

    NodeType plane{"plane", "the half-space dot(normal, p) < offset is solid", {}, {}};
    plane.keys = {vec3Key("normal", glm::dvec3(0.0, 1.0, 0.0), 1.0, "", "points out of the solid"),
                  numberKey("offset", 0.0, -HUGE_LENGTH, HUGE_LENGTH, "m", "distance of the plane along normal")};
    plane.build = [](const NodeArgs& a) -> DensityFieldPtr {
        const glm::dvec3 normal = a.vec3("normal");
        if (!(normal != glm::dvec3(0.0))) a.fail("normal", "must not be [0, 0, 0]");
        return std::make_shared<PlaneField>(normal, a.number("offset"));
    };
    registry.add(std::move(plane));
}

} // namespace strata::terrain
