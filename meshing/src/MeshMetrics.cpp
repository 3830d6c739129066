// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/MeshMetrics.h>

#include "PositionWeld.h"

#include <strata/DeterministicMath.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace strata::meshing {

MeshTopology analyzeTopology(const TriangleMesh& mesh, const TopologyOptions& options)
{
    MeshTopology topology;
    const std::size_t n = mesh.positions.size();

    // Vertex identity: the lowest index at the same position, or the index.
    const std::vector<std::uint32_t> weld = detail::weldByPosition(mesh.positions);
    for (std::uint32_t v = 0; v < n; ++v) topology.coincidentVertices += weld[v] != v ? 1 : 0;
    std::vector<std::uint32_t> indices(mesh.indices.size() / 3 * 3);
    for (std::size_t i = 0; i < indices.size(); ++i) {
        indices[i] = options.weldByPosition ? weld[mesh.indices[i]] : mesh.indices[i];
    }

    // Each directed half-edge as (min, max, direction); sorting groups the
    // uses of one undirected edge together.
    struct HalfEdge
    {
        std::uint32_t lo, hi;
        bool forward; // traversed lo → hi
        bool operator<(const HalfEdge& o) const
        {
            return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : forward < o.forward;
        }
    };

    std::vector<HalfEdge> halfEdges;
    halfEdges.reserve(indices.size());
    for (std::size_t t = 0; t < indices.size(); t += 3) {
        const std::array<std::uint32_t, 3> v{indices[t], indices[t + 1], indices[t + 2]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
            ++topology.degenerateTriangles;
            continue;
        }
        ++topology.triangles;
        const glm::vec3 cross = glm::cross(mesh.positions[v[1]] - mesh.positions[v[0]],
                                           mesh.positions[v[2]] - mesh.positions[v[0]]);
        if (glm::dot(cross, cross) == 0.0f) ++topology.degenerateTriangles;
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = v[e], b = v[(e + 1) % 3];
            halfEdges.push_back({std::min(a, b), std::max(a, b), a < b});
        }
    }
    std::sort(halfEdges.begin(), halfEdges.end());

    for (std::size_t i = 0; i < halfEdges.size();) {
        std::size_t j = i;
        int forward = 0, backward = 0;
        while (j < halfEdges.size() && halfEdges[j].lo == halfEdges[i].lo && halfEdges[j].hi == halfEdges[i].hi) {
            (halfEdges[j].forward ? forward : backward)++;
            ++j;
        }
        ++topology.edges;
        const int uses = forward + backward;
        if (uses == 1) ++topology.boundaryEdges;
        else if (uses > 2) ++topology.nonManifoldEdges;
        else if (forward != 1) ++topology.inconsistentEdges;
        i = j;
    }

    // Components: union-find over the vertices of every triangle.
    std::vector<std::uint32_t> root(n);
    for (std::uint32_t v = 0; v < n; ++v) root[v] = v;
    auto findRoot = [&](std::uint32_t v) {
        while (root[v] != v) v = root[v] = root[root[v]];
        return v;
    };
    for (std::size_t t = 0; t < indices.size(); t += 3) {
        root[findRoot(indices[t + 1])] = findRoot(indices[t]);
        root[findRoot(indices[t + 2])] = findRoot(indices[t]);
    }

    // Vertex fans: join the triangles around each vertex through the edges
    // they share; more than one group is a non-manifold vertex.
    std::vector<std::uint32_t> start(n + 1, 0);
    for (std::uint32_t v : indices) ++start[v + 1];
    for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::uint32_t> corners(indices.size()), fill(start.begin(), start.end() - 1);
    for (std::uint32_t i = 0; i < indices.size(); ++i) corners[fill[indices[i]]++] = i;
    std::vector<std::uint32_t> parent;
    for (std::uint32_t v = 0; v < n; ++v) {
        const std::uint32_t count = start[v + 1] - start[v];
        if (count == 0) {
            // An unused vertex, unless it is a welded copy of another one.
            if (!options.weldByPosition || weld[v] == v) ++topology.nonManifoldVertices;
            continue;
        }
        ++topology.vertices;
        topology.components += findRoot(v) == v ? 1 : 0;
        parent.resize(count);
        for (std::uint32_t k = 0; k < count; ++k) parent[k] = k;
        auto find = [&](std::uint32_t k) {
            while (parent[k] != k) k = parent[k] = parent[parent[k]];
            return k;
        };
        // Two triangles around v are joined when they share a second vertex.
        for (std::uint32_t a = 0; a < count; ++a) {
            const std::uint32_t ta = corners[start[v] + a] / 3 * 3;
            for (std::uint32_t b = a + 1; b < count; ++b) {
                const std::uint32_t tb = corners[start[v] + b] / 3 * 3;
                bool shared = false;
                for (int i = 0; i < 3 && !shared; ++i) {
                    const std::uint32_t w = indices[ta + i];
                    if (w == v) continue;
                    for (int j = 0; j < 3; ++j) shared |= indices[tb + j] == w;
                }
                if (shared) parent[find(a)] = find(b);
            }
        }
        std::uint32_t groups = 0;
        for (std::uint32_t k = 0; k < count; ++k) groups += find(k) == k ? 1 : 0;
        if (groups > 1) ++topology.nonManifoldVertices;
    }
    return topology;
}

