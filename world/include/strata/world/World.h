// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A streaming, chunked, editable voxel world for games: terrain and meshing,
/// no rendering.
///
/// **Field and lattice.** The world samples a terrain::DensityField (negative
/// in rock) on the lattice of points i·voxelSize (i integer, voxel
/// coordinates). LOD level l samples every 2^l-th lattice point, so all levels
/// read the same values where their lattices meet.
///
/// **Chunks.** A chunk of level l is chunkSize³ cells of 2^l voxels. Around
/// the points of interest the resident chunks form an octree partition,
/// computed from the *interest chunks*, the level-0 chunks that hold the
/// points: a top-level chunk (level levels−1) is resident when its box is
/// within viewRadius of an interest chunk's centre; a chunk of level l > 0 is
/// split into its 8 children when its box is closer than lodDistance·2^(l−1)
/// to one (distances off by at most half a level-0 chunk diagonal from those
/// to the points themselves). So the set changes only when a point crosses a
/// level-0 chunk border: setPointsOfInterest() then wakes the
/// world's partition thread, which computes the new set off the callers'
/// threads, and the next poll() after it is ready applies it (O(resident
/// chunks) map walk, no field evaluation). Chunks leaving the set either
/// left the view (evicted: reported removed by that poll(), edits stay) or
/// were split or merged (replaced, below).
///
/// **Look-ahead.** A point of interest is heading for the level-0 chunk its
/// ray of motion enters next, along its last move (from the point with the
/// same index in an earlier setPointsOfInterest()); a point at rest keeps
/// that direction, and only one that has not moved since the number of
/// points last changed stays in its own chunk. The partition thread also
/// computes the resident set for those chunks, and when the pool has no
/// resident chunk to mesh it meshes the chunks of that set that are not
/// resident as they will be (new, or with other neighbour levels). When the
/// point crosses the border, those chunks arrive meshed: a crossing no
/// longer leaves a few hundred chunks pending at once. The meshes are the
/// same bytes as if made on arrival (a chunk mesh is a pure function, see
/// Determinism); an edit drops those it touches. WorldOptions::lookAhead.
///
/// **LOD changes without holes ("keep until replaced").** A chunk the caller
/// holds a mesh for that is split into its children or merged into its parent
/// is not reported removed at once: it is *retained* (WorldStats::retained)
/// until every resident chunk covering its box has been meshed. Then one
/// group of updates hands out the new meshes of those chunks followed by the
/// removals of the chunks they replace, all in the same poll() (poll() never
/// splits a group, see its maxUpdates). Meshes of chunks that overlap a
/// retained chunk are withheld until then. So after every poll() the chunks
/// the caller holds never overlap and cover every surface the resident set
/// covers; while old and new chunks are mixed their seams may not weld
/// exactly (each seam follows the neighbour levels it was meshed with), and
/// they are re-meshed to weld once the neighbours settle. A chunk that comes
/// back into the set before its replacement was handed out keeps its mesh
/// with the caller and is meshed again. Evictions beyond viewRadius are
/// reported at once. Retained meshes are never edited: an edit shows on the
/// replacements.
///
/// **Meshing and LOD without cracks.** Each chunk is meshed by dual contouring
/// on the octree of cells, with surface-nets vertices (the mean of the cell's
/// edge crossings; the cell centre for a coarse cell whose own corners do not
/// change sign): one quad per *minimal* lattice edge whose ends differ in sign,
/// joining the vertices of the leaf cells around the edge; where two of those
/// cells are the same coarse cell the quad becomes a triangle. On the face
/// between a fine and a coarse chunk the minimal edges are the fine ones, so
/// the seam is made of fine edges joined to the coarse cells across it: the
/// union of the chunk meshes is closed across LOD borders exactly as inside a
/// level (Ju et al., "Dual Contouring of Hermite Data", 2002, closedness of
/// minimal-edge polygons). A chunk owns the edges whose lower end lies in it
/// (half-open box), so the seam with a lower neighbour is in the chunk itself
/// and depends on the levels of its 7 lower neighbours (its *signature*); a
/// chunk is re-meshed when its signature changes. Skirts were not chosen
/// because they leave open boundary edges (and visible flaps from the side);
/// Transvoxel was not chosen because it needs marching-cubes tables and a
/// separate transition-cell mesher, while the dual seam is the same quad rule
/// with a different cell lookup. The partition rule keeps neighbouring levels
/// within one of each other (checked: lodDistance >= 2·sqrt(3)·chunk width).
///
/// **Edits** are stored sparsely in one OpenVDB FloatGrid at voxel resolution
/// (voxel size voxelSize, lattice point i at voxel i): an active voxel holds
/// the *edited density* of that lattice point, which replaces the procedural
/// value. A dig sets d = max(d, −shape) (smooth: smoothMax), a fill d =
/// min(d, shape), on the lattice points within editBand voxels of the shape's
/// surface (plus the blend radius); points deeper inside get ±editBand·voxel
/// (exact in sign; at coarse levels the vertices there interpolate the clamped
/// values). Edits persist while chunks are evicted and reloaded, and are
/// saved and loaded as .vdb. An edit marks the resident chunks whose *sample
/// footprint* holds a changed sample: for a chunk of level l with minimum
/// voxel m, the level-l lattice points in [m − 2·2^l, m + chunkSize·2^l] per
/// axis, and, when a lower neighbour is finer, also the level-(l−1) ones
/// (the seam's fine samples). That is exactly the set of samples its mesh is
/// computed from.
///
/// **Threading.** Chunks are sampled and meshed on a TBB task arena of
/// `threads` threads. Every public member function of World is safe to call
/// from any thread, concurrently with the others and with the chunk tasks
/// (internal mutexes; the edit grid is read under a shared lock). poll(),
/// the edits and setPointsOfInterest() never wait for chunk tasks: poll()
/// only collects finished meshes, applies a finished partition and schedules
/// more (O(resident chunks) walks, no partition computation: that runs on
/// the world's partition thread); an edit costs the
/// evaluation of its band of samples on the calling thread and the pool
/// (measured on the default terrain: 0.4 ms for a 2 m sphere, 7.5 ms for a
/// 10 m one); queries evaluate the field directly and never wait for meshes. waitIdle() is the one blocking call (for tools and
/// batch jobs). Only the destructor must not run concurrently with other calls;
/// it cancels queued tasks and waits for running ones.
///
/// **Determinism.** A chunk mesh is a pure function of the field, the edits,
/// its key and its signature: the same bytes whatever the thread count and
/// the order in which tasks run or finish. The resident set is a pure
/// function of the interest chunks; which intermediate sets a moving point
/// passes through, and when replacements are handed out, depend on timing,
/// but once the points stop and waitIdle() returns the meshes do not.

