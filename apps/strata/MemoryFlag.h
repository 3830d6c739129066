// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The --max-memory flag of generate and bake.

#include <strata/Error.h>

#include <cctype>
#include <cstdint>
#include <regex>
#include <string>

namespace strata::app {

// "8GiB", "512MiB", "2G", "1.5GB", "1000000" → bytes (binary units: K, M, G,
// T with or without "iB"/"B"); throws strata::Error otherwise.
inline std::uint64_t parseMemory(const std::string& text)
{
    static const std::regex pattern(R"(\s*([0-9]+(?:\.[0-9]+)?)\s*([kKmMgGtT]?)(?:i?[bB])?\s*)");
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) {
        throw Error(ErrorKind::BadInput, "--max-memory '" + text + "' must be a size like 8GiB, 512MiB or a byte count");
    }
    const double number = std::stod(match[1]);
    const std::string unit = match[2];
    const int shift = unit.empty() ? 0 : 10 * int(std::string("kmgt").find(char(std::tolower(unit[0]))) + 1);
    const double bytes = number * double(1ull << shift);
    if (!(bytes >= 1.0 && bytes < 1.8e19)) {
        throw Error(ErrorKind::BadInput, "--max-memory '" + text + "' is out of range (1 byte to 16 EiB)");
    }
    return std::uint64_t(bytes);
}

} // namespace strata::app
