// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Removing tiny disconnected pieces of a mesh, such as the closed shells a
/// few millimetres across that meshers keep around noise specks.

#include <strata/meshing/TriangleMesh.h>

#include <cstddef>

namespace strata::meshing {

/// Which components removeSmallComponents() removes. The defaults remove
/// nothing: a library caller opts in (the library never drops geometry by
/// itself).
struct SmallComponentOptions
{
    /// Metres: a component whose axis-aligned bounding-box diagonal is
    /// smaller than this is removed; 0 = no limit.
    double minDiagonal = 0.0;
    /// Square metres: a component whose surface area is smaller than this is
    /// removed; 0 = no limit.
    double minArea = 0.0;
    /// true (default): only closed components (no boundary edge) are removed,
    /// so a piece of surface cut by a chunk border, which continues in the
    /// neighbouring chunk, is never removed from a chunk's mesh.
    bool closedOnly = true;
};

/// What removeSmallComponents() found and removed.
struct ComponentRemoval
{
    std::size_t components = 0;        ///< components before removal
    std::size_t removedComponents = 0; ///< components removed
    std::size_t removedTriangles = 0;  ///< their triangles
    std::size_t removedVertices = 0;   ///< vertices no kept triangle uses any more
};

/// Removes the connected components (triangles sharing a vertex, vertices
/// welded by exact position as in analyzeTopology()) that are smaller than
/// either limit of `options`. The vertices only removed triangles used are
/// removed too (with their normals); the kept vertices and triangles keep
/// their relative order, so indices change but the output stays
/// deterministic. Vertices no triangle used before are kept. Does nothing
/// with the default options. O(V log V + T).
ComponentRemoval removeSmallComponents(TriangleMesh& mesh, const SmallComponentOptions& options);

} // namespace strata::meshing