#include <strata/terrain/DensityField.h>
#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/RockMasks.h>
#include <strata/world/WorldTypes.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

namespace strata::world {

struct WorldOptions
{
    double voxelSize = 0.5; ///< metres per voxel at level 0, > 0
    int chunkSize = 32;     ///< cells per chunk edge: a power of two in [8, 128]
    int levels = 4;         ///< LOD levels 1..8: cells of 1, 2, 4, ... 2^(levels−1) voxels
    /// Level 0 is used within about this distance (metres) of a point of
    /// interest (measured from the centre of its level-0 chunk), level l within
    /// lodDistance·2^l. 0 = 4 chunk widths of level
    /// 0. Must be at least 2·sqrt(3) level-0 chunk widths (keeps neighbours
    /// within one level), checked.
    double lodDistance = 0.0;
    /// Top-level chunks farther than this from the centre of the level-0
    /// chunk of every point of interest are evicted (metres, > 0). 0 = 3 chunk widths of the
    /// top level.
    double viewRadius = 0.0;
    int threads = 0; ///< task arena concurrency; 0 = all cores
    /// Half width (in voxels, 1..16) of the band of lattice samples an edit
    /// evaluates exactly around the shape's surface.
    int editBand = 3;
    /// Chunk tasks queued on the pool at most (0 = 2·threads + 2); the rest
    /// wait in the world, nearest first, so a moving point of interest is
    /// served first.
    int maxInFlight = 0;
    /// Chunks of levels below this keep their procedural samples between
    /// re-meshes (about 170 KiB per 32³ chunk that holds surface), so an
    /// edit re-meshes them without evaluating the field again: the edit
    /// latency drops about tenfold. 0 = no cache; `levels` = all levels.
    int sampleCacheLevels = 1;
    /// 0: schedule chunks nearest first. Other values: in a pseudo-random
    /// order drawn from this seed (to exercise other orders: results never depend on it).
    std::uint64_t taskOrderSeed = 0;
    /// Last, so brace-initialised options written before it keep their
    /// meaning. Landform masks (an `erode` node: flow, wear, deposition, water) to
    /// fill each chunk mesh's `landform` with, for terrain layer rules; null:
    /// none. Its global pass has run when the node was built, before the
    /// World exists.
    std::shared_ptr<const terrain::LandformMasks> landform;
    /// Mesh ahead of time the chunks of the partition the points of
    /// interest will need after their next level-0 chunk border, along the
    /// direction each last moved (see the file comment, "Look-ahead"), so a
    /// moving point finds them ready. Costs the chunks meshed for a
    /// direction not taken (WorldStats::prefetchDropped); false: mesh only
    /// for the resident set.
    bool lookAhead = true;
    /// Rock masks (a `beds` node: hardness, bed) to fill each chunk mesh's
    /// `rock` with, for terrain layer rules; null: none. After lookAhead,
    /// so brace-initialised options written before it keep their meaning.
    std::shared_ptr<const terrain::RockMasks> rock;
};

class World
{
public:
    /// Takes shared ownership of `field` (must not be null; its density() is
    /// called concurrently from the pool). Throws strata::Error on bad options,
    /// naming the option and value.
    World(std::shared_ptr<const terrain::DensityField> field, const WorldOptions& options = {});
    /// Cancels queued chunk tasks and waits for running ones.
    ~World();
    World(const World&) = delete;
    World& operator=(const World&) = delete;

