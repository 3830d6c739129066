// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// One tile of a baked world (strata::scene::bake): the surface inside an
/// axis-aligned box of the voxel lattice, meshed at a level of detail with
/// the World's dual mesher (surface nets, one vertex per cell) and clipped
/// exactly to the box, plus skirts that close the cracks against a
/// neighbour meshed at another level.
///
/// Seams. The mesh of a box is cut at the box's faces, so tiles of the same
/// level that share a face produce the same cut: the same border vertices
/// (the same cells, the same cut points, rounded the same way). Positions
/// are multiples of 1/4096 cell relative to the box minimum, so they are
/// exact in float, and a power-of-two voxel size keeps them exact in metres.
/// Two tiles of different levels cut the same face plane along different
/// polylines; the gap between them lies in that plane. Each tile hangs a
/// skirt from its border on every face with a neighbour (never on the
/// world's outer faces): a strip in the face plane, `skirtDepth` deep,
/// pointing away from the air (along the in-plane axis where the surface
/// normal's in-plane part, reversed, is largest: straight down under
/// terrain on a tile's side), clamped into the box and ended where it
/// would leave the rock again (a cave under a thin roof; the level's own
/// samples decide), so the skirt of the upper polyline covers the gap and
/// stays hidden in the rock. No skirt where the surface meets the face
/// within 30° of its plane (a slab cut through nearly flat ground, a cliff
/// along a tile's side): it would lie in the surface's own plane and show
/// as a flap or fight it for pixels. Skirt vertices carry the normal of the
/// surface vertex they hang from and face out of the box (continuing the
/// surface's orientation), so a one-sided material shows them from the air
/// side lit like the surface. Skirts are kept apart from the surface, so
/// the surface stays a clean manifold patch.

#include <strata/meshing/TriangleMesh.h>
#include <strata/terrain/DensityField.h>

#include <array>
#include <cstddef>
#include <cstdint>

namespace strata::world {

/// A box of the level-0 voxel lattice (lattice point i at i·voxelSize).
struct TileBox
{
    std::array<std::int64_t, 3> min{0, 0, 0}; ///< voxel index of the minimum corner
    std::array<std::int64_t, 3> size{0, 0, 0}; ///< voxels per axis, each > 0
    /// Faces with a neighbouring tile (skirts hang from these): bit 2·a is
    /// the minimum face of axis a, bit 2·a + 1 the maximum face.
    unsigned neighbourFaces = 0x3f;
};

struct TileMeshOptions
{
    double voxelSize = 1.0; ///< metres, > 0
    /// Level of detail: cells of 2^level voxels; box.min and box.size must
    /// be multiples of 2^level, with at most 1024 cells per axis.
    int level = 0;
    double skirtDepth = 0.0; ///< metres (0: no skirts)
};

struct TileMeshData
{
    /// The surface inside the box, counter-clockwise seen from air, unit
    /// normals from the samples' gradient; origin = box minimum in metres.
    meshing::TriangleMesh surface;
    /// The skirts, same origin; their top vertices repeat the surface's
    /// border vertices (position and normal), their bottom vertices the
    /// normal of the top; front faces out of the box.
    meshing::TriangleMesh skirt;
};

/// Meshes `field` inside `box` (see the file comment). A pure function of
/// its arguments: the same bytes on any thread, alone or beside its
/// neighbours. Throws strata::Error (BadInput) for a box that breaks the
/// preconditions above. Memory: tileSampleBytes().
TileMeshData meshTile(const terrain::DensityField& field, const TileBox& box, const TileMeshOptions& options);

/// Bytes of the sample array meshTile() allocates for `box` at `level`.
std::size_t tileSampleBytes(const TileBox& box, int level);

} // namespace strata::world
