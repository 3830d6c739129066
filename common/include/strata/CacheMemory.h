// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// What every cache of the process holds, against one limit: the erosion
/// grids, the detail-erosion and talus blocks, the worm caves' buckets and
/// spawn cells, the file server's gzipped bodies (ByteBoundedCache.h). Each
/// cache charges the bytes it keeps here and, while the process is over the
/// limit, drops its own least recently used entries (down to the few it
/// must keep to answer the query at hand), so the caches together stay
/// within the limit plus the entries in use. The CLI sets the limit from
/// --max-memory; the default is a quarter of the machine's memory.
///
/// Caches hold values that are pure functions of their keys: what they drop
/// is computed again, bit for bit, so the limit changes time, never bytes.

#include <cstdint>

namespace strata {

/// The limit, in bytes (0 restores the default). Thread-safe.
void setCacheMemoryLimit(std::uint64_t bytes);
/// The limit now, bytes.
std::uint64_t cacheMemoryLimit();
/// What the caches hold now, bytes.
std::uint64_t cacheMemoryUsed();

namespace detail {
/// For the caches: `delta` bytes kept (> 0) or dropped (< 0).
void chargeCacheMemory(std::int64_t delta);
} // namespace detail

} // namespace strata
