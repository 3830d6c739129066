#include <strata/world/World.h>

#include "ChunkMesher.h"
#include "EditLayer.h"
#include "LodPartition.h"

#include <strata/Error.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <exception>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <thread>

namespace strata::world {

using detail::Signature;
using openvdb::Coord;
using openvdb::CoordBBox;

namespace {

struct ChunkState
{
    Signature signature{};
    double distance = 0.0;
    std::uint64_t generation = 0; ///< from Impl::generations: set on creation, bumped by edits and signature changes
    std::uint64_t meshedGeneration = 0;
    bool inFlight = false;
    bool delivered = false; ///< the caller holds a non-empty mesh for it
    bool withheld = false;  ///< `mesh` is newer than what the caller holds: it waits for a replacement group
    bool everMeshed = false;
    std::shared_ptr<const ChunkMeshData> mesh;
    std::shared_ptr<detail::SampleCache> cache; ///< null for levels without one

    bool dirty() const { return meshedGeneration != generation; }
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
};

std::uint64_t mix(std::uint64_t h)
{
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return h;
}

bool finite(const glm::dvec3& v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string num(double v)
{
    char buffer[64];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}

} // namespace

struct World::Impl
{
    std::shared_ptr<const terrain::DensityField> field;
    WorldOptions options;
    detail::LodParams lod;
    detail::MesherParams mesher;
    detail::EditLayer edits;
    /// TBB caps its workers at the core count − 1 unless told otherwise; the
    /// arena's `threads` workers need that many (plus the caller's slot).
    tbb::global_control parallelism;
    tbb::task_arena arena;

    mutable std::mutex mutex;
    std::condition_variable finishedSignal;
    std::condition_variable partitionSignal;
    /// The level-0 chunks holding the points of interest (the partition's
    /// input) and a version bumped when they change.
    std::vector<ChunkKey> interest;
    std::uint64_t interestVersion = 0;
    std::uint64_t appliedVersion = 0; ///< the version `chunks` follows
    /// A partition computed by the partition thread, not yet applied.
    std::optional<std::pair<std::uint64_t, std::map<ChunkKey, detail::PartitionEntry>>> partitionResult;
    std::thread partitionThread;
    std::map<ChunkKey, ChunkState> chunks;
    /// Chunks that left the resident set by a split or merge while the caller
    /// holds their meshes: kept until every chunk covering them is meshed.
    std::map<ChunkKey, ChunkState> retired;
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
    std::vector<Finished> finished;
    std::size_t inFlight = 0;
    std::uint64_t generations = 0; ///< a world-wide counter, so a chunk evicted and reloaded never reuses one
    bool stopping = false;
    std::exception_ptr failure;
    WorldStats counters;

    Impl(std::shared_ptr<const terrain::DensityField> f, const WorldOptions& o)
        : field(std::move(f))
        , options(o)
        , edits(o.voxelSize)
        , parallelism(tbb::global_control::max_allowed_parallelism,
                      std::max(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism),
                               std::size_t(o.threads) + 1))
        , arena(o.threads, 0)
    {
    }

    // --- with `mutex` held -------------------------------------------------

