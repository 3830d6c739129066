#pragma once
// Internal: gathers one chunk's samples (field, edits, cache) and meshes them
// with meshing::dualMesh() (dual contouring on the octree of
// cells with surface-nets vertices; see World.h for the method).

#include <strata/world/WorldTypes.h>

#include "EditLayer.h"
#include "Lattice.h"

#include <mutex>
#include <vector>

namespace strata::world::detail {

struct MesherParams
{
    double voxelSize = 0.5;
    int chunkSize = 32;
};

/// The procedural samples of one chunk's own-level lattice, kept between
/// re-meshes (after an edit only the edits are looked up again). Used by one
/// task at a time (`mutex`); the values are the same whether cached or not.
struct SampleCache
{
    std::mutex mutex;
    std::vector<float> values;          ///< empty until a block is evaluated
    std::vector<std::uint8_t> blockDone; ///< per 8³ block: values hold the procedural samples
    std::size_t bytes() const { return values.capacity() * sizeof(float) + blockDone.capacity(); }
};

/// The voxel box of edits a chunk's mesh can depend on (its sample footprint
/// grown by the pruning margin): snapshot this box before meshing.
openvdb::CoordBBox editFootprint(const MesherParams& params, const ChunkKey& key);

/// Meshes one chunk. A pure function of its arguments.
/// `cache` may be null; the caller holds its mutex.
ChunkMeshData meshChunk(const terrain::DensityField& field, const MesherParams& params, const ChunkKey& key,
                        const Signature& signature, const EditSnapshot& edits, SampleCache* cache = nullptr);

} // namespace strata::world::detail
