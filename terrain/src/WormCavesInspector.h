// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal (not installed): read access to WormCaves' spawn cells and
// buckets, whose layout is private, so they can be checked from outside
// against the rule that defines them (a bucket holds, in spawn order, the
// segments that come within CAP of its cube).

#include <strata/terrain/Caves.h>

#include <cstdint>
#include <vector>

namespace strata::terrain::detail {

class WormCavesInspector
{
public:
    using Segment = WormCaves::Segment;
    using Key = WormCaves::Key;

    static std::vector<Segment> wormsOfCell(const WormCaves& worms, std::int64_t cx, std::int64_t cz)
    {
        return worms.wormsOfCell(cx, cz);
    }
    static std::vector<Segment> bucketSegments(const WormCaves& worms, const Key& key)
    {
        return worms.bucketSegments(key);
    }
};

} // namespace strata::terrain::detail
