// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "BlockColumns.h"

#include <cstring>

namespace strata::terrain::detail {

void findColumns(const PointBlock& points, BlockColumns& columns)
{
    // A block of voxels (x outer, z inner) repeats its first column after
    // one row of z: 4 or 8 points in the sampler's and the World's blocks.
    constexpr std::size_t PROBE = 16;
    const std::size_t n = points.count;
    columns.of.resize(n);
    columns.x.clear();
    columns.z.clear();
    // Open addressing in a table at least twice the block's size.
    std::size_t slots = 16;
    int shift = 64 - 4;
    while (slots < 2 * n) {
        slots *= 2;
        --shift;
    }
    thread_local std::vector<std::uint32_t> table; // calls nothing: one per thread is safe
    table.assign(slots, UINT32_MAX);
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
    thread_local std::vector<std::uint32_t> firstPoint; // per column
    firstPoint.clear();
    for (std::size_t i = 0; i < n; ++i) {
        if (period != 0 && i >= period && bits(points.x[i]) == bits(points.x[i - period]) &&
            bits(points.z[i]) == bits(points.z[i - period])) {
            columns.of[i] = columns.of[i - period];
            continue;
        }
        if (i == PROBE && columns.x.size() == PROBE) {
            // No two of the first PROBE points share a column (a domain warp
            // moved them apart): hashing the rest would find none either, so
            // each is its own column. Only the work depends on this: a
            // column found twice gives the same values twice.
            for (; i < n; ++i) {
                columns.of[i] = std::uint32_t(columns.x.size());
                columns.x.push_back(points.x[i]);
                columns.z.push_back(points.z[i]);
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
                table[slot] = std::uint32_t(columns.x.size());
                columns.of[i] = std::uint32_t(columns.x.size());
                columns.x.push_back(points.x[i]);
                columns.z.push_back(points.z[i]);
                firstPoint.push_back(std::uint32_t(i));
                break;
            }
            if (bits(columns.x[c]) == bx && bits(columns.z[c]) == bz) {
                columns.of[i] = c;
                if (period == 0) period = i - firstPoint[c];
                break;
            }
        }
    }
}

} // namespace strata::terrain::detail
