// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// What the chunk meshers (surface nets, dual contouring) share: their
/// options, the chunk layout, and a single chunk's mesh.
///
/// A cell the surface crosses gets one vertex per sheet of surface in it
/// (as separated by marching cubes, inside corners kept apart on ambiguous
/// faces; two cells whose sheet crosses their shared ambiguous face twice
/// both group their edges the other way, as OpenVDB's volumeToMesh does), so
/// the mesh stays manifold where thin features meet.
///
/// A chunk is an axis-aligned block of `chunkSize`³ *cells* of the grid's
/// index space, aligned to multiples of `chunkSize` (a multiple of the 8³
/// OpenVDB leaf). A cell with minimum corner `c` spans voxels `c .. c+1` on
/// each axis; it holds at most four mesh vertices. A chunk owns the grid edges
/// whose lower voxel lies inside it and emits one quad (two triangles) per
/// owned edge that crosses the surface; those quads also use the vertices of
/// the one-cell apron below the chunk (cells `min - 1`), which are computed
/// from the same samples, in the same order, as in the chunk that owns them,
/// so adjacent chunks produce identical border vertices and the union of the
/// chunk meshes of a closed surface is watertight.

#include <strata/meshing/GridNormals.h>
#include <strata/meshing/TriangleMesh.h>

#include <openvdb/openvdb.h>

#include <vector>

namespace strata::meshing {

struct ChunkMeshOptions
{
    double isovalue = 0.0; ///< world units; inside is `value < isovalue`
    /// Cells per chunk edge: a multiple of 8 in [8, 512], or 0 for a single
    /// chunk over the whole grid. Changes speed and memory, never the
    /// assembled mesh's geometry (vertex order may differ).
    int chunkSize = 32;
    NormalMethod normals = NormalMethod::Grid; ///< how `normals` are filled
    /// World-space gradient (need not be unit length) for
    /// NormalMethod::Gradient, and for dual contouring's QEF planes when set.
    /// Called concurrently from several threads: it must be thread-safe.
    GradientFunction gradient;
    /// Newton steps that move each vertex along the grid gradient onto the
    /// trilinear isosurface (0 = off); the vertex stays in its cell.
    int projectionSteps = 0;
    glm::dvec3 origin{0.0}; ///< assembled positions are relative to this (metres)
};

/// One chunk's mesh, positions relative to the world position of the
/// chunk's first cell (`mesh.origin`). Vertices of the apron cells are
/// included, so it can be uploaded on its own; faces are emitted only for
/// owned edges, so no face is shared by two chunks.
struct ChunkMesh
{
    openvdb::Coord chunkMin; ///< index coordinates of the first owned cell
    TriangleMesh mesh;
    std::vector<openvdb::Coord> cells; ///< per vertex: the cell it sits in (index space)
    /// Per vertex: which surface sheet of its cell (0 except in the rare cells
    /// the surface crosses more than once). (cell, component) names a vertex
    /// across chunks.
    std::vector<std::uint8_t> components;
};

/// Minimum cells of every chunk that can hold part of the surface (chunks
/// touching a leaf node or its apron), sorted by x, then y, then z.
/// Throws strata::Error if `chunkSize` is not a positive multiple of 8 up to 512.
std::vector<openvdb::Coord> listChunks(const openvdb::FloatGrid& grid, int chunkSize);

} // namespace strata::meshing
