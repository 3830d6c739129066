// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Mesh simplification with an error bound, two ways: meshoptimizer (fast)
/// and OpenMesh's quadric Decimater (accurate, about 10x slower).

#include <strata/meshing/TriangleMesh.h>

namespace strata::meshing {

enum class Simplifier
{
    MeshOptimizer, ///< meshopt_simplify: edge collapses onto existing vertices
    Quadric,       ///< OpenMesh Decimater with ModQuadric
};

/// "meshoptimizer", "quadric".
const char* toString(Simplifier method);

struct SimplifyOptions
{
    Simplifier method = Simplifier::MeshOptimizer;
    /// Target triangle count as a fraction of the input, in (0, 1]; the
    /// result has more when the error bound stops it first.
    double ratio = 0.5;
    /// Largest allowed geometric error, world metres (meshoptimizer: its
    /// quadric-based estimate; Decimater: the square root of the quadric
    /// error, i.e. distance to the planes of the removed triangles).
    double maxError = 0.01;
    /// Keep every boundary edge and its vertices in place (chunk borders:
    /// simplify chunks separately and they still fit together).
    bool lockBorder = true;
};

/// Returns the simplified mesh: surviving vertices keep their positions and
/// normals, unused vertices are dropped (order kept), origin unchanged.
/// Deterministic. Throws strata::Error for a ratio outside (0, 1] or a
/// negative or non-finite error.
TriangleMesh simplify(const TriangleMesh& mesh, const SimplifyOptions& options = {});

} // namespace strata::meshing
