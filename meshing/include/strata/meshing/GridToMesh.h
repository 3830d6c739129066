// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Level set to triangle mesh through OpenVDB's volumeToMesh.

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

namespace strata::meshing {

struct GridToMeshOptions
{
    double isovalue = 0.0;   ///< world units, the surface to extract
    double adaptivity = 0.0; ///< 0 = uniform, 1 = most merging (fewer triangles)
    bool computeNormals = true; ///< false: no normals at all (overrides `normals`)
    NormalMethod normals = NormalMethod::Grid; ///< how normals are computed
    GradientFunction gradient; ///< for NormalMethod::Gradient (thread-safe)
    int projectionSteps = 0;   ///< Newton steps onto the isosurface (projectToSurface)
    glm::dvec3 origin{0.0};  ///< positions are stored relative to this (metres)
};

/// Extracts the isosurface of a level set (negative inside) as triangles,
/// counter-clockwise seen from outside. volumeToMesh's quads are split along
/// their shorter diagonal. Output order is deterministic.
/// Throws strata::Error if the options are not finite, adaptivity is
/// outside [0, 1], or NormalMethod::Gradient comes without a gradient.
TriangleMesh gridToMesh(const openvdb::FloatGrid& grid, const GridToMeshOptions& options = {});

} // namespace strata::meshing
