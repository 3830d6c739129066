#pragma once
/// \file
/// Topology checks and measures of a triangle mesh.

#include <strata/meshing/TriangleMesh.h>

#include <cstddef>

namespace strata::meshing {

struct MeshTopology
{
    std::size_t edges = 0;             ///< distinct undirected edges
    std::size_t boundaryEdges = 0;     ///< used by one triangle
    std::size_t nonManifoldEdges = 0;  ///< used by more than two triangles
    std::size_t inconsistentEdges = 0; ///< two triangles traverse it the same way (flipped orientation)
    std::size_t degenerateTriangles = 0; ///< repeated vertex index or zero area

    /// Closed and consistently oriented: every edge has exactly two
    /// triangles that traverse it in opposite directions.
    bool watertight() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0; }
};

/// Edge-based topology check, O(E log E), deterministic.
MeshTopology analyzeTopology(const TriangleMesh& mesh);

/// Signed volume enclosed by the mesh (divergence theorem, accumulated in
/// double relative to the mesh origin), cubic metres. Positive for a closed
/// mesh with outward orientation.
double signedVolume(const TriangleMesh& mesh);

/// Axis-aligned bounds of the positions in world metres (origin added).
/// Both are zero for an empty mesh.
struct Bounds
{
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
};
Bounds worldBounds(const TriangleMesh& mesh);

} // namespace strata::meshing
