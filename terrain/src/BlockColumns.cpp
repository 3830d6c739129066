// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "BlockColumns.h"

#include <algorithm>
#include <cstring>

namespace strata::terrain::detail {

BlockColumns findColumns(const PointBlock& points, ScratchFrame& scratch)
{
    // A block of voxels (x outer, z inner) repeats its first column after
    // one row of z: 4 or 8 points in the sampler's and the World's blocks.
    constexpr std::size_t PROBE = 16;
    const std::size_t n = points.count;
    BlockColumns columns;
    columns.of = scratch.array<std::uint32_t>(n);
    columns.x = scratch.array<double>(n);
    columns.z = scratch.array<double>(n);
    std::size_t& count = columns.count;
    // Open addressing in a table at least twice the block's size.
    std::size_t slots = 16;
    int shift = 64 - 4;
    while (slots < 2 * n) {
        slots *= 2;
        --shift;
    }
    std::uint32_t* table = scratch.array<std::uint32_t>(slots);
    std::fill(table, table + slots, UINT32_MAX);
    const auto bits = [](double v) {
        std::uint64_t b;
        std::memcpy(&b, &v, sizeof b);
        return b;
    };
    // The lattice's period: the distance back to where the first repeated
    // column was first seen (one row of a block: the same column again one
    // row later). A point that repeats the column of the point one period
    // back takes it without hashing; the others are hashed.
    std::size_t period = 0;
    std::uint32_t* firstPoint = scratch.array<std::uint32_t>(n); // per column
    for (std::size_t i = 0; i < n; ++i) {
        if (period != 0 && i >= period && bits(points.x[i]) == bits(points.x[i - period]) &&
            bits(points.z[i]) == bits(points.z[i - period])) {
            columns.of[i] = columns.of[i - period];
            continue;
        }
        if (i == PROBE && count == PROBE) {
            // No two of the first PROBE points share a column (a domain warp
            // moved them apart): hashing the rest would find none either, so
            // each is its own column. Only the work depends on this: a
            // column found twice gives the same values twice.
            for (; i < n; ++i) {
                columns.of[i] = std::uint32_t(count);
                columns.x[count] = points.x[i];
                columns.z[count++] = points.z[i];
            }
            break;
        }
        const std::uint64_t bx = bits(points.x[i]), bz = bits(points.z[i]);
        const std::uint64_t h = (bx * 0x9e3779b97f4a7c15ULL) ^ ((bz + 0x632be59bd9b4e019ULL) * 0xbf58476d1ce4e5b9ULL);
        // The top bits: the products push the coordinates' entropy up (round
        // coordinates have all-zero low mantissa bits).
        std::size_t slot = std::size_t(h >> shift);
        for (;; slot = (slot + 1) & (slots - 1)) {
            const std::uint32_t c = table[slot];
            if (c == UINT32_MAX) {
                table[slot] = std::uint32_t(count);
                columns.of[i] = std::uint32_t(count);
                firstPoint[count] = std::uint32_t(i);
                columns.x[count] = points.x[i];
                columns.z[count++] = points.z[i];
                break;
            }
            if (bits(columns.x[c]) == bx && bits(columns.z[c]) == bz) {
                columns.of[i] = c;
                if (period == 0) period = i - firstPoint[c];
                break;
            }
        }
    }
    return columns;
}

} // namespace strata::terrain::detail
