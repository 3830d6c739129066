// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ReplacementTracker.h"

namespace strata::world::detail {

void ReplacementTracker::rebuild(const std::map<ChunkKey, PartitionEntry>& target)
{
    releaseDue = true;
    std::vector<ChunkKey> changed; // joined, or a new signature: meshed ahead, perhaps
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
            if (t->first.level < mSampleCacheLevels) {
                // The look-ahead task's samples, when it made some.
                const auto a = ahead.find(t->first);
                state.cache = a != ahead.end() && a->second.cache ? a->second.cache : std::make_shared<SampleCache>();
            }
            chunks.emplace_hint(it, t->first, std::move(state));
            changed.push_back(t->first);
            ++t;
        } else {
            ChunkState& state = it->second;
            state.distance = t->second.distance;
            if (state.signature != t->second.signature) {
                state.signature = t->second.signature;
                state.generation = ++generations;
                changed.push_back(t->first);
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
    // The chunks meshed ahead for this partition take their meshes now.
    for (const ChunkKey& key : changed) {
        const auto a = ahead.find(key);
        if (a == ahead.end() || !a->second.mesh) continue;
        ChunkState& state = chunks.at(key);
        if (a->second.signature != state.signature) continue; // (the chunk already shares its cache)
        ++counters.prefetched;
        install(key, state, state.generation, std::move(a->second.mesh));
        ahead.erase(a);
    }
}

void ReplacementTracker::setLookAhead(const std::map<ChunkKey, PartitionEntry>& next)
{
    for (auto& [key, a] : ahead) a.wanted = false;
    for (const auto& [key, entry] : next) {
        const auto c = chunks.find(key);
        if (c != chunks.end() && c->second.signature == entry.signature) continue; // resident as it will be
        auto [a, added] = ahead.try_emplace(key);
        AheadChunk& chunk = a->second;
        if (added) {
            chunk.signature = entry.signature;
            if (key.level < mSampleCacheLevels)
                chunk.cache = c != chunks.end() && c->second.cache ? c->second.cache : std::make_shared<SampleCache>();
        } else if (chunk.signature != entry.signature) {
            chunk.signature = entry.signature; // a task in flight for the old one is dropped when it ends
            chunk.mesh.reset();
        }
        chunk.distance = entry.distance;
        chunk.wanted = true;
    }
    for (auto a = ahead.begin(); a != ahead.end();) {
        if (a->second.wanted || a->second.inFlight) {
            ++a;
            continue;
        }
        if (a->second.mesh) ++counters.prefetchDropped;
        a = ahead.erase(a);
    }
}

bool ReplacementTracker::aheadCovers(const ChunkKey& key, const ChunkState& state) const
{
    const auto a = ahead.find(key);
    return a != ahead.end() && a->second.inFlight && !a->second.stale && a->second.signature == state.signature;
}


std::vector<ChunkKey> ReplacementTracker::cover(const ChunkKey& key) const
{
    std::vector<ChunkKey> out;
    for (int level = key.level + 1; level < mLevels; ++level) {
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

bool ReplacementTracker::tile(const ChunkKey& key, std::vector<ChunkKey>& out) const
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

void ReplacementTracker::release()
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

void ReplacementTracker::accept(Finished& f)
{
    if (f.ahead) {
        acceptAhead(f);
        return;
    }
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
    install(f.key, state, f.generation, std::move(f.mesh));
}

void ReplacementTracker::acceptAhead(Finished& f)
{
    const auto a = ahead.find(f.key);
    if (a == ahead.end()) { // cannot happen: entries in flight are kept
        ++counters.prefetchDropped;
        return;
    }
    AheadChunk& chunk = a->second;
    const bool valid = !chunk.stale && chunk.signature == f.signature;
    chunk.inFlight = false;
    chunk.stale = false;
    if (!valid) {
        ++counters.prefetchDropped;
        if (!chunk.wanted) ahead.erase(a);
        return;
    }
    // Resident meanwhile with this signature (its partition came first):
    // it is the chunk's current mesh unless the chunk has one already.
    if (const auto c = chunks.find(f.key); c != chunks.end() && c->second.signature == f.signature) {
        if (c->second.dirty()) {
            ++counters.prefetched;
            install(f.key, c->second, c->second.generation, std::move(f.mesh));
        } else {
            ++counters.prefetchDropped;
        }
        ahead.erase(a);
        return;
    }
    if (!chunk.wanted) {
        ++counters.prefetchDropped;
        ahead.erase(a);
        return;
    }
    chunk.mesh = std::move(f.mesh);
}

void ReplacementTracker::install(const ChunkKey& key, ChunkState& state, std::uint64_t generation,
                                 std::shared_ptr<const ChunkMeshData> mesh)
{
    state.meshedGeneration = generation;
    if (state.everMeshed) ++counters.remeshed;
    else ++counters.generated;
    state.everMeshed = true;
    state.mesh = std::move(mesh);
    if (state.withheld || groupOf.count(key)) {
        // Part of a replacement after an LOD change: release() hands it out.
        state.withheld = true;
        withheldKeys.insert(key);
        releaseDue = true;
    } else if (!state.mesh->mesh.indices.empty()) {
        push(ChunkUpdate{key, state.mesh});
        state.delivered = true;
    } else if (state.delivered) {
        push(ChunkUpdate{key, nullptr});
        state.delivered = false;
    }
}

void ReplacementTracker::abandoned(const ChunkKey& key, bool isAhead)
{
    if (isAhead) {
        if (auto a = ahead.find(key); a != ahead.end()) {
            a->second.inFlight = false;
            a->second.stale = false;
            if (!a->second.wanted) ahead.erase(a);
        }
    } else if (auto it = chunks.find(key); it != chunks.end()) {
        it->second.inFlight = false;
    } else if (auto r = retired.find(key); r != retired.end()) {
        r->second.inFlight = false;
    }
}

namespace {

/// Does the chunk's sample footprint (see World.h) hold a changed sample?
/// `lo`..`hi` bound `changed`.
bool footprintHolds(const ChunkKey& key, const Signature& signature, const std::vector<openvdb::Coord>& changed,
                    const openvdb::Coord& lo, const openvdb::Coord& hi, int chunkSize)
{
    const std::int64_t s = std::int64_t(1) << key.level;
    const std::int64_t w = std::int64_t(chunkSize) * s;
    const std::int64_t m[3] = {key.x * w, key.y * w, key.z * w};
    bool overlaps = true;
    for (int a = 0; a < 3; ++a) overlaps = overlaps && lo[a] <= m[a] + w && hi[a] >= m[a] - 2 * s;
    if (!overlaps) return false;
    bool finer = false;
    for (int i = 1; i < 8; ++i) finer = finer || signature[i] < 0;
    const std::int64_t step = (finer && key.level > 0) ? s / 2 : s;
    for (const openvdb::Coord& c : changed) {
        bool in = true;
        for (int a = 0; a < 3 && in; ++a)
            in = c[a] >= m[a] - 2 * s && c[a] <= m[a] + w && (std::int64_t(c[a]) & (step - 1)) == 0;
        if (in) return true;
    }
    return false;
}

} // namespace

EditResult ReplacementTracker::mark(const std::vector<openvdb::Coord>& changed, int chunkSize)
{
    EditResult result;
    result.changedVoxels = changed.size();
    if (changed.empty()) return result;
    openvdb::Coord lo = changed.front(), hi = changed.front();
    for (const openvdb::Coord& c : changed) {
        lo.minComponent(c);
        hi.maxComponent(c);
    }
    for (auto& [key, state] : chunks) {
        if (!footprintHolds(key, state.signature, changed, lo, hi, chunkSize)) continue;
        state.generation = ++generations;
        result.markedChunks.push_back(key);
    }
    // Meshes made ahead from the old samples are dropped, and so are the
    // results of tasks that may have read them.
    for (auto& [key, a] : ahead) {
        if (!footprintHolds(key, a.signature, changed, lo, hi, chunkSize)) continue;
        if (a.mesh) ++counters.prefetchDropped;
        a.mesh.reset();
        a.stale = a.inFlight;
    }
    return result;
}

std::vector<ChunkUpdate> ReplacementTracker::poll(std::size_t maxUpdates)
{
    std::vector<ChunkUpdate> out;
    while (!updates.empty() && maxUpdates > 0) {
        const std::size_t group = updates.front().groupSize;
        if (!out.empty() && out.size() + group > maxUpdates) break;
        for (std::size_t i = 0; i < group; ++i) {
            out.push_back(std::move(updates.front().update));
            updates.pop_front();
        }
    }
    return out;
}

bool ReplacementTracker::anyDirty() const
{
    for (const auto& [key, state] : chunks)
        if (state.dirty()) return true;
    return false;
}

} // namespace strata::world::detail
