// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The one cache facility of Strata: immutable values by key, shared
/// (std::shared_ptr<const Value>, so a dropped value lives on for whoever
/// holds it), least recently used dropped first, bounded in bytes twice:
/// by the cache's own budget and by the process-wide limit of CacheMemory.h
/// (--max-memory), which every cache charges. Thread-safe (one mutex: a
/// lookup is short next to computing a value; hot callers keep a per-thread
/// copy of their last few values, or shard, see Sharded below).
///
/// The caller says what a value weighs when it inserts it (its heap bytes:
/// the capacity of its vectors, not sizeof).

#include <strata/CacheMemory.h>

#include <cstddef>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

namespace strata {

template <class Key, class Value>
class ByteBoundedCache
{
public:
    using Pointer = std::shared_ptr<const Value>;

    /// Holds at most `budgetBytes` (and less while the process is over its
    /// limit), but always its `minEntries` most recent values (those one
    /// query may need together; 0: a value over the budget is not kept).
    explicit ByteBoundedCache(std::uint64_t budgetBytes, std::size_t minEntries = 1)
        : mBudget(budgetBytes), mMinEntries(minEntries)
    {
    }
    ~ByteBoundedCache() { detail::chargeCacheMemory(-std::int64_t(mBytes)); }
    ByteBoundedCache(const ByteBoundedCache&) = delete;
    ByteBoundedCache& operator=(const ByteBoundedCache&) = delete;

    /// The value of `key`, now the most recently used; null when not held.
    Pointer find(const Key& key)
    {
        std::lock_guard<std::mutex> lock(mMutex);
        const auto found = mIndex.find(key);
        if (found == mIndex.end()) {
            ++mMisses;
            return nullptr;
        }
        ++mHits;
        mOrder.splice(mOrder.begin(), mOrder, found->second);
        return found->second->value;
    }

    /// Keeps `value` (weighing `bytes`) for `key` and drops the least
    /// recently used values while over a bound. Returns the value held for
    /// `key`: the one another thread inserted first, or `value`.
    Pointer insert(const Key& key, Pointer value, std::uint64_t bytes)
    {
        std::lock_guard<std::mutex> lock(mMutex);
        if (const auto found = mIndex.find(key); found != mIndex.end()) {
            mOrder.splice(mOrder.begin(), mOrder, found->second);
            return found->second->value;
        }
        if (mMinEntries == 0 && bytes > mBudget) return value;
        mOrder.push_front(Entry{key, value, bytes});
        mIndex.emplace(key, mOrder.begin());
        mBytes += bytes;
        detail::chargeCacheMemory(std::int64_t(bytes));
        while (mOrder.size() > mMinEntries && (mBytes > mBudget || cacheMemoryUsed() > cacheMemoryLimit())) {
            const Entry& oldest = mOrder.back();
            mBytes -= oldest.bytes;
            detail::chargeCacheMemory(-std::int64_t(oldest.bytes));
            mIndex.erase(oldest.key);
            mOrder.pop_back();
        }
        return value;
    }

    /// Drops every value.
    void clear()
    {
        std::lock_guard<std::mutex> lock(mMutex);
        detail::chargeCacheMemory(-std::int64_t(mBytes));
        mIndex.clear();
        mOrder.clear();
        mBytes = 0;
    }

    struct Stats
    {
        std::uint64_t bytes = 0;   ///< held now
        std::size_t entries = 0;   ///< held now
        std::uint64_t hits = 0, misses = 0;
    };
    Stats stats() const
    {
        std::lock_guard<std::mutex> lock(mMutex);
        return {mBytes, mOrder.size(), mHits, mMisses};
    }

private:
    struct Entry
    {
        Key key;
        Pointer value;
        std::uint64_t bytes;
    };
    using Order = std::list<Entry>; ///< most recently used first

    const std::uint64_t mBudget;
    const std::size_t mMinEntries;
    mutable std::mutex mMutex;
    Order mOrder;
    std::map<Key, typename Order::iterator> mIndex;
    std::uint64_t mBytes = 0, mHits = 0, mMisses = 0;
};

/// SHARDS caches of budget / SHARDS each, a key's shard chosen by `shardOf`
/// (a hash): for values many threads ask for at once.
template <class Key, class Value, std::size_t SHARDS, class ShardOf>
class ShardedByteBoundedCache
{
public:
    explicit ShardedByteBoundedCache(std::uint64_t budgetBytes, std::size_t minEntriesPerShard = 1)
    {
        for (auto& shard : mShards) shard = std::make_unique<ByteBoundedCache<Key, Value>>(budgetBytes / SHARDS, minEntriesPerShard);
    }
    std::shared_ptr<const Value> find(const Key& key) { return shard(key).find(key); }
    std::shared_ptr<const Value> insert(const Key& key, std::shared_ptr<const Value> value, std::uint64_t bytes)
    {
        return shard(key).insert(key, std::move(value), bytes);
    }
    typename ByteBoundedCache<Key, Value>::Stats stats() const
    {
        typename ByteBoundedCache<Key, Value>::Stats all;
        for (const auto& shard : mShards) {
            const auto s = shard->stats();
            all.bytes += s.bytes;
            all.entries += s.entries;
            all.hits += s.hits;
            all.misses += s.misses;
        }
        return all;
    }

private:
    ByteBoundedCache<Key, Value>& shard(const Key& key) { return *mShards[ShardOf{}(key) % SHARDS]; }
    std::unique_ptr<ByteBoundedCache<Key, Value>> mShards[SHARDS];
};

} // namespace strata