    /// Moves `chunks` to a new partition. Chunks the caller holds that leave
    /// it go to `retired` when the new partition still covers them (an LOD
    /// change), else they are reported removed at once (eviction).
    void rebuild(const std::map<ChunkKey, detail::PartitionEntry>& target)
    {
        releaseDue = true;
        // One merge walk over the two sorted maps: O(resident chunks).
        auto it = chunks.begin();
        auto t = target.begin();
        while (it != chunks.end() || t != target.end()) {
            if (t == target.end() || (it != chunks.end() && it->first < t->first)) {
                // Leaves the set.
                ++counters.evicted;
                withheldKeys.erase(it->first);
                if (it->second.delivered) {
                    ChunkState& state = retired[it->first];
                    state = std::move(it->second);
                    state.cache.reset();
                    state.withheld = false;
                }
                it = chunks.erase(it);
            } else if (it == chunks.end() || t->first < it->first) {
                // Joins the set.
                ChunkState state;
                if (const auto r = retired.find(t->first); r != retired.end()) {
                    // Back before it was replaced: the caller still holds its
                    // mesh. Edits may have passed it by: mesh it again.
                    state = std::move(r->second);
                    retired.erase(r);
                }
                state.signature = t->second.signature;
                state.distance = t->second.distance;
                state.generation = ++generations;
                if (t->first.level < options.sampleCacheLevels) state.cache = std::make_shared<detail::SampleCache>();
                chunks.emplace_hint(it, t->first, std::move(state));
                ++t;
            } else {
                ChunkState& state = it->second;
                state.distance = t->second.distance;
                if (state.signature != t->second.signature) {
                    state.signature = t->second.signature;
                    state.generation = ++generations;
                }
                ++it;
                ++t;
            }
        }
        groups.clear();
        groupOf.clear();
        for (auto it = retired.begin(); it != retired.end();) {
            const std::vector<ChunkKey> c = cover(it->first);
            if (c.empty()) { // left the view: evicted at once
                push(ChunkUpdate{it->first, nullptr});
                it = retired.erase(it);
                continue;
            }
            const ChunkKey g = c.front().level > it->first.level ? c.front() : it->first;
            Group& group = groups[g];
            group.retired.push_back(it->first);
            if (group.covers.empty())
                for (const ChunkKey& k : c) {
                    group.covers.emplace_back(k, &chunks.at(k));
                    groupOf[k] = g;
                }
            ++it;
        }
        // Withheld meshes that no longer replace anything go out alone.
        for (auto it = withheldKeys.begin(); it != withheldKeys.end();) {
            if (groupOf.count(*it)) {
                ++it;
                continue;
            }
            ChunkState& state = chunks.at(*it);
            state.withheld = false;
            if (!state.mesh->mesh.indices.empty()) {
                push(ChunkUpdate{*it, state.mesh});
                state.delivered = true;
            }
            it = withheldKeys.erase(it);
        }
    }

    void push(ChunkUpdate update) { updates.push_back(QueuedUpdate{std::move(update), 1}); }

    /// The resident chunks covering a retired chunk's box: its resident
    /// ancestor, or the resident descendants that tile it; empty when the
    /// resident set does not cover it (its top-level chunk was evicted).
    std::vector<ChunkKey> cover(const ChunkKey& key) const
    {
        std::vector<ChunkKey> out;
        for (int level = key.level + 1; level < options.levels; ++level) {
            const int shift = level - key.level;
            const ChunkKey up{level, key.x >> shift, key.y >> shift, key.z >> shift};
            if (chunks.count(up)) {
                out.push_back(up);
                return out;
            }
        }
        if (!tile(key, out)) out.clear();
        return out;
    }

    bool tile(const ChunkKey& key, std::vector<ChunkKey>& out) const
    {
        if (key.level == 0) return false;
        for (int c = 0; c < 8; ++c) {
            const ChunkKey child{key.level - 1, 2 * key.x + (c & 1), 2 * key.y + ((c >> 1) & 1),
                                 2 * key.z + ((c >> 2) & 1)};
            if (chunks.count(child)) out.push_back(child);
            else if (!tile(child, out)) return false;
        }
        return true;
    }

    /// Hands out every group whose covering chunks are all meshed: their
    /// withheld meshes, then the removals of the retired chunks, as one group
    /// of updates. O(groups · covering chunks).
    void release()
    {
        if (!releaseDue) return;
        releaseDue = false;
        for (auto g = groups.begin(); g != groups.end();) {
            bool ready = true;
            for (const auto& [key, state] : g->second.covers) ready = ready && state->mesh != nullptr;
            if (!ready) {
                ++g;
                continue;
            }
            std::vector<ChunkUpdate> group;
            for (const auto& [key, state] : g->second.covers) {
                groupOf.erase(key);
                if (!state->withheld) continue;
                state->withheld = false;
                withheldKeys.erase(key);
                if (!state->mesh->mesh.indices.empty()) {
                    group.push_back(ChunkUpdate{key, state->mesh});
                    state->delivered = true;
                }
            }
            for (const ChunkKey& key : g->second.retired) {
                group.push_back(ChunkUpdate{key, nullptr});
                retired.erase(key);
            }
            for (std::size_t i = 0; i < group.size(); ++i)
                updates.push_back(QueuedUpdate{std::move(group[i]), i == 0 ? group.size() : 0});
            g = groups.erase(g);
        }
    }

