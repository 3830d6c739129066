// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The gzipped bodies the file server made, kept for the next request of the
// same version of the same file: a viewer's reload, or a second browser, asks
// again for the same tileset.json and script, and gzipping them again costs
// a read of the file and 17 ms a MB. Header-only: the file server and its
// tests.

#include <strata/ByteBoundedCache.h>

#include <compare>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
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

    auto operator<=>(const CompressedBodyKey&) const = default;
};

/// The gzipped bodies, least recently used dropped first, within the budget
/// and the process's cache limit (strata/ByteBoundedCache.h); a body larger
/// than the whole budget is not kept.
class CompressedBodyCache : public ByteBoundedCache<CompressedBodyKey, std::string>
{
public:
    using Body = std::shared_ptr<const std::string>;

    /// Holds at most `budgetBytes` of bodies (their capacity); 0 holds none.
    explicit CompressedBodyCache(std::size_t budgetBytes) : ByteBoundedCache(budgetBytes, 0) {}

    /// Keeps `body` for `key`; returns the body held for `key` (an equal
    /// one another thread kept first), or `body` itself. Bodies already
    /// handed out live on in their answers when dropped here.
    Body insert(const CompressedBodyKey& key, Body body)
    {
        const std::uint64_t bytes = body->capacity();
        return ByteBoundedCache::insert(key, std::move(body), bytes);
    }

    /// The bytes held now (at most the budget).
    std::size_t bytes() const { return std::size_t(stats().bytes); }
};

} // namespace strata::serve::detail
