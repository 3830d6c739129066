// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the range check of the renderers' parameter structs (Material,
// Atmosphere), one message format for all of them.

#include <strata/Error.h>

#include <cmath>
#include <sstream>

namespace strata::render::detail {

/// Throws strata::Error "WHAT: KEY = VALUE outside [LO, HI]" unless `value`
/// is finite and within [lo, hi].
inline void checkRange(const char* what, const char* key, double value, double lo, double hi)
{
    if (!(std::isfinite(value) && value >= lo && value <= hi)) {
        std::ostringstream s;
        s << what << ": " << key << " = " << value << " outside [" << lo << ", " << hi << "]";
        throw Error(ErrorKind::BadInput, s.str());
    }
}

} // namespace strata::render::detail