    void accept(Finished& f)
    {
        const auto it = chunks.find(f.key);
        if (it == chunks.end()) {
            if (const auto r = retired.find(f.key); r != retired.end()) r->second.inFlight = false;
            ++counters.discarded;
            return;
        }
        ChunkState& state = it->second;
        state.inFlight = false;
        if (state.signature != f.signature || f.generation <= state.meshedGeneration) {
            ++counters.discarded;
            return;
        }
        // A mesh from an older generation is still the newest one: deliver it
        // (the chunk stays dirty and is meshed again).
        state.meshedGeneration = f.generation;
        if (state.everMeshed) ++counters.remeshed;
        else ++counters.generated;
        state.everMeshed = true;
        state.mesh = std::move(f.mesh);
        if (state.withheld || groupOf.count(f.key)) {
            // Part of a replacement after an LOD change: release() hands it out.
            state.withheld = true;
            withheldKeys.insert(f.key);
            releaseDue = true;
        } else if (!state.mesh->mesh.indices.empty()) {
            push(ChunkUpdate{f.key, state.mesh});
            state.delivered = true;
        } else if (state.delivered) {
            push(ChunkUpdate{f.key, nullptr});
            state.delivered = false;
        }
    }

    void schedule()
    {
        const std::size_t cap = std::size_t(options.maxInFlight);
        if (inFlight >= cap) return;
        std::vector<std::pair<std::pair<double, ChunkKey>, ChunkState*>> candidates;
        for (auto& [key, state] : chunks) {
            if (state.inFlight || !state.dirty()) continue;
            double order = state.distance;
            if (options.taskOrderSeed != 0) {
                const std::uint64_t h = mix(options.taskOrderSeed ^ mix(std::uint64_t(key.level) * 0x9e3779b97f4a7c15ull ^
                                                                    mix(std::uint64_t(std::uint32_t(key.x)) << 32 ^
                                                                        std::uint64_t(std::uint32_t(key.y))) ^
                                                                    std::uint64_t(std::uint32_t(key.z))));
                order = double(h >> 11);
            }
            candidates.push_back({{order, key}, &state});
        }
        const std::size_t count = std::min(candidates.size(), cap - inFlight);
        std::partial_sort(candidates.begin(), candidates.begin() + std::ptrdiff_t(count), candidates.end(),
                          [](const auto& a, const auto& b) { return a.first < b.first; });
        for (std::size_t i = 0; i < count; ++i) {
            ChunkState& state = *candidates[i].second;
            state.inFlight = true;
            ++inFlight;
            launch(candidates[i].first.second, state.signature, state.generation, state.cache);
        }
    }

    /// What a chunk task needs, on the heap: the task object itself holds
    /// only this pointer, so nothing of ours lives in TBB's recycled task
    /// memory (whose reuse ThreadSanitizer cannot order).
    struct Job
    {
        Impl* impl;
        ChunkKey key;
        Signature signature;
        std::uint64_t generation;
        std::shared_ptr<detail::SampleCache> cache;
    };

    /// Taken around enqueue and first thing in each task: orders the job
    /// pointer's hand-over in a way ThreadSanitizer sees.
    static std::mutex& handOver()
    {
        static std::mutex m;
        return m;
    }

    void launch(const ChunkKey& key, const Signature& signature, std::uint64_t generation,
                std::shared_ptr<detail::SampleCache> cache)
    {
        Job* job = new Job{this, key, signature, generation, std::move(cache)};
        std::lock_guard<std::mutex> fence(handOver());
        arena.enqueue([job] {
            Job* mine;
            {
                std::lock_guard<std::mutex> fence(handOver());
                mine = job;
            }
            std::unique_ptr<Job> owned(mine);
            owned->impl->runTask(*owned);
        });
    }

