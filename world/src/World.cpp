// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/world/World.h>

#include <strata/Finite.h>
#include <strata/Format.h>

#include "ChunkScheduler.h"
#include "EditLayer.h"
#include "LodPartition.h"
#include "MotionLookAhead.h"
#include "ReplacementTracker.h"
#include "WorldQueries.h"

#include <strata/Error.h>

#include <cmath>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace strata::world {

using openvdb::Coord;

/// The World's coordination: one mutex over the resident chunks (tracker)
/// and the tasks (scheduler), the partition thread that turns points of
/// interest into a resident set, and pump(), which applies what the threads
/// produced. Queries (WorldQueries.h) need none of it.
struct World::Impl
{
    std::shared_ptr<const terrain::DensityField> field;
    WorldOptions options;
    detail::LodParams lod;
    detail::EditLayer edits;

    mutable std::mutex mutex;
    std::condition_variable finishedSignal;
    std::condition_variable partitionSignal;
    /// The level-0 chunks holding the points of interest (the partition's
    /// input), those they enter next (the look-ahead partition's), and a
    /// version bumped when either changes.
    std::vector<ChunkKey> interest;
    std::vector<ChunkKey> nextInterest;
    detail::MotionLookAhead motion;
    std::uint64_t interestVersion = 0;
    std::uint64_t appliedVersion = 0; ///< the version `tracker.chunks` follows
    /// Partitions computed by the partition thread, not yet applied.
    struct PartitionResult
    {
        std::uint64_t version = 0;
        std::map<ChunkKey, detail::PartitionEntry> now;
        std::map<ChunkKey, detail::PartitionEntry> next; ///< empty when the points stand still
    };
    std::optional<PartitionResult> partitionResult;
    std::thread partitionThread;
    detail::ReplacementTracker tracker;
    detail::ChunkScheduler scheduler;

    Impl(std::shared_ptr<const terrain::DensityField> f, const WorldOptions& o)
        : field(std::move(f))
        , options(o)
        , lod{o.voxelSize, o.chunkSize, o.levels, o.lodDistance, o.viewRadius}
        , edits(o.voxelSize)
        , tracker(o.levels, o.sampleCacheLevels)
        , scheduler(field,
                    detail::SchedulerParams{detail::MesherParams{o.voxelSize, o.chunkSize, o.landform.get(), o.rock.get()}, o.threads,
                                            std::size_t(o.maxInFlight), o.taskOrderSeed},
                    edits, tracker, mutex, finishedSignal)
    {
    }

    // --- with `mutex` held -------------------------------------------------

    /// Rethrows a task's or the partition thread's error, applies a new
    /// partition, accepts finished meshes, releases ready replacement groups
    /// and launches more tasks.
    void pump()
    {
        if (scheduler.failure) {
            // Moved, not copied: libstdc++ counts an exception's references
            // with atomics that ThreadSanitizer does not see (it reports the
            // worker's and the caller's counts as a race).
            std::exception_ptr e = std::move(scheduler.failure);
            scheduler.failure = nullptr;
            std::rethrow_exception(std::move(e));
        }
        if (partitionResult) {
            tracker.rebuild(partitionResult->now);
            tracker.setLookAhead(partitionResult->next);
            appliedVersion = partitionResult->version;
            partitionResult.reset();
        }
        for (detail::Finished& f : scheduler.finished) tracker.accept(f);
        scheduler.finished.clear();
        tracker.release();
        scheduler.schedule();
    }

    /// The partition thread: computes the resident set for each new version
    /// of `interest` off the callers' threads; pump() applies it.
    void partitionLoop()
    {
        std::unique_lock<std::mutex> lock(mutex);
        std::uint64_t computed = 0;
        // The last look-ahead partition and its input: when the points cross
        // as predicted, it is the new resident set, not computed again.
        std::vector<ChunkKey> lastNextInput;
        std::map<ChunkKey, detail::PartitionEntry> lastNext;
        for (;;) {
            partitionSignal.wait(lock, [&] { return scheduler.stopping || interestVersion != computed; });
            if (scheduler.stopping) return;
            const std::uint64_t version = interestVersion;
            const std::vector<ChunkKey> input = interest;
            const std::vector<ChunkKey> nextInput = nextInterest;
            lock.unlock();
            PartitionResult result{version, {}, {}};
            std::exception_ptr error;
            try {
                result.now = input == lastNextInput && !lastNext.empty() ? lastNext
                                                                        : detail::computePartition(input, lod);
                if (nextInput != input) result.next = detail::computePartition(nextInput, lod);
                lastNextInput = nextInput;
                lastNext = result.next;
            } catch (...) {
                error = std::current_exception();
            }
            lock.lock();
            computed = version;
            if (error) {
                if (!scheduler.failure) scheduler.failure = std::move(error);
            } else {
                partitionResult = std::move(result);
            }
            finishedSignal.notify_all();
        }
    }

    /// Has the resident set caught up with the latest points of interest?
    bool partitionCurrent() const { return appliedVersion == interestVersion && !partitionResult; }

