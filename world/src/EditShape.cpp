// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/world/WorldTypes.h>

#include <strata/Finite.h>

#include <strata/Error.h>
#include <strata/terrain/Primitives.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>

namespace strata::world {

namespace {


std::string str(const glm::dvec3& v)
{
    std::string out = "(";
    out += std::to_string(v.x);
    out += ", ";
    out += std::to_string(v.y);
    out += ", ";
    out += std::to_string(v.z);
    out += ")";
    return out;
}

/// Throws strata::Error("edit shape: " + the parts), appended piece by piece
/// (GCC 12 warns falsely, -Wrestrict, on a chain of + of temporaries).
[[noreturn]] void fail(std::initializer_list<std::string> parts)
{
    std::string message = "edit shape: ";
    for (const std::string& part : parts) message += part;
    throw Error(ErrorKind::BadInput, message);
}

} // namespace

std::size_t ChunkMeshData::memoryBytes() const
{
    return mesh.positions.capacity() * sizeof(glm::vec3) + mesh.normals.capacity() * sizeof(glm::vec3) +
           mesh.indices.capacity() * sizeof(std::uint32_t) + vertexCells.capacity() * sizeof(VertexCell);
}

EditShape EditShape::sphere(const glm::dvec3& centre, double radius)
{
    EditShape s;
    s.kind = Kind::SPHERE;
    s.a = centre;
    s.radius = radius;
    return s;
}

EditShape EditShape::box(const glm::dvec3& centre, const glm::dvec3& halfSize, double rounding)
{
    EditShape s;
    s.kind = Kind::BOX;
    s.a = centre;
    s.halfSize = halfSize;
    s.radius = rounding;
    return s;
}

EditShape EditShape::capsule(const glm::dvec3& a, const glm::dvec3& b, double radius)
{
    EditShape s;
    s.kind = Kind::CAPSULE;
    s.a = a;
    s.b = b;
    s.radius = radius;
    return s;
}

EditShape EditShape::path(std::vector<glm::dvec3> points, double radius)
{
    EditShape s;
    s.kind = Kind::PATH;
    s.points = std::move(points);
    s.radius = radius;
    return s;
}

void EditShape::validate() const
{
    switch (kind) {
    case Kind::SPHERE:
    case Kind::CAPSULE:
        if (!isFinite(a) || (kind == Kind::CAPSULE && !isFinite(b))) fail({"end point ", str(a), " is not finite"});
        if (!std::isfinite(radius) || radius <= 0.0) fail({"radius = ", std::to_string(radius), " must be > 0"});
        break;
    case Kind::BOX:
        if (!isFinite(a)) fail({"box centre ", str(a), " is not finite"});
        if (!isFinite(halfSize) || halfSize.x <= 0.0 || halfSize.y <= 0.0 || halfSize.z <= 0.0)
            fail({"box halfSize ", str(halfSize), " must be > 0 per axis"});
        if (!std::isfinite(radius) || radius < 0.0 || radius > std::min({halfSize.x, halfSize.y, halfSize.z}))
            fail({"box rounding = ", std::to_string(radius), " must be in [0, min(halfSize)]"});
        break;
    case Kind::PATH:
        if (points.empty()) fail({"path has no points"});
        for (const glm::dvec3& p : points)
            if (!isFinite(p)) fail({"path point ", str(p), " is not finite"});
        if (!std::isfinite(radius) || radius <= 0.0) fail({"radius = ", std::to_string(radius), " must be > 0"});
        break;
    }
}

double EditShape::distance(const glm::dvec3& p) const
{
    switch (kind) {
    case Kind::SPHERE: return terrain::SphereField(a, radius).density(p);
    case Kind::BOX: return terrain::BoxField(a, halfSize, radius).density(p);
    case Kind::CAPSULE: return terrain::CapsuleField(a, b, radius).density(p);
    case Kind::PATH: {
        if (points.size() == 1) return terrain::SphereField(points[0], radius).density(p);
        double d = HUGE_VAL;
        for (std::size_t i = 0; i + 1 < points.size(); ++i)
            d = std::min(d, terrain::CapsuleField(points[i], points[i + 1], radius).density(p));
        return d;
    }
    }
    return HUGE_VAL;
}

void EditShape::bounds(glm::dvec3& min, glm::dvec3& max) const
{
    switch (kind) {
    case Kind::SPHERE:
        min = a - radius;
        max = a + radius;
        return;
    case Kind::BOX:
        min = a - halfSize;
        max = a + halfSize;
        return;
    case Kind::CAPSULE:
        min = glm::min(a, b) - radius;
        max = glm::max(a, b) + radius;
        return;
    case Kind::PATH:
        min = glm::dvec3(HUGE_VAL);
        max = glm::dvec3(-HUGE_VAL);
        for (const glm::dvec3& p : points) {
            min = glm::min(min, p - radius);
            max = glm::max(max, p + radius);
        }
        return;
    }
}

} // namespace strata::world
