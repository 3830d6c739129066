// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The gzipped bodies the file server made, kept for the next request of the
// same version of the same file: a viewer's reload, or a second browser, asks
// again for the same tileset.json and script, and gzipping them again costs
// a read of the file and 17 ms a MB. Bounded in bytes (least recently used
// dropped first), thread-safe (one mutex: a lookup is short next to a
// request). Header-only: the file server and its tests.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>

namespace strata::serve::detail {

/// One version of one file as gzipped: which file (device and inode, so a
/// file replaced by a rename is another), which version (size and
/// modification time, as in the ETag) and the zlib level.
struct CompressedBodyKey
{
    std::uint64_t device = 0;
    std::uint64_t inode = 0;
    std::uint64_t size = 0;
    std::uint64_t modifiedNs = 0;
    int level = 0;

    bool operator==(const CompressedBodyKey&) const = default;
};

struct CompressedBodyKeyHash
{
    std::size_t operator()(const CompressedBodyKey& key) const
    {
        std::size_t hash = std::hash<std::uint64_t>{}(key.inode);
        for (const std::uint64_t part : {key.device, key.size, key.modifiedNs, std::uint64_t(key.level)}) {
            hash ^= std::hash<std::uint64_t>{}(part) + 0x9e3779b97f4a7c15ULL + (hash << 6) + (hash >> 2);
        }
        return hash;
    }
};

class CompressedBodyCache
{
public:
    using Body = std::shared_ptr<const std::string>;

    /// Holds at most `budgetBytes` of bodies (their capacity); 0 holds none.
    explicit CompressedBodyCache(std::size_t budgetBytes) : mBudget(budgetBytes) {}

    /// The body of `key`, now the most recently used; null when not held.
    Body find(const CompressedBodyKey& key)
    {
        std::lock_guard lock(mMutex);
        const auto found = mIndex.find(key);
        if (found == mIndex.end()) return nullptr;
        mOrder.splice(mOrder.begin(), mOrder, found->second);
        return found->second->second;
    }

    /// Keeps `body` for `key`, dropping the least recently used bodies to
    /// stay within the budget; a body larger than the whole budget is not
    /// kept. Returns the body held for `key` (an equal one another thread
    /// kept first), or `body` itself. Bodies already handed out live on in
    /// their answers when dropped here.
    Body insert(const CompressedBodyKey& key, Body body)
    {
        const std::size_t bytes = body->capacity();
        std::lock_guard lock(mMutex);
        if (const auto found = mIndex.find(key); found != mIndex.end()) {
            mOrder.splice(mOrder.begin(), mOrder, found->second);
            return found->second->second;
        }
        if (bytes > mBudget) return body;
        while (mBytes + bytes > mBudget) {
            mBytes -= mOrder.back().second->capacity();
            mIndex.erase(mOrder.back().first);
            mOrder.pop_back();
        }
        mOrder.emplace_front(key, body);
        mIndex.emplace(key, mOrder.begin());
        mBytes += bytes;
        return body;
    }

    /// The bytes held now (at most the budget).
    std::size_t bytes() const
    {
        std::lock_guard lock(mMutex);
        return mBytes;
    }

private:
    using Order = std::list<std::pair<CompressedBodyKey, Body>>; // most recently used first

    mutable std::mutex mMutex;
    const std::size_t mBudget;
    std::size_t mBytes = 0;
    Order mOrder;
    std::unordered_map<CompressedBodyKey, Order::iterator, CompressedBodyKeyHash> mIndex;
};

} // namespace strata::serve::detail
