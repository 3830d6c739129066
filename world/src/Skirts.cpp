// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "Skirts.h"

#include <glm/geometric.hpp>

#include <algorithm>
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

/// Away from the air within the plane of `axis`; zero where undefined.
glm::dvec3 skirtDirection(const glm::dvec3& normal, int axis)
{
    glm::dvec3 d = -normal;
    d[axis] = 0.0;
    const double len = glm::length(d);
    if (len > 1e-3) return d / len;
    return axis == 1 ? glm::dvec3(0.0) : glm::dvec3(0.0, -1.0, 0.0);
}

} // namespace

ClipMesh makeSkirts(const ClipMesh& surface, const glm::dvec3& lo, const glm::dvec3& hi, unsigned faces, double depth)
{
    ClipMesh skirt;
    if (depth <= 0.0 || faces == 0) return skirt;
    // Directed edges of the surface; a boundary edge has no reverse twin.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
    edges.reserve(surface.indices.size());
    for (std::size_t t = 0; t + 2 < surface.indices.size(); t += 3)
        for (int k = 0; k < 3; ++k) edges.emplace_back(surface.indices[t + k], surface.indices[t + (k + 1) % 3]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> sorted = edges;
    std::sort(sorted.begin(), sorted.end());

    // Skirt vertices per (surface vertex, face): the top copy and the bottom.
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
            skirt.positions.push_back(surface.positions[v] + depth * d);
            skirt.normals.push_back(surface.normals[v]);
        }
        made.emplace(std::make_pair(v, face), pair);
        return pair;
    };

    for (const auto& [a, b] : edges) {
        if (std::binary_search(sorted.begin(), sorted.end(), std::make_pair(b, a))) continue;
        const int face = sharedFace(surface.positions[a], surface.positions[b], lo, hi, faces);
        if (face < 0) continue;
        const auto [aTop, aBottom] = vertexPair(a, face);
        const auto [bTop, bBottom] = vertexPair(b, face);
        if (aTop == UINT32_MAX || bTop == UINT32_MAX) continue;
        // The surface runs a→b along this edge; the skirt runs b→a.
        skirt.indices.insert(skirt.indices.end(), {bTop, aTop, aBottom, bTop, aBottom, bBottom});
    }
    return skirt;
}

} // namespace strata::world::detail
