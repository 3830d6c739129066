#pragma once
/// \file
/// CRC-32 (the zip, PNG and gzip checksum: polynomial 0xEDB88320 reflected,
/// initial and final XOR 0xFFFFFFFF), for checking and writing archives.

#include <array>
#include <cstdint>
#include <string_view>

namespace strata {

/// The CRC-32 of `bytes`; crc32("123456789") = 0xCBF43926. O(n), table-driven.
inline std::uint32_t crc32(std::string_view bytes)
{
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    std::uint32_t c = 0xFFFFFFFFu;
    for (char b : bytes) c = table[(c ^ std::uint8_t(b)) & 0xFFu] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

} // namespace strata
