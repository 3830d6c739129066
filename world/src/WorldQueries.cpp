// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "WorldQueries.h"

#include <strata/Finite.h>
#include <strata/Format.h>

#include <strata/Error.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace strata::world::detail {

using openvdb::Coord;
using openvdb::CoordBBox;

double latticeDensity(const terrain::DensityField& field, const EditLayer& edits, double voxelSize,
                      const glm::dvec3& p)
{
    const double v = voxelSize;
    const glm::dvec3 x = p / v;
    const glm::dvec3 f = glm::floor(x);
    const glm::dvec3 t = x - f;
    Coord corners[8];
    for (int i = 0; i < 8; ++i)
        corners[i] = Coord(int(f.x) + (i & 1), int(f.y) + ((i >> 1) & 1), int(f.z) + ((i >> 2) & 1));
    float values[8];
    edits.samples(field, corners, 8, values);
    double result = 0.0;
    for (int i = 0; i < 8; ++i) {
        const double w = ((i & 1) ? t.x : 1.0 - t.x) * (((i >> 1) & 1) ? t.y : 1.0 - t.y) *
                         (((i >> 2) & 1) ? t.z : 1.0 - t.z);
        result += w * double(values[i]);
    }
    return result;
}

std::optional<RayHit> raycast(const terrain::DensityField& field, const EditLayer& edits, double voxelSize,
                              const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance)
{
    if (!isFinite(origin) || !isFinite(direction) || glm::length(direction) == 0.0 || !std::isfinite(maxDistance) ||
        maxDistance < 0.0)
        throw Error(ErrorKind::BadInput, "World::raycast: origin and direction must be finite, direction not zero, maxDistance >= 0 (got " +
                    formatNumber(maxDistance) + ")");
    const glm::dvec3 d = glm::normalize(direction);
    const double v = voxelSize;
    const double minStep = 0.25 * v;
    const double slope = std::sqrt(3.0) * std::max(1.0, field.lipschitz());
    auto at = [&](double t) { return latticeDensity(field, edits, voxelSize, origin + t * d); };

    double t0 = 0.0;
    double f0 = at(0.0);
    double hitT = -1.0;
    if (f0 < 0.0) {
        hitT = 0.0;
    } else {
        while (t0 < maxDistance) {
            double step = std::max(minStep, f0 / slope);
            if (step > minStep) {
                // Stored edits are not bounded by the field's slope: step
                // finely wherever an edit lies within the step.
                const glm::dvec3 p = origin + t0 * d;
                const glm::dvec3 lo = glm::floor((p - step) / v), hi = glm::ceil((p + step) / v);
                if (edits.anyIn(CoordBBox(Coord(int(lo.x), int(lo.y), int(lo.z)),
                                                 Coord(int(hi.x), int(hi.y), int(hi.z)))))
                    step = minStep;
            }
            const double t1 = std::min(maxDistance, t0 + step);
            const double f1 = at(t1);
            if (f1 < 0.0) {
                double a = t0, b = t1;
                for (int i = 0; i < 60 && b - a > 1e-9; ++i) {
                    const double m = 0.5 * (a + b);
                    if (at(m) < 0.0) b = m;
                    else a = m;
                }
                hitT = 0.5 * (a + b);
                break;
            }
            if (t1 >= maxDistance) break;
            t0 = t1;
            f0 = f1;
        }
    }
    if (hitT < 0.0) return std::nullopt;
    RayHit hit;
    hit.distance = hitT;
    hit.position = origin + hitT * d;
    const double h = 0.5 * v;
    auto density = [&](const glm::dvec3& p) { return latticeDensity(field, edits, voxelSize, p); };
    glm::dvec3 g(density(hit.position + glm::dvec3(h, 0, 0)) - density(hit.position - glm::dvec3(h, 0, 0)),
                 density(hit.position + glm::dvec3(0, h, 0)) - density(hit.position - glm::dvec3(0, h, 0)),
                 density(hit.position + glm::dvec3(0, 0, h)) - density(hit.position - glm::dvec3(0, 0, h)));
    hit.normal = glm::length(g) > 0.0 ? glm::normalize(g) : -d;
    return hit;
}

bool isBoxSolid(const terrain::DensityField& field, const EditLayer& edits, double voxelSize, const glm::dvec3& min,
                const glm::dvec3& max)
{
    if (!isFinite(min) || !isFinite(max) || min.x > max.x || min.y > max.y || min.z > max.z)
        throw Error(ErrorKind::BadInput, "World::isBoxSolid: the box must be finite with min <= max");
    const double v = voxelSize;
    const glm::dvec3 lo = glm::floor(min / v), hi = glm::floor(max / v) + 1.0;
    const Coord clo(int(lo.x), int(lo.y), int(lo.z)), chi(int(hi.x), int(hi.y), int(hi.z));
    const int B = 8;
    std::vector<Coord> points;
    std::vector<float> values;
    for (int bz = clo.z() & ~(B - 1); bz <= chi.z(); bz += B) {
        for (int by = clo.y() & ~(B - 1); by <= chi.y(); by += B) {
            for (int bx = clo.x() & ~(B - 1); bx <= chi.x(); bx += B) {
                const Coord b0(std::max(bx, clo.x()), std::max(by, clo.y()), std::max(bz, clo.z()));
                const Coord b1(std::min(bx + B - 1, chi.x()), std::min(by + B - 1, chi.y()), std::min(bz + B - 1, chi.z()));
                const CoordBBox box(b0, b1);
                if (!edits.anyIn(box)) {
                    const glm::dvec3 c0(b0.x(), b0.y(), b0.z()), c1(b1.x(), b1.y(), b1.z());
                    const double bound = field.distanceBound(0.5 * (c0 + c1) * v);
                    const double radius = 0.5 * glm::length(c1 - c0) * v;
                    if (bound < -radius) continue;     // all rock
                    if (bound > radius) return false; // all air
                }
                points.clear();
                for (auto c = box.begin(); c; ++c) points.push_back(*c);
                values.resize(points.size());
                edits.samples(field, points.data(), int(points.size()), values.data());
                for (float value : values)
                    if (!(value < 0.0f)) return false;
            }
        }
    }
    return true;
}

} // namespace strata::world::detail
