// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/RemoveSmallComponents.h>

#include "PositionWeld.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata::meshing {

ComponentRemoval removeSmallComponents(TriangleMesh& mesh, const SmallComponentOptions& options)
{
    assert(options.minDiagonal >= 0.0 && options.minArea >= 0.0);
    ComponentRemoval removal;
    const std::size_t vertexCount = mesh.positions.size();
    const std::size_t triangleCount = mesh.indices.size() / 3;
    const std::vector<std::uint32_t> weld = detail::weldByPosition(mesh.positions);

    // Components: union-find over the welded vertices of every triangle.
    std::vector<std::uint32_t> root(vertexCount);
    for (std::uint32_t v = 0; v < vertexCount; ++v) root[v] = v;
    auto findRoot = [&](std::uint32_t v) {
        while (root[v] != v) v = root[v] = root[root[v]];
        return v;
    };
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t a = findRoot(weld[mesh.indices[3 * t]]);
        root[findRoot(weld[mesh.indices[3 * t + 1]])] = a;
        root[findRoot(weld[mesh.indices[3 * t + 2]])] = a;
    }

    // Number the components in order of their first triangle.
    constexpr std::uint32_t NONE = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> componentOfRoot(vertexCount, NONE), componentOf(triangleCount);
    for (std::size_t t = 0; t < triangleCount; ++t) {
        const std::uint32_t r = findRoot(weld[mesh.indices[3 * t]]);
        if (componentOfRoot[r] == NONE) componentOfRoot[r] = std::uint32_t(removal.components++);
        componentOf[t] = componentOfRoot[r];
    }
    if (options.minDiagonal <= 0.0 && options.minArea <= 0.0) return removal;

    // Bounds and area per component (double, relative to the origin).
    struct Measure
    {
        glm::dvec3 lo{std::numeric_limits<double>::max()};
        glm::dvec3 hi{std::numeric_limits<double>::lowest()};
        double area = 0.0;
    };
    std::vector<Measure> measures(removal.components);
    for (std::size_t t = 0; t < triangleCount; ++t) {
        Measure& m = measures[componentOf[t]];
        glm::dvec3 p[3];
        for (int k = 0; k < 3; ++k) {
            p[k] = glm::dvec3(mesh.positions[mesh.indices[3 * t + k]]);
            m.lo = glm::min(m.lo, p[k]);
            m.hi = glm::max(m.hi, p[k]);
        }
        m.area += 0.5 * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
    }
    // Candidates: the components under either limit.
    std::vector<unsigned char> remove(removal.components, 0);
    bool anySmall = false;
    for (std::size_t c = 0; c < removal.components; ++c) {
        const Measure& m = measures[c];
        remove[c] = glm::length(m.hi - m.lo) < options.minDiagonal || m.area < options.minArea ? 1 : 0;
        anySmall |= remove[c] != 0;
    }
    if (anySmall && options.closedOnly) {
        // A boundary edge (one use, welded) keeps a candidate: it is open.
        // Only the candidates' edges are sorted, usually a tiny share.
        struct Edge
        {
            std::uint32_t lo, hi, component;
            bool operator<(const Edge& o) const { return lo != o.lo ? lo < o.lo : hi < o.hi; }
            bool operator==(const Edge& o) const { return lo == o.lo && hi == o.hi; }
        };
        std::vector<Edge> edges;
        for (std::size_t t = 0; t < triangleCount; ++t) {
            if (!remove[componentOf[t]]) continue;
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = weld[mesh.indices[3 * t + e]], b = weld[mesh.indices[3 * t + (e + 1) % 3]];
                if (a != b) edges.push_back({std::min(a, b), std::max(a, b), componentOf[t]});
            }
        }
        std::sort(edges.begin(), edges.end());
        for (std::size_t i = 0; i < edges.size();) {
            std::size_t j = i + 1;
            while (j < edges.size() && edges[j] == edges[i]) ++j;
            if (j - i == 1) remove[edges[i].component] = 0;
            i = j;
        }
    }
    for (unsigned char r : remove) removal.removedComponents += r;
    if (removal.removedComponents == 0) return removal;

    // Keep the triangles of kept components; then the vertices they use (and
    // those no triangle used at all), in their original order.
    std::vector<unsigned char> used(vertexCount, 0), kept(vertexCount, 0);
    std::size_t out = 0;
    for (std::size_t t = 0; t < triangleCount; ++t) {
        for (int k = 0; k < 3; ++k) used[mesh.indices[3 * t + k]] = 1;
        if (remove[componentOf[t]]) {
            ++removal.removedTriangles;
            continue;
        }
        for (int k = 0; k < 3; ++k) {
            kept[mesh.indices[3 * t + k]] = 1;
            mesh.indices[out++] = mesh.indices[3 * t + k];
        }
    }
    mesh.indices.resize(out);
    const bool withNormals = mesh.normals.size() == vertexCount;
    std::vector<std::uint32_t> newIndex(vertexCount, NONE);
    std::uint32_t next = 0;
    for (std::uint32_t v = 0; v < vertexCount; ++v) {
        if (used[v] && !kept[v]) continue;
        newIndex[v] = next;
        mesh.positions[next] = mesh.positions[v];
        if (withNormals) mesh.normals[next] = mesh.normals[v];
        ++next;
    }
    removal.removedVertices = vertexCount - next;
    mesh.positions.resize(next);
    if (withNormals) mesh.normals.resize(next);
    for (std::uint32_t& i : mesh.indices) i = newIndex[i];
    return removal;
}

} // namespace strata::meshing
