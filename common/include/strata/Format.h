// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Numbers as Strata's messages and reports print them, in one place.

#include <cstdint>
#include <sstream>
#include <string>

namespace strata {

/// The shortest stream form of `value` (6 significant digits): "0.5", "1e+09".
/// For messages, where the user's own value is echoed back.
inline std::string formatNumber(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

/// `value` with 17 significant digits, enough to read back the same double.
inline std::string formatExact(double value)
{
    std::ostringstream out;
    out.precision(17);
    out << value;
    return out.str();
}

/// 3151246 → "3,151,246".
inline std::string withThousands(std::uint64_t n)
{
    const std::string digits = std::to_string(n);
    std::string out;
    for (std::size_t i = 0; i < digits.size(); ++i) {
        if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
        out += digits[i];
    }
    return out;
}

} // namespace strata
