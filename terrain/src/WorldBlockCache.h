// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The cache of a height node computed in fixed world blocks (erode_detail,
/// talus): blocks by their (bx, bz) index in a ByteBoundedCache (bounded in
/// bytes and by the process's cache limit, --max-memory; a dropped block
/// computed again gives the same bits), plus the last few blocks each
/// thread used for the node, since neighbouring columns and a thread's next
/// calls mostly read the same blocks.
///
/// `Block` has `std::size_t bytes() const`. Two threads that miss the same
/// block may both compute it; the first one stored is kept (both are the
/// same bits: a block is a pure function of its index).

#include <strata/ByteBoundedCache.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>

namespace strata::terrain::detail {

template<typename Block>
class WorldBlockCache
{
public:
    /// Keeps blocks up to `byteBudget` bytes, and at least `minBlocks` (the
    /// blocks one query may need together).
    explicit WorldBlockCache(std::size_t byteBudget, std::size_t minBlocks = 4)
        : mBlocks(byteBudget, minBlocks), mId(nextId())
    {
    }

    /// The block (bx, bz), computed by `compute()` (returning a
    /// std::shared_ptr<const Block>) when it is not cached.
    template<typename Compute>
    std::shared_ptr<const Block> get(std::int64_t bx, std::int64_t bz, Compute&& compute)
    {
        Recent& recent = recentOfThisThread();
        for (const Entry& e : recent.entries) {
            if (e.block && e.bx == bx && e.bz == bz) return e.block;
        }
        std::shared_ptr<const Block> block = find(bx, bz);
        if (!block) {
            block = compute();
            block = add(bx, bz, std::move(block));
        }
        std::rotate(recent.entries, recent.entries + RECENT - 1, recent.entries + RECENT);
        recent.entries[0] = Entry{bx, bz, block};
        return block;
    }

    /// Blocks computed and stored so far (for benchmarks and tests).
    std::size_t computed() const { return mComputed.load(); }

private:
    static constexpr int RECENT = 4;
    struct Entry
    {
        std::int64_t bx = 0, bz = 0;
        std::shared_ptr<const Block> block;
    };
    struct Recent
    {
        std::uint64_t cache = 0;
        Entry entries[RECENT];
    };

    static std::uint64_t nextId()
    {
        static std::atomic<std::uint64_t> ids{0};
        return ++ids; // never reused, unlike an address
    }
    Recent& recentOfThisThread() const
    {
        thread_local Recent recent;
        if (recent.cache != mId) recent = Recent{mId, {}};
        return recent;
    }
    std::shared_ptr<const Block> find(std::int64_t bx, std::int64_t bz) { return mBlocks.find({bx, bz}); }
    std::shared_ptr<const Block> add(std::int64_t bx, std::int64_t bz, std::shared_ptr<const Block> block)
    {
        const std::size_t bytes = block->bytes();
        std::shared_ptr<const Block> kept = mBlocks.insert({bx, bz}, block, bytes);
        if (kept == block) ++mComputed;
        return kept;
    }

    ByteBoundedCache<std::pair<std::int64_t, std::int64_t>, Block> mBlocks;
    const std::uint64_t mId; ///< this cache among all made in the process (threads' recent blocks)
    std::atomic<std::size_t> mComputed{0};
};

} // namespace strata::terrain::detail
