#include <strata/meshing/MeshMetrics.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata::meshing {

MeshTopology analyzeTopology(const TriangleMesh& mesh)
{
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

    MeshTopology topology;
    std::vector<HalfEdge> halfEdges;
    halfEdges.reserve(mesh.indices.size());
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::array<std::uint32_t, 3> v{mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) {
            ++topology.degenerateTriangles;
            continue;
        }
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
    return topology;
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