    void runTask(Job& job)
    {
        Finished result{job.key, job.signature, job.generation, nullptr};
        std::exception_ptr error;
        bool stop;
        {
            std::lock_guard<std::mutex> lock(mutex);
            stop = stopping;
        }
        if (!stop) {
            try {
                const std::unique_ptr<detail::EditSnapshot> snapshot =
                    edits.snapshot(detail::editFootprint(mesher, job.key));
                std::unique_lock<std::mutex> cacheLock;
                if (job.cache) cacheLock = std::unique_lock<std::mutex>(job.cache->mutex);
                result.mesh = std::make_shared<ChunkMeshData>(
                    detail::meshChunk(*field, mesher, job.key, job.signature, *snapshot, job.cache.get()));
            } catch (...) {
                error = std::current_exception();
            }
        }
        job.cache.reset(); // before the world may be destroyed
        std::lock_guard<std::mutex> lock(mutex);
        if (result.mesh) finished.push_back(std::move(result));
        else if (auto it = chunks.find(job.key); it != chunks.end()) it->second.inFlight = false;
        else if (auto r = retired.find(job.key); r != retired.end()) r->second.inFlight = false;
        if (error && !failure) failure = error;
        --inFlight;
        finishedSignal.notify_all();
    }

    void pump()
    {
        if (failure) {
            std::exception_ptr e = failure;
            failure = nullptr;
            std::rethrow_exception(e);
        }
        if (partitionResult) {
            rebuild(partitionResult->second);
            appliedVersion = partitionResult->first;
            partitionResult.reset();
        }
        for (Finished& f : finished) accept(f);
        finished.clear();
        release();
        schedule();
    }

    /// The partition thread: computes the resident set for each new version
    /// of `interest` off the callers' threads; pump() applies it.
    void partitionLoop()
    {
        std::unique_lock<std::mutex> lock(mutex);
        std::uint64_t computed = 0;
        for (;;) {
            partitionSignal.wait(lock, [&] { return stopping || interestVersion != computed; });
            if (stopping) return;
            const std::uint64_t version = interestVersion;
            const std::vector<ChunkKey> input = interest;
            lock.unlock();
            std::map<ChunkKey, detail::PartitionEntry> target;
            std::exception_ptr error;
            try {
                target = detail::computePartition(input, lod);
            } catch (...) {
                error = std::current_exception();
            }
            lock.lock();
            computed = version;
            if (error) {
                if (!failure) failure = error;
            } else {
                partitionResult.emplace(version, std::move(target));
            }
            finishedSignal.notify_all();
        }
    }

    /// Has `chunks` caught up with the latest points of interest?
    bool partitionCurrent() const { return appliedVersion == interestVersion && !partitionResult; }

    bool anyDirty() const
    {
        for (const auto& [key, state] : chunks)
            if (state.dirty()) return true;
        return false;
    }

    EditResult mark(const std::vector<Coord>& changed)
    {
        EditResult result;
        result.changedVoxels = changed.size();
        if (changed.empty()) return result;
        Coord lo = changed.front(), hi = changed.front();
        for (const Coord& c : changed) {
            lo.minComponent(c);
            hi.maxComponent(c);
        }
        std::lock_guard<std::mutex> lock(mutex);
        for (auto& [key, state] : chunks) {
            const std::int64_t s = std::int64_t(1) << key.level;
            const std::int64_t w = std::int64_t(options.chunkSize) * s;
            const std::int64_t m[3] = {key.x * w, key.y * w, key.z * w};
            bool overlaps = true;
            for (int a = 0; a < 3; ++a) overlaps = overlaps && lo[a] <= m[a] + w && hi[a] >= m[a] - 2 * s;
            if (!overlaps) continue;
            bool finer = false;
            for (int i = 1; i < 8; ++i) finer = finer || state.signature[i] < 0;
            const std::int64_t step = (finer && key.level > 0) ? s / 2 : s;
            bool hit = false;
            for (const Coord& c : changed) {
                bool in = true;
                for (int a = 0; a < 3 && in; ++a)
                    in = c[a] >= m[a] - 2 * s && c[a] <= m[a] + w && (std::int64_t(c[a]) & (step - 1)) == 0;
                if (in) {
                    hit = true;
                    break;
                }
            }
            if (!hit) continue;
            state.generation = ++generations;
            result.markedChunks.push_back(key);
        }
        return result;
    }

    // --- queries (no `mutex`) ----------------------------------------------

