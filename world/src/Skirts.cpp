// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "Skirts.h"

#include <strata/IntegerMath.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <functional>
#include <cmath>
#include <map>
#include <utility>

namespace strata::world::detail {

namespace {

/// The face of [lo, hi] that both ends of an edge lie on, as a face bit
/// index (2·axis + side), or −1.
int sharedFace(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& lo, const glm::dvec3& hi, unsigned faces)
{
    for (int axis = 0; axis < 3; ++axis) {
        if ((faces >> (2 * axis) & 1u) && a[axis] == lo[axis] && b[axis] == lo[axis]) return 2 * axis;
        if ((faces >> (2 * axis + 1) & 1u) && a[axis] == hi[axis] && b[axis] == hi[axis]) return 2 * axis + 1;
    }
    return -1;
}

/// Away from the air within the plane of `axis`: along the in-plane axis on
/// which the normal's in-plane part, reversed, is largest (y first: on the
/// sides of a tile, terrain hangs its skirt straight down, a cliff across
/// the face horizontally into the rock, a cave ceiling up); zero where the
/// surface lies within SKIRT_MIN_SINE of the plane (that part shorter than
/// its sine). One of four directions per face keeps neighbouring skirt
/// vertices parallel, where the normals' own directions would twist a
/// quad whose top edge is short.
glm::dvec3 skirtDirection(const glm::dvec3& normal, int axis)
{
    glm::dvec3 d = -normal;
    d[axis] = 0.0;
    const double len = glm::length(d);
    if (!(len >= SKIRT_MIN_SINE * glm::length(normal)) || len == 0.0) return glm::dvec3(0.0);
    const int first = axis == 1 ? 0 : 1, second = axis == 2 ? 0 : 2;
    const int along = std::abs(d[first]) >= std::abs(d[second]) ? first : second;
    glm::dvec3 out(0.0);
    out[along] = d[along] > 0.0 ? 1.0 : -1.0;
    return out;
}

} // namespace

namespace {

/// How far a skirt from `top` along `d` may reach: `depth`, or less where
/// it would leave the rock again (into a cave, under an overhang's lip, out
/// of a thin ridge) after having entered it: there it ends at the crossing.
/// Marched in steps of a quarter cell; the crossing interpolated between
/// the two densities around it.
double rockDepth(const glm::dvec3& top, const glm::dvec3& d, double depth,
                 const std::function<double(const glm::dvec3&)>& density)
{
    if (!density) return depth;
    constexpr double STEP = 0.25; // cells
    bool inRock = false;
    double previous = 0.0;
    const int steps = ceilToInt<int>(depth / STEP);
    for (int s = 1; s <= steps; ++s) {
        const double t = std::min(depth, s * STEP);
        const double value = density(top + t * d);
        if (value < 0.0) {
            inRock = true;
        } else if (inRock) {
            const double t0 = (s - 1) * STEP;
            return t0 + (t - t0) * previous / (previous - value); // previous < 0 <= value
        }
        previous = value;
    }
    return depth;
}

} // namespace

ClipMesh makeSkirts(const ClipMesh& surface, const glm::dvec3& lo, const glm::dvec3& hi, unsigned faces, double depth,
                    const std::function<double(const glm::dvec3&)>& density)
{
    ClipMesh skirt;
    if (depth <= 0.0 || faces == 0) return skirt;
    // Directed edges of the surface that lie in one of the faces, in
    // triangle order; a boundary edge has no reverse twin. The twin of such
    // an edge joins the same two points, so it lies in the same face: only
    // these few edges need sorting and searching.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    std::vector<int> edgeFaces;
    for (std::size_t t = 0; t + 2 < surface.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = surface.indices[t + k], b = surface.indices[t + (k + 1) % 3];
            const int face = sharedFace(surface.positions[a], surface.positions[b], lo, hi, faces);
            if (face < 0) continue;
            edges.emplace_back(a, b);
            edgeFaces.push_back(face);
        }
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted = edges;
    std::sort(sorted.begin(), sorted.end());

    // Skirt vertices per (surface vertex, face): the top copy and the bottom,
    // both with the surface vertex's normal (lit like the surface above).
    std::map<std::pair<std::uint32_t, int>, std::pair<std::uint32_t, std::uint32_t>> made;
    const auto vertexPair = [&](std::uint32_t v, int face) -> std::pair<std::uint32_t, std::uint32_t> {
        const auto found = made.find({v, face});
        if (found != made.end()) return found->second;
        const glm::dvec3 d = skirtDirection(surface.normals[v], face / 2);
        std::pair<std::uint32_t, std::uint32_t> pair{UINT32_MAX, UINT32_MAX};
        if (d != glm::dvec3(0.0)) {
            pair = {std::uint32_t(skirt.positions.size()), std::uint32_t(skirt.positions.size() + 1)};
            skirt.positions.push_back(surface.positions[v]);
            skirt.normals.push_back(surface.normals[v]);
            // Kept inside the box: never past the world's outer faces, and
            // within the tile's bounding volume. The face's own coordinate
            // is untouched (d has none), so the skirt stays in the face plane.
            const double reach = rockDepth(surface.positions[v], d, depth, density);
            skirt.positions.push_back(glm::clamp(surface.positions[v] + reach * d, lo, hi));
            skirt.normals.push_back(surface.normals[v]);
        }
        made.emplace(std::make_pair(v, face), pair);
        return pair;
    };
    // A triangle that faces into the box is the folded-back half of a quad
    // whose ends hang in different directions, or a fold over the air side
    // (a vertex normal that disagrees with its triangle): dropped, as are
    // triangles the clamp collapsed.
    const auto addTriangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, int face) {
        const glm::dvec3& p = skirt.positions[a];
        const glm::dvec3 n = glm::cross(skirt.positions[b] - p, skirt.positions[c] - p);
        const double outward = face % 2 ? n[face / 2] : -n[face / 2];
        if (outward > 0.0) skirt.indices.insert(skirt.indices.end(), {a, b, c});
    };

    for (std::size_t e = 0; e < edges.size(); ++e) {
        const auto [a, b] = edges[e];
        if (std::binary_search(sorted.begin(), sorted.end(), std::make_pair(b, a))) continue;
        const int face = edgeFaces[e];
        const auto [aTop, aBottom] = vertexPair(a, face);
        const auto [bTop, bBottom] = vertexPair(b, face);
        if (aTop == UINT32_MAX || bTop == UINT32_MAX) continue;
        // The surface runs a→b along this edge; the skirt runs b→a, so it
        // continues the surface's orientation over the fold: its front faces
        // out of the box, toward the air side of the seam.
        addTriangle(bTop, aTop, aBottom, face);
        addTriangle(bTop, aBottom, bBottom, face);
    }
    // Vertices only dropped triangles used stay; they are harmless (and few).
    return skirt;
}

} // namespace strata::world::detail
