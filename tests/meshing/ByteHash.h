// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// FNV-1a over raw bytes: the golden hashes of mesher outputs (bit for bit).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::test {

struct ByteHash
{
    std::uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* data, std::size_t n)
    {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    }
    /// The element count, then the elements' bytes.
    template <class T>
    void vec(const std::vector<T>& v)
    {
        const std::uint64_t n = v.size();
        bytes(&n, sizeof n);
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
};

} // namespace strata::test