    double density(const glm::dvec3& p) const
    {
        const double v = options.voxelSize;
        const glm::dvec3 x = p / v;
        const glm::dvec3 f = glm::floor(x);
        const glm::dvec3 t = x - f;
        Coord corners[8];
        for (int i = 0; i < 8; ++i)
            corners[i] = Coord(int(f.x) + (i & 1), int(f.y) + ((i >> 1) & 1), int(f.z) + ((i >> 2) & 1));
        float values[8];
        edits.samples(*field, corners, 8, values);
        double result = 0.0;
        for (int i = 0; i < 8; ++i) {
            const double w = ((i & 1) ? t.x : 1.0 - t.x) * (((i >> 1) & 1) ? t.y : 1.0 - t.y) *
                             (((i >> 2) & 1) ? t.z : 1.0 - t.z);
            result += w * double(values[i]);
        }
        return result;
    }
};

World::World(std::shared_ptr<const terrain::DensityField> field, const WorldOptions& options)
{
    if (!field) throw Error("World: the density field is null");
    WorldOptions o = options;
    if (!std::isfinite(o.voxelSize) || o.voxelSize <= 0.0)
        throw Error("WorldOptions: voxelSize = " + num(o.voxelSize) + " must be finite and > 0");
    if (o.chunkSize < 8 || o.chunkSize > 128 || (o.chunkSize & (o.chunkSize - 1)) != 0)
        throw Error("WorldOptions: chunkSize = " + std::to_string(o.chunkSize) + " must be a power of two in [8, 128]");
    if (o.levels < 1 || o.levels > 8)
        throw Error("WorldOptions: levels = " + std::to_string(o.levels) + " must be in [1, 8]");
    const double w0 = o.chunkSize * o.voxelSize;
    if (o.lodDistance == 0.0) o.lodDistance = 4.0 * w0;
    const double minLod = 2.0 * std::sqrt(3.0) * w0;
    if (!std::isfinite(o.lodDistance) || (o.levels > 1 && o.lodDistance < minLod) || o.lodDistance < 0.0)
        throw Error("WorldOptions: lodDistance = " + num(o.lodDistance) + " must be at least 2·sqrt(3) chunk widths (" +
                    num(minLod) + " m)");
    if (o.viewRadius == 0.0) o.viewRadius = 3.0 * w0 * double(1 << (o.levels - 1));
    if (!std::isfinite(o.viewRadius) || o.viewRadius <= 0.0)
        throw Error("WorldOptions: viewRadius = " + num(o.viewRadius) + " must be finite and > 0");
    if (o.threads < 0) throw Error("WorldOptions: threads = " + std::to_string(o.threads) + " must be >= 0");
    if (o.threads == 0) o.threads = int(std::max(1u, std::thread::hardware_concurrency()));
    if (o.editBand < 1 || o.editBand > 16)
        throw Error("WorldOptions: editBand = " + std::to_string(o.editBand) + " must be in [1, 16]");
    if (o.sampleCacheLevels < 0 || o.sampleCacheLevels > o.levels)
        throw Error("WorldOptions: sampleCacheLevels = " + std::to_string(o.sampleCacheLevels) + " must be in [0, levels]");
    if (o.maxInFlight < 0) throw Error("WorldOptions: maxInFlight = " + std::to_string(o.maxInFlight) + " must be >= 0");
    if (o.maxInFlight == 0) o.maxInFlight = 2 * o.threads + 2;
    openvdb::initialize();
    mImpl = std::make_unique<Impl>(std::move(field), o);
    mImpl->lod = detail::LodParams{o.voxelSize, o.chunkSize, o.levels, o.lodDistance, o.viewRadius};
    mImpl->mesher = detail::MesherParams{o.voxelSize, o.chunkSize};
    mImpl->partitionThread = std::thread([impl = mImpl.get()] { impl->partitionLoop(); });
}

World::~World()
{
    {
        std::lock_guard<std::mutex> lock(mImpl->mutex);
        mImpl->stopping = true;
        mImpl->partitionSignal.notify_all();
    }
    mImpl->partitionThread.join();
    std::unique_lock<std::mutex> lock(mImpl->mutex);
    mImpl->finishedSignal.wait(lock, [&] { return mImpl->inFlight == 0; });
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
        if (!finite(p)) throw Error("World: point of interest (" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) +
                                    ") is not finite");
        if (std::abs(p.x) > limit || std::abs(p.y) > limit || std::abs(p.z) > limit)
            throw Error("World: point of interest (" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) +
                        ") is farther than " + num(limit) + " m from the origin");
    }
    std::vector<ChunkKey> interest = detail::interestChunks(points, mImpl->lod);
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    if (interest == mImpl->interest) return; // the same level-0 chunks: the same partition
    mImpl->interest = std::move(interest);
    ++mImpl->interestVersion;
    mImpl->partitionSignal.notify_all();
}

