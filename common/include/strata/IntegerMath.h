// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Integer helpers every library shares (lattices, tiles, blocks).

#include <cstdint>

namespace strata {

/// ⌊a / b⌋ for b > 0, rounding toward −∞ (C++'s `/` rounds toward zero):
/// the index of the block of size b that holds a, negative a included.
inline std::int64_t floorDiv(std::int64_t a, std::int64_t b)
{
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

} // namespace strata