    EditResult mark(const std::vector<Coord>& changed)
    {
        std::lock_guard<std::mutex> lock(mutex);
        return tracker.mark(changed, options.chunkSize);
    }
};

World::World(std::shared_ptr<const terrain::DensityField> field, const WorldOptions& options)
{
    if (!field) throw Error(ErrorKind::BadInput, "World: the density field is null");
    WorldOptions o = options;
    if (!std::isfinite(o.voxelSize) || o.voxelSize <= 0.0)
        throw Error(ErrorKind::BadInput, "WorldOptions: voxelSize = " + formatNumber(o.voxelSize) + " must be finite and > 0");
    if (o.chunkSize < 8 || o.chunkSize > 128 || (o.chunkSize & (o.chunkSize - 1)) != 0)
        throw Error(ErrorKind::BadInput, "WorldOptions: chunkSize = " + std::to_string(o.chunkSize) + " must be a power of two in [8, 128]");
    if (o.levels < 1 || o.levels > 8)
        throw Error(ErrorKind::BadInput, "WorldOptions: levels = " + std::to_string(o.levels) + " must be in [1, 8]");
    const double w0 = o.chunkSize * o.voxelSize;
    if (o.lodDistance == 0.0) o.lodDistance = 4.0 * w0;
    const double minLod = 2.0 * std::sqrt(3.0) * w0;
    if (!std::isfinite(o.lodDistance) || (o.levels > 1 && o.lodDistance < minLod) || o.lodDistance < 0.0)
        throw Error(ErrorKind::BadInput, "WorldOptions: lodDistance = " + formatNumber(o.lodDistance) + " must be at least 2·sqrt(3) chunk widths (" +
                    formatNumber(minLod) + " m)");
    if (o.viewRadius == 0.0) o.viewRadius = 3.0 * w0 * double(1 << (o.levels - 1));
    if (!std::isfinite(o.viewRadius) || o.viewRadius <= 0.0)
        throw Error(ErrorKind::BadInput, "WorldOptions: viewRadius = " + formatNumber(o.viewRadius) + " must be finite and > 0");
    if (o.threads < 0) throw Error(ErrorKind::BadInput, "WorldOptions: threads = " + std::to_string(o.threads) + " must be >= 0");
    if (o.threads == 0) o.threads = int(std::max(1u, std::thread::hardware_concurrency()));
    if (o.editBand < 1 || o.editBand > 16)
        throw Error(ErrorKind::BadInput, "WorldOptions: editBand = " + std::to_string(o.editBand) + " must be in [1, 16]");
    if (o.sampleCacheLevels < 0 || o.sampleCacheLevels > o.levels)
        throw Error(ErrorKind::BadInput, "WorldOptions: sampleCacheLevels = " + std::to_string(o.sampleCacheLevels) + " must be in [0, levels]");
    if (o.maxInFlight < 0) throw Error(ErrorKind::BadInput, "WorldOptions: maxInFlight = " + std::to_string(o.maxInFlight) + " must be >= 0");
    if (o.maxInFlight == 0) o.maxInFlight = 2 * o.threads + 2;
    openvdb::initialize();
    mImpl = std::make_unique<Impl>(std::move(field), o);
    mImpl->partitionThread = std::thread([impl = mImpl.get()] { impl->partitionLoop(); });
}

World::~World()
{
    {
        std::lock_guard<std::mutex> lock(mImpl->mutex);
        mImpl->scheduler.stopping = true;
        mImpl->partitionSignal.notify_all();
    }
    mImpl->partitionThread.join();
    std::unique_lock<std::mutex> lock(mImpl->mutex);
    mImpl->finishedSignal.wait(lock, [&] { return mImpl->scheduler.inFlight == 0; });
}

const WorldOptions& World::options() const
{
    return mImpl->options;
}

void World::setPointsOfInterest(std::vector<glm::dvec3> points)
{
    const double limit = double(1 << 29) * mImpl->options.voxelSize - mImpl->options.viewRadius -
                         detail::chunkWidth(mImpl->lod, mImpl->options.levels - 1);
    for (const glm::dvec3& p : points) {
        if (!isFinite(p)) throw Error(ErrorKind::BadInput, "World: point of interest (" + formatNumber(p.x) + ", " + formatNumber(p.y) + ", " + formatNumber(p.z) +
                                    ") is not finite");
        if (std::abs(p.x) > limit || std::abs(p.y) > limit || std::abs(p.z) > limit)
            throw Error(ErrorKind::BadInput, "World: point of interest (" + formatNumber(p.x) + ", " + formatNumber(p.y) + ", " + formatNumber(p.z) +
                        ") is farther than " + formatNumber(limit) + " m from the origin");
    }
    std::vector<ChunkKey> interest = detail::interestChunks(points, mImpl->lod);
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    std::vector<ChunkKey> next = interest;
    if (mImpl->options.lookAhead) {
        mImpl->motion.update(points);
        next = mImpl->motion.nextInterest(mImpl->lod);
    }
    // The same level-0 chunks, now and next: the same partitions.
    if (interest == mImpl->interest && next == mImpl->nextInterest) return;
    mImpl->interest = std::move(interest);
    mImpl->nextInterest = std::move(next);
    ++mImpl->interestVersion;
    mImpl->partitionSignal.notify_all();
}

