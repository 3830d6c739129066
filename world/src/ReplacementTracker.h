// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the World's resident chunks and their replacement bookkeeping.
// Which chunks are resident (the LOD partition, applied by rebuild()), which
// need a mesh (generations), and the queue of updates poll() hands out, with
// the meshes of split or merged chunks kept until every chunk replacing them
// is meshed (groups). Not thread-safe: the World calls it with its mutex held.

#include <strata/world/WorldTypes.h>

#include "ChunkMesher.h"
#include "LodPartition.h"

#include <deque>
#include <map>
#include <memory>
#include <set>
#include <vector>

namespace strata::world::detail {

struct ChunkState
{
    Signature signature{};
    double distance = 0.0;
    std::uint64_t generation = 0; ///< from ReplacementTracker::generations: set on creation, bumped by edits and signature changes
    std::uint64_t meshedGeneration = 0;
    bool inFlight = false;
    bool delivered = false; ///< the caller holds a non-empty mesh for it
    bool withheld = false;  ///< `mesh` is newer than what the caller holds: it waits for a replacement group
    bool everMeshed = false;
    std::shared_ptr<const ChunkMeshData> mesh;
    std::shared_ptr<SampleCache> cache; ///< null for levels without one

    bool dirty() const { return meshedGeneration != generation; }
};

/// A chunk of the look-ahead partition (where the points of interest go
/// next) that is not resident with the signature it will have there: new,
/// or its neighbours' levels change. Meshed ahead of time when the pool has
/// nothing resident to do; rebuild() hands the mesh to the chunk when the
/// partition it was made for arrives.
struct AheadChunk
{
    Signature signature{};
    double distance = 0.0;
    bool inFlight = false;
    bool stale = false;  ///< an edit touched its samples while its task ran: the result is dropped
    bool wanted = true;  ///< still in the look-ahead partition; if not, erased once its task ends
    std::shared_ptr<const ChunkMeshData> mesh;
    std::shared_ptr<SampleCache> cache; ///< handed to the chunk with the mesh; null for levels without one
};

/// An entry of the update queue: `groupSize` > 0 starts a group of that many
/// updates that poll() hands out together (the replacement of chunks after an
/// LOD change); 0 continues the group.
struct QueuedUpdate
{
    ChunkUpdate update;
    std::size_t groupSize = 1;
};

struct Finished
{
    ChunkKey key;
    Signature signature{};
    std::uint64_t generation = 0;
    std::shared_ptr<const ChunkMeshData> mesh;
    bool ahead = false; ///< meshed for the look-ahead partition (AheadChunk), not for a resident chunk
};

class ReplacementTracker
{
public:
    /// `levels` and `sampleCacheLevels` as in WorldOptions.
    ReplacementTracker(int levels, int sampleCacheLevels)
        : mLevels(levels)
        , mSampleCacheLevels(sampleCacheLevels)
    {
    }

    /// Moves `chunks` to a new partition. Chunks the caller holds that leave
    /// it go to `retired` when the new partition still covers them (an LOD
    /// change), else they are reported removed at once (eviction).
    void rebuild(const std::map<ChunkKey, PartitionEntry>& target);

    /// Sets the look-ahead partition: the resident set after the points'
    /// next level-0 chunk border (empty: none). Call after rebuild().
    void setLookAhead(const std::map<ChunkKey, PartitionEntry>& next);

    /// Hands out every group whose covering chunks are all meshed: their
    /// withheld meshes, then the removals of the retired chunks, as one group
    /// of updates. O(groups · covering chunks).
    void release();

    /// Takes a finished mesh: delivered, withheld for a replacement group,
    /// or discarded when the chunk left or changed meanwhile. A look-ahead
    /// mesh is kept for its chunk, or handed to it at once when the chunk
    /// became resident meanwhile and waits for it.
    void accept(Finished& f);

    /// A task for `key` ended without a mesh (an error, or the world stops).
    void abandoned(const ChunkKey& key, bool ahead);

    /// Is a look-ahead task running that will give this resident chunk its
    /// current mesh? Then the scheduler does not launch the chunk again.
    bool aheadCovers(const ChunkKey& key, const ChunkState& state) const;

    /// Does the caller hold nothing for this chunk's box: never meshed, and
    /// no retired mesh of a split or merge stands in for it (a chunk that
    /// just came into view)? The view has a hole there until it is meshed.
    bool uncovered(const ChunkKey& key, const ChunkState& state) const
    {
        return !state.everMeshed && groupOf.find(key) == groupOf.end();
    }

    /// Would this look-ahead chunk be a hole when its partition arrives: no
    /// resident chunk of its key, ancestor or descendants tiling it has a
    /// mesh that could stand in for it (new ground coming into view)?
    bool aheadWouldBeHole(const ChunkKey& key) const { return chunks.count(key) == 0 && cover(key).empty(); }

    /// Marks the resident chunks whose sample footprint holds a changed
    /// lattice point (`chunkSize` cells per chunk edge).
    EditResult mark(const std::vector<openvdb::Coord>& changed, int chunkSize);

    /// Up to `maxUpdates` queued updates, never splitting a group (a group
    /// larger than the limit goes out alone).
    std::vector<ChunkUpdate> poll(std::size_t maxUpdates);

    bool anyDirty() const;
    /// Nothing withheld or retired: the caller holds exactly the resident meshes.
    bool settled() const { return retired.empty() && withheldKeys.empty(); }

    std::map<ChunkKey, ChunkState> chunks;
    /// Chunks that left the resident set by a split or merge while the caller
    /// holds their meshes: kept until every chunk covering them is meshed.
    std::map<ChunkKey, ChunkState> retired;
    /// The look-ahead partition's chunks that differ from the resident ones.
    std::map<ChunkKey, AheadChunk> ahead;
    WorldStats counters; ///< generated, remeshed, evicted, discarded, prefetched, prefetchDropped

private:
    void push(ChunkUpdate update) { updates.push_back(QueuedUpdate{std::move(update), 1}); }
    /// Gives a resident chunk its mesh of `generation` (checked by the caller).
    void install(const ChunkKey& key, ChunkState& state, std::uint64_t generation,
                 std::shared_ptr<const ChunkMeshData> mesh);
    void acceptAhead(Finished& f);

    /// The resident chunks covering a retired chunk's box: its resident
    /// ancestor, or the resident descendants that tile it; empty when the
    /// resident set does not cover it (its top-level chunk was evicted).
    std::vector<ChunkKey> cover(const ChunkKey& key) const;
    bool tile(const ChunkKey& key, std::vector<ChunkKey>& out) const;

    int mLevels;
    int mSampleCacheLevels;
    std::set<ChunkKey> withheldKeys; ///< resident chunks with `withheld` set
    /// A replacement: retired chunks and the resident chunks covering them
    /// (a split: one retired chunk and its resident descendants; a merge: the
    /// retired descendants of one resident chunk). Keyed by the coarsest
    /// chunk of the group; rebuilt whenever the partition changes, so the
    /// state pointers stay valid (`chunks` erases only in rebuild()).
    struct Group
    {
        std::vector<ChunkKey> retired;
        std::vector<std::pair<ChunkKey, ChunkState*>> covers;
    };
    std::map<ChunkKey, Group> groups;
    std::map<ChunkKey, ChunkKey> groupOf; ///< covering resident chunk -> its group's key
    bool releaseDue = false;              ///< a group may have become ready
    std::deque<QueuedUpdate> updates;
    std::uint64_t generations = 0; ///< a world-wide counter, so a chunk evicted and reloaded never reuses one
};

} // namespace strata::world::detail