std::vector<ChunkUpdate> World::poll(std::size_t maxUpdates)
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    mImpl->pump();
    std::vector<ChunkUpdate> out;
    std::deque<QueuedUpdate>& queue = mImpl->updates;
    while (!queue.empty() && maxUpdates > 0) {
        const std::size_t group = queue.front().groupSize;
        if (!out.empty() && out.size() + group > maxUpdates) break;
        for (std::size_t i = 0; i < group; ++i) {
            out.push_back(std::move(queue.front().update));
            queue.pop_front();
        }
    }
    return out;
}

bool World::idle() const
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    return mImpl->partitionCurrent() && mImpl->inFlight == 0 && mImpl->finished.empty() && mImpl->retired.empty() &&
           mImpl->withheldKeys.empty() && !mImpl->anyDirty();
}

void World::waitIdle()
{
    std::unique_lock<std::mutex> lock(mImpl->mutex);
    for (;;) {
        mImpl->pump();
        const bool partitionDone = mImpl->partitionCurrent();
        if (partitionDone && mImpl->inFlight == 0 && !mImpl->anyDirty()) return;
        mImpl->finishedSignal.wait(lock, [&] {
            return !mImpl->finished.empty() || mImpl->failure || mImpl->partitionResult ||
                   (mImpl->inFlight == 0 && partitionDone);
        });
    }
}

EditResult World::apply(const Edit& edit)
{
    edit.shape.validate();
    if (!std::isfinite(edit.smoothRadius) || edit.smoothRadius < 0.0)
        throw Error("edit: smoothRadius = " + num(edit.smoothRadius) + " must be finite and >= 0");
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
    return mImpl->density(p);
}

std::optional<RayHit> World::raycast(const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance) const
{
    if (!finite(origin) || !finite(direction) || glm::length(direction) == 0.0 || !std::isfinite(maxDistance) ||
        maxDistance < 0.0)
        throw Error("World::raycast: origin and direction must be finite, direction not zero, maxDistance >= 0 (got " +
                    num(maxDistance) + ")");
    const glm::dvec3 d = glm::normalize(direction);
    const double v = mImpl->options.voxelSize;
    const double minStep = 0.25 * v;
    const double slope = std::sqrt(3.0) * std::max(1.0, mImpl->field->lipschitz());
    auto at = [&](double t) { return mImpl->density(origin + t * d); };

    double t0 = 0.0;
    double f0 = at(0.0);
    double hitT = -1.0;
    if (f0 < 0.0) {
        hitT = 0.0;
    } else {
        while (t0 < maxDistance) {
            double step = std::max(minStep, f0 / slope);
            if (step > minStep) {
                // Stored edits are not bounded by the field's slope: step
                // finely wherever an edit lies within the step.
                const glm::dvec3 p = origin + t0 * d;
                const glm::dvec3 lo = glm::floor((p - step) / v), hi = glm::ceil((p + step) / v);
                if (mImpl->edits.anyIn(CoordBBox(Coord(int(lo.x), int(lo.y), int(lo.z)),
                                                 Coord(int(hi.x), int(hi.y), int(hi.z)))))
                    step = minStep;
            }
            const double t1 = std::min(maxDistance, t0 + step);
            const double f1 = at(t1);
            if (f1 < 0.0) {
                double a = t0, b = t1;
                for (int i = 0; i < 60 && b - a > 1e-9; ++i) {
                    const double m = 0.5 * (a + b);
                    if (at(m) < 0.0) b = m;
                    else a = m;
                }
                hitT = 0.5 * (a + b);
                break;
            }
            if (t1 >= maxDistance) break;
            t0 = t1;
            f0 = f1;
        }
    }
    if (hitT < 0.0) return std::nullopt;
    RayHit hit;
    hit.distance = hitT;
    hit.position = origin + hitT * d;
    const double h = 0.5 * v;
    glm::dvec3 g(mImpl->density(hit.position + glm::dvec3(h, 0, 0)) - mImpl->density(hit.position - glm::dvec3(h, 0, 0)),
                 mImpl->density(hit.position + glm::dvec3(0, h, 0)) - mImpl->density(hit.position - glm::dvec3(0, h, 0)),
                 mImpl->density(hit.position + glm::dvec3(0, 0, h)) - mImpl->density(hit.position - glm::dvec3(0, 0, h)));
    hit.normal = glm::length(g) > 0.0 ? glm::normalize(g) : -d;
    return hit;
}

