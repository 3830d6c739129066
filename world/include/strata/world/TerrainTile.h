// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// One tile of a world as a game engine's terrain system holds it: a
/// heightfield (the top surface of the level set) with holes, and the
/// rest of the surface (caves, overhangs, arches: what no heightfield can
/// hold) as a mesh in the same frame (strata::scene::exportTerrain()).
///
/// Heights come from the level set, not from the field: the lattice is
/// sampled exactly as the bake's tiles sample it (world::meshTile()), and
/// each lattice column's height is its highest sign change, interpolated
/// linearly along the vertical lattice edge, so heightfield and meshes
/// agree. Neighbouring tiles share their edge columns, which read the same
/// lattice points: their heights are the same bits.
///
/// Holes. A lattice cell (the square between four columns) is a hole where
/// the heightfield drawn over it would close off air that the level set
/// leaves open: a lattice point of air below a corner column's top but no
/// lower than HOLE_DEPTH voxels under the cell's lowest corner top (a cave
/// mouth, the lip of an overhang, a shaft opening), or a corner column
/// with no rock at all in the box. The engine cuts the terrain there, and
/// the remainder mesh (heightfieldRemainder()) draws the level set's
/// surface over every hole cell and everywhere below the skin.

#include <strata/meshing/TriangleMesh.h>
#include <strata/terrain/DensityField.h>
#include <strata/world/TileMesh.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::world {

/// Depth below a cell's lowest corner top (voxels) within which air makes
/// the cell a hole; one voxel more than heightfieldRemainder() drops, so a
/// lattice cube that holds a dropped vertex has no air below the skin.
inline constexpr int HOLE_DEPTH = 2;

struct TerrainTileOptions
{
    double voxelSize = 1.0; ///< metres, > 0
};

struct TerrainTile
{
    double voxelSize = 1.0;
    TileBox box;      ///< voxels
    int columns = 0;  ///< lattice columns along x: box.size[0] + 1
    int rows = 0;     ///< lattice columns along z: box.size[2] + 1
    /// Per column, row-major (z rows, x fastest): the world height (metres)
    /// of the highest sign change; the box top where the column is rock at
    /// the top, the box bottom where it holds no rock.
    std::vector<double> heights;
    /// Per cell, (rows − 1) × (columns − 1), row-major: 1 for a hole.
    std::vector<std::uint8_t> holes;
    std::size_t columnsAtTop = 0;    ///< columns clipped by the box top (rock there)
    std::size_t columnsAtBottom = 0; ///< columns without rock in the box
    /// The whole level-0 surface in the box (dual mesher, clipped to the
    /// box, as meshTile() makes it), origin = the box minimum in metres.
    meshing::TriangleMesh surface;

    double height(int x, int z) const { return heights[std::size_t(z) * columns + x]; }
    bool hole(int x, int z) const { return holes[std::size_t(z) * (columns - 1) + x] != 0; }
};

/// Samples `field` on the lattice of `box` (every lattice point of it plus
/// a two-voxel apron, pruned as the bake prunes) and extracts the tile's
/// heights, holes and surface. A pure function: the same bytes on any
/// thread and beside any neighbour. Throws strata::Error (BadInput) for a
/// voxel size that is not positive, a box with an empty axis, more than
/// 1024 voxels across x or z or 4096 up y, or beyond the 32-bit lattice.
/// Memory: terrainTileBytes(); time: one field evaluation per lattice point
/// near the surface (distance-bound pruning skips the rest).
TerrainTile extractTerrainTile(const terrain::DensityField& field, const TileBox& box,
                               const TerrainTileOptions& options);

/// The heightfield's height between the columns: bilinear in the lattice
/// cell holding (fx, fz), lattice units from the tile's minimum corner,
/// clamped to the tile. Exact at the columns (a coordinate with no
/// fraction reads the column itself), and along an edge of the tile it
/// reads that edge's columns only, so neighbours agree there.
double latticeHeight(const TerrainTile& tile, double fx, double fz);

/// latticeHeight() at (x, z) metres from the tile's minimum corner: the
/// surface an engine draws from a heightmap of one sample per voxel.
double heightAt(const TerrainTile& tile, double x, double z);

/// Bytes of the sample array extractTerrainTile() allocates for `box`.
std::size_t terrainTileBytes(const TileBox& box);

/// The holes of a heightfield drawn over the tile: `cellsX` × `cellsZ`
/// cells (row-major, 1 for a hole) of `cellSize` metres covering the tile
/// from its minimum corner. Engine grids that differ from the lattice mark
/// a cell a hole where it overlaps a hole cell of the lattice.
struct HeightfieldHoles
{
    int cellsX = 0, cellsZ = 0;
    double cellSize = 1.0; ///< metres
    std::vector<std::uint8_t> cells;
};

/// The engine's hole cells for a grid of `cellsX` × `cellsZ` cells of
/// `cellSize` metres over the tile: a cell is a hole where it overlaps a
/// lattice hole cell (closed intervals shrunk by 1e-9 cell, so touching at
/// an edge is not overlapping).
HeightfieldHoles engineHoles(const TerrainTile& tile, int cellsX, int cellsZ, double cellSize);

/// The triangles of tile.surface that a heightfield with `holes` does not
/// draw: a vertex is drawn by the heightfield when its cell is no hole (in
/// the lattice and in `holes`) and it lies no more than one voxel below the
/// lowest corner top of its lattice cell; a triangle is dropped when all
/// three of its vertices are drawn. What is kept: every hole cell's
/// surface, and every surface below the skin (cave walls, floors and
/// ceilings, overhang undersides). Its open border runs along the hole
/// cells' edges and along the skin, which the heightfield meets there.
/// Vertices keep their order (unused ones dropped); origin as the tile's.
meshing::TriangleMesh heightfieldRemainder(const TerrainTile& tile, const HeightfieldHoles& holes);

} // namespace strata::world
