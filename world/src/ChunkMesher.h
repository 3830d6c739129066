// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: gathers one chunk's samples (field, edits, cache) and meshes them
// with meshing::dualMesh() (dual contouring on the octree of
// cells with surface-nets vertices; see World.h for the method).

#include <strata/world/WorldTypes.h>

#include "EditLayer.h"
#include "Lattice.h"
#include "SampleArray.h"

#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/RockMasks.h>

#include <mutex>
#include <vector>

namespace strata::world::detail {

struct MesherParams
{
    double voxelSize = 0.5;
    int chunkSize = 32;
    const terrain::LandformMasks* landform = nullptr; ///< fills the meshes' landform when set
    const terrain::RockMasks* rock = nullptr;         ///< fills the meshes' rock when set
};

/// The voxel box of edits a chunk's mesh can depend on (its sample footprint
/// grown by the pruning margin): snapshot this box before meshing.
openvdb::CoordBBox editFootprint(const MesherParams& params, const ChunkKey& key);

/// Meshes one chunk. A pure function of its arguments.
/// `cache` may be null; the caller holds its mutex.
ChunkMeshData meshChunk(const terrain::DensityField& field, const MesherParams& params, const ChunkKey& key,
                        const Signature& signature, const EditSnapshot& edits, SampleCache* cache = nullptr);

} // namespace strata::world::detail