bool World::isBoxSolid(const glm::dvec3& min, const glm::dvec3& max) const
{
    if (!finite(min) || !finite(max) || min.x > max.x || min.y > max.y || min.z > max.z)
        throw Error("World::isBoxSolid: the box must be finite with min <= max");
    const double v = mImpl->options.voxelSize;
    const glm::dvec3 lo = glm::floor(min / v), hi = glm::floor(max / v) + 1.0;
    const Coord clo(int(lo.x), int(lo.y), int(lo.z)), chi(int(hi.x), int(hi.y), int(hi.z));
    const int B = 8;
    std::vector<Coord> points;
    std::vector<float> values;
    for (int bz = clo.z() & ~(B - 1); bz <= chi.z(); bz += B) {
        for (int by = clo.y() & ~(B - 1); by <= chi.y(); by += B) {
            for (int bx = clo.x() & ~(B - 1); bx <= chi.x(); bx += B) {
                const Coord b0(std::max(bx, clo.x()), std::max(by, clo.y()), std::max(bz, clo.z()));
                const Coord b1(std::min(bx + B - 1, chi.x()), std::min(by + B - 1, chi.y()), std::min(bz + B - 1, chi.z()));
                const CoordBBox box(b0, b1);
                if (!mImpl->edits.anyIn(box)) {
                    const glm::dvec3 c0(b0.x(), b0.y(), b0.z()), c1(b1.x(), b1.y(), b1.z());
                    const double bound = mImpl->field->distanceBound(0.5 * (c0 + c1) * v);
                    const double radius = 0.5 * glm::length(c1 - c0) * v;
                    if (bound < -radius) continue;     // all rock
                    if (bound > radius) return false; // all air
                }
                points.clear();
                for (auto c = box.begin(); c; ++c) points.push_back(*c);
                values.resize(points.size());
                mImpl->edits.samples(*mImpl->field, points.data(), int(points.size()), values.data());
                for (float value : values)
                    if (!(value < 0.0f)) return false;
            }
        }
    }
    return true;
}

WorldStats World::stats() const
{
    WorldStats s;
    {
        std::lock_guard<std::mutex> lock(mImpl->mutex);
        s = mImpl->counters;
        s.resident = mImpl->chunks.size();
        s.inFlight = mImpl->inFlight;
        s.retained = mImpl->retired.size();
        for (const auto& [key, state] : mImpl->chunks) {
            if (state.dirty()) ++s.pending;
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
    const auto it = mImpl->chunks.find(key);
    return it == mImpl->chunks.end() ? nullptr : it->second.mesh;
}

std::vector<ChunkKey> World::residentChunks() const
{
    std::lock_guard<std::mutex> lock(mImpl->mutex);
    std::vector<ChunkKey> keys;
    keys.reserve(mImpl->chunks.size());
    for (const auto& [key, state] : mImpl->chunks) keys.push_back(key);
    return keys;
}

void World::chunkBounds(const ChunkKey& key, glm::dvec3& min, glm::dvec3& max) const
{
    const double w = detail::chunkWidth(mImpl->lod, key.level);
    min = glm::dvec3(key.x, key.y, key.z) * w;
    max = min + w;
}

} // namespace strata::world
