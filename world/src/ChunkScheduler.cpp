// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ChunkScheduler.h"
#include <strata/detail/IntegerHash.h>
#include <strata/detail/TsanHandOver.h>

#include <algorithm>
#include <tuple>

namespace strata::world::detail {

using strata::detail::tsanHandOff;
using strata::detail::tsanTakeOver;
using strata::detail::tsanUncheckedRead;

namespace {

using strata::detail::mix64;

} // namespace

ChunkScheduler::ChunkScheduler(std::shared_ptr<const terrain::DensityField> field, const SchedulerParams& params,
                               const EditLayer& edits, ReplacementTracker& tracker, std::mutex& mutex,
                               std::condition_variable& finishedSignal)
    : mField(std::move(field))
    , mParams(params)
    , mEdits(edits)
    , mTracker(tracker)
    , mMutex(mutex)
    , mFinishedSignal(finishedSignal)
    , mParallelism(tbb::global_control::max_allowed_parallelism,
                   std::max(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism),
                            std::size_t(params.threads) + 1))
    , mArena(params.threads, 0)
{
}

double ChunkScheduler::order(const ChunkKey& key, double distance) const
{
    if (mParams.taskOrderSeed == 0) return distance;
    const std::uint64_t h =
        mix64(mParams.taskOrderSeed ^ mix64(std::uint64_t(key.level) * strata::detail::SPLITMIX64_STEP ^
                                            mix64(std::uint64_t(std::uint32_t(key.x)) << 32 ^
                                                  std::uint64_t(std::uint32_t(key.y))) ^
                                            std::uint64_t(std::uint32_t(key.z))));
    return double(h >> 11);
}

void ChunkScheduler::schedule()
{
    // Holes first: chunks the caller holds nothing for (they just came into
    // view, mostly coarse ones at its edge); then the look-ahead chunks that
    // will be holes when the points cross the next border; then chunks whose
    // old or retired meshes stand in until they are replaced (an LOD change,
    // an edit); then the rest of the look-ahead. Nearest first within each.
    // When the pool cannot keep up, the view stays whole and the backlog is
    // refinement.
    enum Rank { HOLE, HOLE_AHEAD, STAND_IN, AHEAD };
    std::vector<std::tuple<Rank, double, ChunkKey, bool>> candidates;
    for (auto& [key, state] : mTracker.chunks) {
        if (state.inFlight || !state.dirty() || mTracker.aheadCovers(key, state)) continue;
        candidates.emplace_back(mTracker.uncovered(key, state) ? HOLE : STAND_IN, order(key, state.distance), key, false);
    }
    for (auto& [key, chunk] : mTracker.ahead)
        if (chunk.wanted && !chunk.inFlight && !chunk.mesh)
            candidates.emplace_back(mTracker.aheadWouldBeHole(key) ? HOLE_AHEAD : AHEAD, order(key, chunk.distance), key,
                                    true);
    std::sort(candidates.begin(), candidates.end());
    mQueue.clear();
    for (const auto& candidate : candidates) mQueue.push_back({std::get<2>(candidate), std::get<3>(candidate)});
    mQueueNext = 0;
    launchQueued();
}

void ChunkScheduler::launchQueued()
{
    while (inFlight < mParams.maxInFlight && mQueueNext < mQueue.size()) {
        const Queued next = mQueue[mQueueNext++];
        // The tracker may have changed since schedule() (a chunk evicted,
        // accepted, or launched): only a chunk still waiting goes.
        if (next.ahead) {
            const auto found = mTracker.ahead.find(next.key);
            if (found == mTracker.ahead.end()) continue;
            AheadChunk& chunk = found->second;
            if (!chunk.wanted || chunk.inFlight || chunk.mesh) continue;
            chunk.inFlight = true;
            ++inFlight;
            launch(next.key, chunk.signature, 0, chunk.cache, true);
            continue;
        }
        const auto found = mTracker.chunks.find(next.key);
        if (found == mTracker.chunks.end()) continue;
        ChunkState& state = found->second;
        if (state.inFlight || !state.dirty() || mTracker.aheadCovers(next.key, state)) continue;
        state.inFlight = true;
        ++inFlight;
        launch(next.key, state.signature, state.generation, state.cache, false);
    }
}

void ChunkScheduler::launch(const ChunkKey& key, const Signature& signature, std::uint64_t generation,
                            std::shared_ptr<SampleCache> cache, bool ahead)
{
    Job* job = new Job{this, key, signature, generation, std::move(cache), ahead};
    // task_arena::enqueue() orders everything before it (the Job written
    // here) before the task runs: TBB's guarantee, so no lock is needed. A
    // process-wide mutex taken here and first thing in every task only made
    // that edge visible to ThreadSanitizer, which cannot see TBB's atomics;
    // the annotations say the same to it at no cost in other builds.
    tsanHandOff(job);
    mArena.enqueue([job] {
        Job* const mine = tsanUncheckedRead(job); // the capture lives in TBB's task memory
        tsanTakeOver(mine);
        std::unique_ptr<Job> owned(mine);
        owned->scheduler->runTask(*owned);
    });
}

void ChunkScheduler::runTask(Job& job)
{
    Finished result{job.key, job.signature, job.generation, nullptr, job.ahead};
    std::exception_ptr error;
    bool stop;
    {
        std::lock_guard<std::mutex> lock(mMutex);
        stop = stopping;
    }
    if (!stop) {
        try {
            const std::unique_ptr<EditSnapshot> snapshot =
                mEdits.snapshot(editFootprint(mParams.mesher, job.key));
            std::unique_lock<std::mutex> cacheLock;
            if (job.cache) cacheLock = std::unique_lock<std::mutex>(job.cache->mutex);
            result.mesh = std::make_shared<ChunkMeshData>(
                meshChunk(*mField, mParams.mesher, job.key, job.signature, *snapshot, job.cache.get()));
        } catch (...) {
            error = std::current_exception();
        }
    }
    job.cache.reset(); // before the world may be destroyed
    std::lock_guard<std::mutex> lock(mMutex);
    if (result.mesh) finished.push_back(std::move(result));
    else mTracker.abandoned(job.key, job.ahead);
    if (error && !failure) failure = std::move(error);
    --inFlight;
    // Refill the pool now rather than at the next poll(): between two polls
    // (a frame) the workers would otherwise run dry once the tasks in
    // flight are done, which capped streaming at maxInFlight chunks a frame.
    if (!stopping && !failure) launchQueued();
    mFinishedSignal.notify_all();
}

} // namespace strata::world::detail