std::size_t removeDegenerateTriangles(TriangleMesh& mesh)
{
    std::size_t kept = 0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if (a == b || b == c || a == c) continue;
        const glm::vec3 cross = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        if (glm::dot(cross, cross) == 0.0f) continue;
        mesh.indices[kept++] = a;
        mesh.indices[kept++] = b;
        mesh.indices[kept++] = c;
    }
    const std::size_t removed = mesh.indices.size() / 3 - kept / 3;
    mesh.indices.resize(kept);
    return removed;
}

AngleStatistics angleStatistics(const TriangleMesh& mesh)
{
    AngleStatistics stats;
    const std::size_t triangles = mesh.indices.size() / 3;
    if (triangles == 0) return stats;
    double sum = 0.0, smallest = 180.0;
    std::size_t below = 0;
    for (std::size_t t = 0; t < triangles; ++t) {
        const glm::dvec3 p[3] = {glm::dvec3(mesh.positions[mesh.indices[3 * t]]),
                                 glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]),
                                 glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]])};
        double least = 180.0;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 u = p[(k + 1) % 3] - p[k], v = p[(k + 2) % 3] - p[k];
            const double len = glm::length(u) * glm::length(v);
            const double angle =
                len > 0 ? dmath::acos(std::clamp(glm::dot(u, v) / len, -1.0, 1.0)) * 180.0 / std::numbers::pi : 0.0;
            least = std::min(least, angle);
        }
        sum += least;
        smallest = std::min(smallest, least);
        below += least < 10.0 ? 1 : 0;
    }
    stats.minDegrees = smallest;
    stats.meanMinDegrees = sum / double(triangles);
    stats.below10Percent = 100.0 * double(below) / double(triangles);
    return stats;
}

double signedVolume(const TriangleMesh& mesh)
{
    // Sum of signed tetrahedra against the local origin; local coordinates
    // keep the terms small, so the sum is accurate far from the world origin.
    double volume = 0.0;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const glm::dvec3 a(mesh.positions[mesh.indices[t]]);
        const glm::dvec3 b(mesh.positions[mesh.indices[t + 1]]);
        const glm::dvec3 c(mesh.positions[mesh.indices[t + 2]]);
        volume += glm::dot(a, glm::cross(b, c));
    }
    return volume / 6.0;
}

Bounds worldBounds(const TriangleMesh& mesh)
{
    Bounds bounds;
    if (mesh.positions.empty()) return bounds;
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    bounds.min = mesh.origin + lo;
    bounds.max = mesh.origin + hi;
    return bounds;
}

} // namespace strata::meshing
