// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/AnalyticShapes.h>

#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <openvdb/tools/SignedFloodFill.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace strata::meshing {

AnalyticShape analyticSphere(const glm::dvec3& c, double r)
{
    return {"sphere", [=](const glm::dvec3& p) { return glm::length(p - c) - r; },
            [=](const glm::dvec3& p) { return glm::normalize(p - c); }, c - r, c + r,
            4.0 / 3.0 * std::numbers::pi * r * r * r, true};
}

AnalyticShape analyticBox(const glm::dvec3& lo, const glm::dvec3& hi)
{
    const glm::dvec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
    auto sdf = [=](const glm::dvec3& p) {
        const glm::dvec3 q = glm::abs(p - c) - h;
        return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
    };
    auto gradient = [=](const glm::dvec3& p) {
        const glm::dvec3 d = p - c, q = glm::abs(d) - h;
        const glm::dvec3 s(d.x < 0 ? -1 : 1, d.y < 0 ? -1 : 1, d.z < 0 ? -1 : 1);
        if (q.x > 0 || q.y > 0 || q.z > 0) return glm::normalize(glm::max(q, 0.0) * s);
        if (q.x >= q.y && q.x >= q.z) return glm::dvec3(s.x, 0, 0);
        if (q.y >= q.z) return glm::dvec3(0, s.y, 0);
        return glm::dvec3(0, 0, s.z);
    };
    const glm::dvec3 e = hi - lo;
    return {"box", sdf, gradient, lo, hi, e.x * e.y * e.z, true};
}

// Torus around the y axis: major radius R, minor radius r.
AnalyticShape analyticTorus(const glm::dvec3& c, double R, double r)
{
    auto sdf = [=](const glm::dvec3& p) {
        const glm::dvec3 d = p - c;
        return std::hypot(std::hypot(d.x, d.z) - R, d.y) - r;
    };
    auto gradient = [=](const glm::dvec3& p) {
        const glm::dvec3 d = p - c;
        const double q = std::hypot(d.x, d.z);
        const glm::dvec3 ring = q > 0 ? glm::dvec3(d.x / q * R, 0, d.z / q * R) : glm::dvec3(R, 0, 0);
        return glm::normalize(d - ring);
    };
    return {"torus", sdf, gradient, c - glm::dvec3(R + r, r, R + r), c + glm::dvec3(R + r, r, R + r),
            2.0 * std::numbers::pi * std::numbers::pi * R * r * r, true};
}

// A gyroid sheet, thickness t, clipped by a sphere of radius `clip`:
// first-order distance (value over gradient length), not exact.
AnalyticShape analyticGyroid(double period, double thickness, double clip)
{
    const double k = 2.0 * std::numbers::pi / period;
    auto g = [=](const glm::dvec3& p) {
        return std::sin(k * p.x) * std::cos(k * p.y) + std::sin(k * p.y) * std::cos(k * p.z) +
               std::sin(k * p.z) * std::cos(k * p.x);
    };
    auto dg = [=](const glm::dvec3& p) {
        return k * glm::dvec3(std::cos(k * p.x) * std::cos(k * p.y) - std::sin(k * p.z) * std::sin(k * p.x),
                              -std::sin(k * p.x) * std::sin(k * p.y) + std::cos(k * p.y) * std::cos(k * p.z),
                              -std::sin(k * p.y) * std::sin(k * p.z) + std::cos(k * p.z) * std::cos(k * p.x));
    };
    auto sheet = [=](const glm::dvec3& p) {
        const double len = std::max(glm::length(dg(p)), 1e-6);
        return std::abs(g(p)) / len - 0.5 * thickness;
    };
    auto sdf = [=](const glm::dvec3& p) { return std::max(sheet(p), glm::length(p) - clip); };
    auto gradient = [=](const glm::dvec3& p) {
        if (glm::length(p) - clip > sheet(p)) return glm::normalize(p);
        const glm::dvec3 d = dg(p);
        return glm::normalize(g(p) < 0 ? -d : d);
    };
    return {"gyroid", sdf, gradient, glm::dvec3(-clip), glm::dvec3(clip), 0.0, false};
}

// A narrow-band level set of `shape`, half width `halfWidth` voxels.
openvdb::FloatGrid::Ptr levelSetFromShape(const AnalyticShape& shape, double voxelSize, double halfWidth)
{
    if (!(voxelSize > 0.0) || !(halfWidth >= 1.0)) {
        throw Error(ErrorKind::BadInput, "levelSetFromShape: voxel size must be positive and the half width at least 1 voxel");
    }
    openvdb::initialize();
    const float background = float(halfWidth * voxelSize);
    openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(background);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    const int pad = ceilToInt<int>(halfWidth) + 1;
    const openvdb::Coord lo(floorToInt<int>(shape.min.x / voxelSize) - pad, floorToInt<int>(shape.min.y / voxelSize) - pad,
                            floorToInt<int>(shape.min.z / voxelSize) - pad);
    const openvdb::Coord hi(ceilToInt<int>(shape.max.x / voxelSize) + pad, ceilToInt<int>(shape.max.y / voxelSize) + pad,
                            ceilToInt<int>(shape.max.z / voxelSize) + pad);
    openvdb::FloatGrid::Accessor accessor = grid->getAccessor();
    for (int x = lo.x(); x <= hi.x(); ++x)
        for (int y = lo.y(); y <= hi.y(); ++y)
            for (int z = lo.z(); z <= hi.z(); ++z) {
                const double d = shape.distance(glm::dvec3(x, y, z) * voxelSize);
                if (std::abs(d) < background) accessor.setValue(openvdb::Coord(x, y, z), float(d));
            }
    openvdb::tools::signedFloodFill(grid->tree());
    return grid;
}

} // namespace strata::meshing
