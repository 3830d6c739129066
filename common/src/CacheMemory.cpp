// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/CacheMemory.h>

#include <atomic>

#include <unistd.h>

namespace strata {

namespace {

std::uint64_t defaultLimit()
{
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    if (pages <= 0 || pageSize <= 0) return std::uint64_t(2) << 30; // unknown: 2 GiB
    return std::uint64_t(pages) * std::uint64_t(pageSize) / 4;
}

std::atomic<std::uint64_t> gLimit{0}; // 0: the default, looked up on first use
std::atomic<std::int64_t> gUsed{0};

} // namespace

void setCacheMemoryLimit(std::uint64_t bytes) { gLimit = bytes ? bytes : defaultLimit(); }

std::uint64_t cacheMemoryLimit()
{
    std::uint64_t limit = gLimit.load();
    if (limit == 0) {
        std::uint64_t none = 0;
        gLimit.compare_exchange_strong(none, defaultLimit());
        limit = gLimit.load();
    }
    return limit;
}

std::uint64_t cacheMemoryUsed()
{
    const std::int64_t used = gUsed.load();
    return used > 0 ? std::uint64_t(used) : 0;
}

namespace detail {
void chargeCacheMemory(std::int64_t delta) { gUsed += delta; }
} // namespace detail

} // namespace strata
