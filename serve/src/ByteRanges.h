// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The byte ranges of a Range header that a file of a given size can
// satisfy (RFC 9110 14.1.2), made absolute and clamped to the file.
// cpp-httplib 0.11 (Debian 12) parses the header but slices with the
// values as given: `bytes=990-2000` of a 1000-byte file would be answered
// with 1011 bytes read past the end. The server passes it these instead.

#include <cstdint>
#include <utility>
#include <vector>

namespace strata::serve::detail {

/// (first, last) as parsed, -1 where the header left the bound out:
/// (a, -1) is `a-`, (-1, n) the suffix `-n`.
using ByteRange = std::pair<std::int64_t, std::int64_t>;

/// The satisfiable ranges of `requested`, each as (first, last) with
/// 0 <= first <= last < size: a range starting at or past the end, and an
/// empty suffix, are dropped; a last byte past the end is clamped. Empty
/// result: nothing is satisfiable (answer 416).
std::vector<ByteRange> satisfiableRanges(const std::vector<ByteRange>& requested, std::uint64_t size);

} // namespace strata::serve::detail
