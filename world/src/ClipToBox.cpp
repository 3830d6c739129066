// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ClipToBox.h"

#include <strata/IntegerMath.h>

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <map>

namespace strata::world::detail {

namespace {

using Key = std::array<std::int64_t, 3>;

struct Corner
{
    glm::dvec3 position;
    glm::dvec3 normal;
    std::uint32_t index; ///< UINT32_MAX until it is looked up
};

class Clipper
{
public:
    // Only cut points are indexed: a vertex on a face plane is kept as
    // itself (Sutherland–Hodgman cuts only edges that cross a plane
    // strictly), so a cut never lands on an original vertex.
    Clipper(ClipMesh& mesh, double quantum)
        : mMesh(mesh)
        , mQuantum(quantum)
    {
    }

    Key key(const glm::dvec3& p) const
    {
        return {roundToInt<std::int64_t>(p.x * mQuantum), roundToInt<std::int64_t>(p.y * mQuantum),
                roundToInt<std::int64_t>(p.z * mQuantum)};
    }

    /// The cut of edge a–b by the plane x[axis] = c (a and b on either side).
    Corner cut(const Corner& p, const Corner& q, int axis, double c) const
    {
        const Corner& a = p.position[axis] < q.position[axis] ? p : q;
        const Corner& b = p.position[axis] < q.position[axis] ? q : p;
        const double t = (c - a.position[axis]) / (b.position[axis] - a.position[axis]);
        Corner out;
        for (int k = 0; k < 3; ++k) {
            const double v = a.position[k] + t * (b.position[k] - a.position[k]);
            out.position[k] = k == axis ? c : std::round(v * mQuantum) / mQuantum;
        }
        const glm::dvec3 n = a.normal + t * (b.normal - a.normal);
        const double len = glm::length(n);
        out.normal = len > 1e-12 ? n / len : a.normal;
        out.index = UINT32_MAX;
        return out;
    }

    std::uint32_t indexOf(Corner& c)
    {
        if (c.index != UINT32_MAX) return c.index;
        const auto [it, added] = mIndex.emplace(key(c.position), std::uint32_t(mMesh.positions.size()));
        if (added) {
            mMesh.positions.push_back(c.position);
            mMesh.normals.push_back(c.normal);
        }
        c.index = it->second;
        return c.index;
    }

private:
    ClipMesh& mMesh;
    double mQuantum;
    std::map<Key, std::uint32_t> mIndex;
};

/// Sutherland–Hodgman against one plane: keeps the side where
/// sign·(x[axis] − c) <= 0.
void clipPolygon(std::vector<Corner>& poly, std::vector<Corner>& scratch, const Clipper& clipper, int axis, double c,
                 double sign)
{
    scratch.clear();
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Corner& p = poly[i];
        const Corner& q = poly[(i + 1) % n];
        const double dp = sign * (p.position[axis] - c), dq = sign * (q.position[axis] - c);
        if (dp <= 0.0) scratch.push_back(p);
        if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) scratch.push_back(clipper.cut(p, q, axis, c));
    }
    poly.swap(scratch);
}

} // namespace

void clipToBox(ClipMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi, double quantum)
{
    Clipper clipper(mesh, quantum);
    std::vector<std::uint32_t> out;
    out.reserve(mesh.indices.size());
    std::vector<Corner> poly, scratch;
    const auto inside = [&](const glm::dvec3& p) {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
    };
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t v[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        if (inside(mesh.positions[v[0]]) && inside(mesh.positions[v[1]]) && inside(mesh.positions[v[2]])) {
            out.insert(out.end(), v, v + 3);
            continue;
        }
        poly.clear();
        for (std::uint32_t i : v) poly.push_back(Corner{mesh.positions[i], mesh.normals[i], i});
        for (int axis = 0; axis < 3 && poly.size() >= 3; ++axis) {
            clipPolygon(poly, scratch, clipper, axis, lo[axis], -1.0);
            if (poly.size() >= 3) clipPolygon(poly, scratch, clipper, axis, hi[axis], 1.0);
        }
        if (poly.size() < 3) continue;
        std::vector<std::uint32_t> ring;
        for (Corner& c : poly) {
            const std::uint32_t i = clipper.indexOf(c);
            if (ring.empty() || ring.back() != i) ring.push_back(i);
        }
        while (ring.size() > 1 && ring.back() == ring.front()) ring.pop_back();
        for (std::size_t i = 1; i + 1 < ring.size(); ++i) {
            const std::uint32_t a = ring[0], b = ring[i], c = ring[i + 1];
            if (a == b || b == c || a == c) continue;
            out.insert(out.end(), {a, b, c});
        }
    }
    // Drop the vertices no triangle uses, keeping the order of the rest.
    std::vector<std::uint32_t> remap(mesh.positions.size(), UINT32_MAX);
    for (std::uint32_t i : out) remap[i] = 0;
    std::uint32_t next = 0;
    for (std::size_t i = 0; i < remap.size(); ++i) {
        if (remap[i] == UINT32_MAX) continue;
        remap[i] = next;
        mesh.positions[next] = mesh.positions[i];
        mesh.normals[next] = mesh.normals[i];
        ++next;
    }
    mesh.positions.resize(next);
    mesh.normals.resize(next);
    for (std::uint32_t& i : out) i = remap[i];
    mesh.indices = std::move(out);
}

} // namespace strata::world::detail
