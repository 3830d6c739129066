// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Topology checks and measures of a triangle mesh.

#include <strata/meshing/TriangleMesh.h>

#include <cstddef>

namespace strata::meshing {

/// How analyzeTopology() identifies vertices.
struct TopologyOptions
{
    /// true (default): vertices at exactly the same float position (bit for
    /// bit, +0 = -0) are one vertex, as a file reader or a viewer sees them.
    /// This catches two distinct vertices at one point that make an edge
    /// non-manifold or leave a crack, and reads formats without shared
    /// vertices (STL) and meshes assembled from pieces correctly.
    /// false: vertices are their indices only (the mesh's own connectivity).
    bool weldByPosition = true;
};

struct MeshTopology
{
    std::size_t vertices = 0;          ///< distinct vertices that triangles use (after welding, if on)
    std::size_t triangles = 0;         ///< triangles with three distinct vertices (the others are degenerate)
    std::size_t edges = 0;             ///< distinct undirected edges
    std::size_t boundaryEdges = 0;     ///< used by one triangle
    std::size_t nonManifoldEdges = 0;  ///< used by more than two triangles
    std::size_t inconsistentEdges = 0; ///< two triangles traverse it the same way (flipped orientation)
    /// Repeated vertex (index, or position when welding) or zero area.
    std::size_t degenerateTriangles = 0;
    /// Vertices whose triangles form more than one fan (two surface sheets
    /// touching at a point), or that no triangle uses.
    std::size_t nonManifoldVertices = 0;
    /// Connected pieces: triangles sharing a vertex are in the same one.
    std::size_t components = 0;
    /// Vertex indices at the same position as a lower index, whether or not
    /// welding is on: non-zero means the index topology and the welded one
    /// differ (expected for STL and for meshes written unwelded).
    std::size_t coincidentVertices = 0;

    /// Closed and consistently oriented: every edge has exactly two
    /// triangles that traverse it in opposite directions.
    bool watertight() const { return boundaryEdges == 0 && nonManifoldEdges == 0 && inconsistentEdges == 0; }

    /// V - E + F over `vertices`, `edges` and `triangles`: 2 per closed
    /// sphere-like component, 2 - 2g for genus g.
    long eulerCharacteristic() const { return long(vertices) - long(edges) + long(triangles); }
};

/// Edge- and vertex-based topology check, O(E log E), deterministic.
/// Welds by position first unless `options` say otherwise (see TopologyOptions).
MeshTopology analyzeTopology(const TriangleMesh& mesh, const TopologyOptions& options = {});

/// Removes triangles with a repeated vertex index or zero area (in float);
/// returns how many. Vertices are kept (indices stay valid).
std::size_t removeDegenerateTriangles(TriangleMesh& mesh);

struct AngleStatistics
{
    double minDegrees = 0.0;     ///< smallest angle of any triangle
    double meanMinDegrees = 0.0; ///< mean over triangles of their smallest angle
    double below10Percent = 0.0; ///< % of triangles whose smallest angle is under 10°
};

/// Triangle shape quality; degenerate triangles count as 0°.
AngleStatistics angleStatistics(const TriangleMesh& mesh);

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