std::vector<ChunkUpdate> World::poll(std::size_t maxUpdates)
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    mImpl->pump();
    return mImpl->tracker.poll(maxUpdates);
}

bool World::idle() const
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    return mImpl->partitionCurrent() && mImpl->scheduler.inFlight == 0 && mImpl->scheduler.finished.empty() &&
           mImpl->tracker.settled() && !mImpl->tracker.anyDirty();
}

void World::waitIdle()
{
    std::unique_lock<std::mutex> lock(mImpl->mutex);
    for (;;) {
        mImpl->pump();
        const bool partitionDone = mImpl->partitionCurrent();
        if (partitionDone && mImpl->scheduler.inFlight == 0 && !mImpl->tracker.anyDirty()) return;
        mImpl->finishedSignal.wait(lock, [&] {
            return !mImpl->scheduler.finished.empty() || mImpl->scheduler.failure || mImpl->partitionResult ||
                   (mImpl->scheduler.inFlight == 0 && partitionDone);
        });
    }
}

EditResult World::apply(const Edit& edit)
{
    edit.shape.validate();
    if (!std::isfinite(edit.smoothRadius) || edit.smoothRadius < 0.0)
        throw Error(ErrorKind::BadInput, "edit: smoothRadius = " + formatNumber(edit.smoothRadius) + " must be finite and >= 0");
    const std::vector<Coord> changed = mImpl->edits.apply(edit, *mImpl->field, mImpl->options.editBand);
    return mImpl->mark(changed);
}

EditResult World::dig(const EditShape& shape, double smoothRadius)
{
    return apply(Edit{shape, EditMode::DIG, smoothRadius});
}

EditResult World::fill(const EditShape& shape, double smoothRadius)
{
    return apply(Edit{shape, EditMode::FILL, smoothRadius});
}

void World::saveEdits(const std::filesystem::path& path) const
{
    mImpl->edits.save(path);
}

EditResult World::loadEdits(const std::filesystem::path& path)
{
    return mImpl->mark(mImpl->edits.load(path));
}

double World::density(const glm::dvec3& p) const
{
    return detail::latticeDensity(*mImpl->field, mImpl->edits, mImpl->options.voxelSize, p);
}

std::optional<RayHit> World::raycast(const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance) const
{
    return detail::raycast(*mImpl->field, mImpl->edits, mImpl->options.voxelSize, origin, direction, maxDistance);
}

bool World::isBoxSolid(const glm::dvec3& min, const glm::dvec3& max) const
{
    return detail::isBoxSolid(*mImpl->field, mImpl->edits, mImpl->options.voxelSize, min, max);
}

WorldStats World::stats() const
{
    WorldStats s;
    {
        std::lock_guard<std::mutex> lock(mImpl->mutex);
        s = mImpl->tracker.counters;
        s.resident = mImpl->tracker.chunks.size();
        s.inFlight = mImpl->scheduler.inFlight;
        s.retained = mImpl->tracker.retired.size();
        for (const auto& [key, chunk] : mImpl->tracker.ahead)
            if (chunk.mesh) {
                ++s.prefetchHeld;
                s.prefetchBytes += chunk.mesh->memoryBytes() + sizeof(ChunkMeshData);
            }
        for (const auto& [key, state] : mImpl->tracker.chunks) {
            if (state.dirty()) ++s.pending;
            if (mImpl->tracker.uncovered(key, state)) ++s.holes;
            if (state.cache) {
                // A task that holds the cache is filling it: count it next time.
                std::unique_lock<std::mutex> cacheLock(state.cache->mutex, std::try_to_lock);
                if (cacheLock) s.cacheBytes += state.cache->bytes();
            }
            if (state.mesh) {
                s.meshBytes += state.mesh->memoryBytes() + sizeof(ChunkMeshData);
                if (!state.mesh->mesh.indices.empty()) ++s.withSurface;
            }
        }
    }
    s.editVoxels = mImpl->edits.activeVoxels();
    s.editBytes = mImpl->edits.memoryBytes();
    return s;
}

std::shared_ptr<const ChunkMeshData> World::chunkMesh(const ChunkKey& key) const
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    const auto it = mImpl->tracker.chunks.find(key);
    return it == mImpl->tracker.chunks.end() ? nullptr : it->second.mesh;
}

std::vector<ChunkKey> World::residentChunks() const
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    std::vector<ChunkKey> keys;
    keys.reserve(mImpl->tracker.chunks.size());
    for (const auto& [key, state] : mImpl->tracker.chunks) keys.push_back(key);
    return keys;
}

void World::chunkBounds(const ChunkKey& key, glm::dvec3& min, glm::dvec3& max) const
{
    const double w = detail::chunkWidth(mImpl->lod, key.level);
    min = glm::dvec3(key.x, key.y, key.z) * w;
    max = min + w;
}

} // namespace strata::world