    /// The options in effect (defaults resolved).
    const WorldOptions& options() const;

    /// Replaces the points of interest (world metres). When the level-0
    /// chunks holding them change, the partition thread computes the new
    /// resident set and the first poll() after it is ready applies it (about
    /// 1 ms later for 1500 chunks); otherwise nothing changes. O(points) on
    /// the calling thread. Throws strata::Error on a non-finite point.
    void setPointsOfInterest(std::vector<glm::dvec3> points);

    /// Collects finished chunk meshes and evictions since the last call, and
    /// queues more chunk tasks. Never waits for a task. Updates for one key
    /// come in the order they happened. A replacement after an LOD change
    /// (the new meshes, then the removals of the chunks they replace: see the
    /// file comment) is one group that is never split: at most `maxUpdates`
    /// updates are returned, except that a first group larger than that is
    /// returned whole; the rest stay for the next call. Apply all updates of
    /// one call before drawing, and the chunks you hold cover the surface.
    /// Cost: O(resident chunks) walks, plus O(retained chunks · the chunks
    /// covering them) map look-ups while LOD changes are pending.
    std::vector<ChunkUpdate> poll(std::size_t maxUpdates = SIZE_MAX);

    /// True when the resident set follows the latest points of interest,
    /// every resident chunk has its current mesh, no task is queued and no
    /// replacement waits to be handed out by poll().
    bool idle() const;
    /// Blocks until idle() (keeps scheduling meanwhile); the updates wait for
    /// poll(). For tools, batch jobs and benchmarks.
    void waitIdle();

    /// Applies an edit (see the file comment). Throws strata::Error on an
    /// invalid shape or a negative blend radius; the world is unchanged then.
    /// Cost: O(samples in the band around the shape's surface), on the
    /// calling thread and the pool.
    EditResult apply(const Edit& edit);
    EditResult dig(const EditShape& shape, double smoothRadius = 0.0);
    EditResult fill(const EditShape& shape, double smoothRadius = 0.0);

    /// Writes the edit grid ("edits", FloatGrid, voxel size = voxelSize) to a
    /// .vdb file atomically; the same edits give the same bytes. Throws
    /// strata::Error naming the path.
    void saveEdits(const std::filesystem::path& path) const;
    /// Replaces all edits by those of a file written by saveEdits() and marks
    /// the chunks whose samples differ. Throws strata::Error naming the path
    /// if it cannot be read, holds no float grid named "edits", or its voxel
    /// size differs from voxelSize; the world is unchanged then.
    EditResult loadEdits(const std::filesystem::path& path);

    /// The density at a world point: trilinear interpolation of the level-0
    /// lattice samples (procedural values and edits), i.e. the field the
    /// finest chunks mesh. 8 field evaluations.
    double density(const glm::dvec3& p) const;
    /// First surface hit along origin + t·direction, 0 <= t <= maxDistance
    /// (metres; direction need not be unit, must not be zero). A ray starting
    /// inside rock hits at t = 0. Steps of at most a quarter voxel near the
    /// surface (features thinner than that may be missed), then bisection.
    std::optional<RayHit> raycast(const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance) const;
    /// True when every level-0 lattice sample of the cells the box overlaps
    /// is negative, which makes density() negative all over the box
    /// (conservative). Whole 8³ blocks are decided by the field's distance
    /// bound where no edit lies; O(box volume / 512 + samples evaluated).
    bool isBoxSolid(const glm::dvec3& min, const glm::dvec3& max) const;

    WorldStats stats() const;

    /// The current mesh of a resident chunk (null if not resident or not
    /// meshed yet).
    std::shared_ptr<const ChunkMeshData> chunkMesh(const ChunkKey& key) const;
    /// The resident chunk keys, sorted.
    std::vector<ChunkKey> residentChunks() const;

    /// The world box of a chunk (metres).
    void chunkBounds(const ChunkKey& key, glm::dvec3& min, glm::dvec3& max) const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

} // namespace strata::world
