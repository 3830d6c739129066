// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ByteRanges.h"

#include <algorithm>

namespace strata::serve::detail {

std::vector<ByteRange> satisfiableRanges(const std::vector<ByteRange>& requested, std::uint64_t size)
{
    std::vector<ByteRange> out;
    const auto fileSize = std::int64_t(size);
    for (auto [first, last] : requested) {
        if (first < 0) { // suffix: the last `last` bytes
            if (last <= 0 || fileSize == 0) continue;
            first = std::max<std::int64_t>(0, fileSize - last);
            last = fileSize - 1;
        } else {
            if (first >= fileSize) continue;
            if (last < 0 || last >= fileSize) last = fileSize - 1;
            if (last < first) continue;
        }
        out.emplace_back(first, last);
    }
    return out;
}

} // namespace strata::serve::detail
