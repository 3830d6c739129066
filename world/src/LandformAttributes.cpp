// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/world/LandformAttributes.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>

namespace strata::world {

namespace {

constexpr std::size_t BLOCK = 1024; // vertices per masks call

} // namespace

std::vector<glm::vec4> computeLandformAttributes(const terrain::LandformMasks& masks, const meshing::TriangleMesh& mesh)
{
    const std::size_t n = mesh.positions.size();
    std::vector<glm::vec4> out(n);
    const std::size_t blocks = (n + BLOCK - 1) / BLOCK;
    // One block per task (simple_partitioner on a grain of 1): the ranges
    // are fixed whatever the thread count.
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, blocks, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
            std::array<double, BLOCK> x, z;
            for (std::size_t b = range.begin(); b != range.end(); ++b) {
                const std::size_t begin = b * BLOCK;
                const std::size_t count = std::min(BLOCK, n - begin);
                for (std::size_t i = 0; i < count; ++i) {
                    const glm::vec3& p = mesh.positions[begin + i];
                    x[i] = mesh.origin.x + double(p.x);
                    z[i] = mesh.origin.z + double(p.z);
                }
                masks.landformMasks(x.data(), z.data(), count, out.data() + begin);
            }
        },
        tbb::simple_partitioner());
    return out;
}

} // namespace strata::world
