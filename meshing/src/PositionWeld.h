// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: vertices at the same position, shared by the mesh checks
// (MeshMetrics) and removeSmallComponents.

#include <strata/meshing/TriangleMesh.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <vector>

namespace strata::meshing::detail {

/// For each vertex, the smallest index of a vertex with exactly the same
/// float position (itself if none precedes it); +0 and -0 count as equal.
/// Sorting instead of hashing keeps it simple and deterministic;
/// O(V log V).
inline std::vector<std::uint32_t> weldByPosition(const std::vector<glm::vec3>& positions)
{
    using Key = std::array<std::uint32_t, 3>;
    auto key = [&](std::uint32_t i) {
        Key k;
        for (int a = 0; a < 3; ++a) {
            const float f = positions[i][a] + 0.0f; // -0 + 0 = +0
            std::memcpy(&k[a], &f, sizeof(float));
        }
        return k;
    };
    std::vector<Key> keys(positions.size());
    for (std::uint32_t i = 0; i < positions.size(); ++i) keys[i] = key(i);
    std::vector<std::uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
        return keys[a] != keys[b] ? keys[a] < keys[b] : a < b;
    });
    std::vector<std::uint32_t> weld(positions.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
        const bool first = i == 0 || keys[order[i]] != keys[order[i - 1]];
        weld[order[i]] = first ? order[i] : weld[order[i - 1]];
    }
    return weld;
}

} // namespace strata::meshing::detail
