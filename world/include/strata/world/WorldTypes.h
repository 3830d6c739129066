// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The value types of the streaming world (World.h): chunk keys, chunk
/// meshes, edits, ray hits and counters.

#include <strata/meshing/TriangleMesh.h>

#include <glm/vec3.hpp>

#include <compare>
#include <cstdint>
#include <memory>
#include <vector>

namespace strata::world {

/// Names one chunk: its LOD level (0 = finest; cells of 2^level voxels) and
/// its integer position in chunks of that level. The chunk covers the world
/// box [k·W, (k+1)·W) per axis, W = chunkSize · 2^level · voxelSize metres.
/// Ordered by level, then x, y, z.
struct ChunkKey
{
    int level = 0;
    std::int32_t x = 0, y = 0, z = 0;

    auto operator<=>(const ChunkKey&) const = default;
};

/// Which cell a mesh vertex belongs to: LOD level and the cell's integer
/// index at that level (a cell spans voxels index·2^level .. (index+1)·2^level).
/// The same VertexCell in two chunk meshes is the same vertex at the same
/// world position, so it welds chunk meshes exactly.
struct VertexCell
{
    int level = 0;
    std::int32_t x = 0, y = 0, z = 0;

    auto operator<=>(const VertexCell&) const = default;
};

/// One chunk's mesh, ready to upload: positions (float, metres relative to
/// `mesh.origin`, the chunk's minimum corner in double precision), unit
/// normals, uint32 triangle indices wound counter-clockwise seen from air.
/// Vertices on the chunk's lower faces are shared with the neighbours'
/// meshes (same world position, same VertexCell); no triangle appears in two
/// chunks. The bytes depend only on the density field, the edits, the key
/// and the levels of the chunk's lower neighbours (see World.h), never on
/// thread count or completion order.
struct ChunkMeshData
{
    ChunkKey key;
    meshing::TriangleMesh mesh;
    std::vector<VertexCell> vertexCells; ///< one per vertex

    /// Heap bytes held by the buffers (capacity, not size).
    std::size_t memoryBytes() const;
};

/// What World::poll() reports about one chunk.
struct ChunkUpdate
{
    ChunkKey key;
    /// The chunk's new mesh (replace whatever you hold for `key`), or null:
    /// drop the chunk (evicted, or it no longer holds any surface).
    std::shared_ptr<const ChunkMeshData> mesh;
};

/// A shape for edits, in world metres. Build one with the factory functions.
struct EditShape
{
    enum class Kind
    {
        SPHERE,  ///< `a` centre, `radius`
        BOX,     ///< `a` centre, `halfSize`, `radius` = edge rounding (0 = sharp)
        CAPSULE, ///< segment `a`–`b`, `radius`
        PATH,    ///< the union of capsules along `points`, `radius` (a brush stroke)
    };
    Kind kind = Kind::SPHERE;
    glm::dvec3 a{0.0}, b{0.0};
    glm::dvec3 halfSize{0.0};
    double radius = 0.0;
    std::vector<glm::dvec3> points;

    static EditShape sphere(const glm::dvec3& centre, double radius);
    /// `rounding` in [0, min(halfSize)].
    static EditShape box(const glm::dvec3& centre, const glm::dvec3& halfSize, double rounding = 0.0);
    static EditShape capsule(const glm::dvec3& a, const glm::dvec3& b, double radius);
    /// A brush dragged along a polyline of at least one point.
    static EditShape path(std::vector<glm::dvec3> points, double radius);

    /// Exact signed distance (metres, negative inside). O(1), O(points) for PATH.
    double distance(const glm::dvec3& p) const;
    /// Throws strata::Error naming the bad value (non-finite, radius or half
    /// size <= 0, rounding out of range, empty path).
    void validate() const;
    /// World bounds of the shape (min, max).
    void bounds(glm::dvec3& min, glm::dvec3& max) const;
};

enum class EditMode
{
    DIG,  ///< carve the shape out: density = max(density, −shape)
    FILL, ///< add the shape as rock: density = min(density, shape)
};

struct Edit
{
    EditShape shape;
    EditMode mode = EditMode::DIG;
    /// Blend radius in metres (0 = hard edit): the min/max become the
    /// polynomial smooth-min of terrain::smoothMin, with fillets about this wide.
    double smoothRadius = 0.0;
};

/// What an edit changed.
struct EditResult
{
    std::size_t changedVoxels = 0; ///< lattice samples whose value changed
    /// Resident chunks marked for re-meshing, sorted: those whose sample
    /// footprint (see World.h) holds a changed sample.
    std::vector<ChunkKey> markedChunks;
};

struct RayHit
{
    glm::dvec3 position{0.0}; ///< world metres, on the surface (density 0, within 1e-6 m)
    glm::dvec3 normal{0.0};   ///< unit, pointing into air
    double distance = 0.0;    ///< metres along the (normalised) ray direction
};

/// Counters since the world was made (cumulative) and its state now.
struct WorldStats
{
    std::uint64_t generated = 0; ///< chunks meshed for the first time since they became resident
    std::uint64_t remeshed = 0;  ///< chunk meshes replaced after an edit or an LOD change of a neighbour
    std::uint64_t evicted = 0;   ///< chunks dropped from the resident set
    std::uint64_t discarded = 0; ///< finished meshes thrown away (chunk evicted or neighbours changed meanwhile)
    /// Of `generated` and `remeshed`: meshes made ahead for the partition
    /// the points were heading to (WorldOptions::lookAhead), handed to their
    /// chunk when it arrived.
    std::uint64_t prefetched = 0;
    /// Meshes made ahead and thrown away: the points turned, or an edit
    /// changed their samples.
    std::uint64_t prefetchDropped = 0;
    std::size_t resident = 0;    ///< chunks in the resident set now (empty ones included)
    std::size_t withSurface = 0; ///< resident chunks whose current mesh has triangles
    std::size_t pending = 0;     ///< resident chunks waiting for a (re)mesh
    /// Of `pending`: chunks the caller holds nothing for yet (never meshed,
    /// and no retired mesh stands in): holes in the view. The World meshes
    /// them before any other pending chunk.
    std::size_t holes = 0;
    /// Chunks split or merged away whose meshes the caller still holds until
    /// every chunk replacing them is meshed (see World::poll()).
    std::size_t retained = 0;
    std::size_t inFlight = 0;    ///< chunk tasks running or queued on the task pool
    std::size_t meshBytes = 0;   ///< heap bytes of all resident chunk meshes
    std::size_t cacheBytes = 0;  ///< heap bytes of the kept samples (WorldOptions::sampleCacheLevels)
    std::size_t prefetchHeld = 0;  ///< meshes made ahead, waiting for their partition
    std::size_t prefetchBytes = 0; ///< heap bytes of those meshes (not in meshBytes)
    std::size_t editVoxels = 0;  ///< active voxels of the edit grid
    std::size_t editBytes = 0;   ///< memory of the edit grid
};

} // namespace strata::world
