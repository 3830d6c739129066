// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: runs the World's chunk tasks. Picks the dirty resident chunks
// nearest the points of interest (or in a seeded random order, for tests),
// then the look-ahead chunks (AheadChunk) the same way, meshes each on the
// World's task arena from a snapshot of the edits, and collects the finished
// meshes for the World to accept. The state below is
// guarded by the World's mutex (passed in); tasks take it to report.

#include "ChunkMesher.h"
#include "EditLayer.h"
#include "ReplacementTracker.h"

#include <strata/terrain/DensityField.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <vector>

namespace strata::world::detail {

struct SchedulerParams
{
    MesherParams mesher;
    int threads = 1;              ///< task arena workers
    std::size_t maxInFlight = 4;  ///< tasks running or queued at most
    std::uint64_t taskOrderSeed = 0; ///< 0: nearest first; else a seeded order
};

class ChunkScheduler
{
public:
    /// `mutex` guards the tracker and this scheduler's state; `finishedSignal`
    /// is notified whenever a task ends.
    ChunkScheduler(std::shared_ptr<const terrain::DensityField> field, const SchedulerParams& params,
                   const EditLayer& edits, ReplacementTracker& tracker, std::mutex& mutex,
                   std::condition_variable& finishedSignal);

    /// With the mutex held: orders the dirty chunks not in flight, then the
    /// look-ahead chunks not meshed yet, and launches them, up to maxInFlight
    /// tasks. The World calls it at each
    /// poll(); the rest wait in the queue for launchQueued().
    void schedule();

    /// With the mutex held: launches the next chunks of the queue that
    /// schedule() ordered (those still dirty and not in flight), up to
    /// maxInFlight tasks. Each task calls it as it ends: one step down the
    /// queue instead of a pass over every resident chunk.
    void launchQueued();

    /// Guarded by the mutex.
    std::vector<Finished> finished; ///< meshes waiting for ReplacementTracker::accept()
    std::size_t inFlight = 0;       ///< tasks launched and not ended
    bool stopping = false;          ///< set at destruction: tasks not started yet skip their work
    std::exception_ptr failure;     ///< the first error of a task, for the caller

private:
    /// What a chunk task needs, on the heap: the task object itself holds
    /// only this pointer, so nothing of ours lives in TBB's recycled task
    /// memory (whose reuse ThreadSanitizer cannot order).
    struct Job
    {
        ChunkScheduler* scheduler;
        ChunkKey key;
        Signature signature;
        std::uint64_t generation;
        std::shared_ptr<SampleCache> cache;
        bool ahead; ///< for the look-ahead partition
    };
    struct Queued
    {
        ChunkKey key;
        bool ahead;
    };

    double order(const ChunkKey& key, double distance) const;
    void launch(const ChunkKey& key, const Signature& signature, std::uint64_t generation,
                std::shared_ptr<SampleCache> cache, bool ahead);
    void runTask(Job& job);

    std::shared_ptr<const terrain::DensityField> mField;
    SchedulerParams mParams;
    std::vector<Queued> mQueue; ///< chunks in launch order, from the last schedule()
    std::size_t mQueueNext = 0;   ///< the first entry of mQueue not taken yet
    const EditLayer& mEdits;
    ReplacementTracker& mTracker;
    std::mutex& mMutex;
    std::condition_variable& mFinishedSignal;
    /// TBB caps its workers at the core count − 1 unless told otherwise; the
    /// arena's `threads` workers need that many (plus the caller's slot).
    tbb::global_control mParallelism;
    tbb::task_arena mArena;
};

} // namespace strata::world::detail
