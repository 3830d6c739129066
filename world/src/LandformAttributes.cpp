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

/// `fill(x, y, z, count, out)` over every vertex's world point, in blocks of
/// BLOCK vertices over fixed ranges (one block per task, simple_partitioner
/// on a grain of 1), whatever the thread count.
template<typename Value, typename Fill>
std::vector<Value> perVertex(const meshing::TriangleMesh& mesh, const Fill& fill)
{
    const std::size_t n = mesh.positions.size();
    std::vector<Value> out(n);
    const std::size_t blocks = (n + BLOCK - 1) / BLOCK;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, blocks, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
            std::array<double, BLOCK> x, y, z;
            for (std::size_t b = range.begin(); b != range.end(); ++b) {
                const std::size_t begin = b * BLOCK;
                const std::size_t count = std::min(BLOCK, n - begin);
                for (std::size_t i = 0; i < count; ++i) {
                    const glm::vec3& p = mesh.positions[begin + i];
                    x[i] = mesh.origin.x + double(p.x);
                    y[i] = mesh.origin.y + double(p.y);
                    z[i] = mesh.origin.z + double(p.z);
                }
                fill(x.data(), y.data(), z.data(), count, out.data() + begin);
            }
        },
        tbb::simple_partitioner());
    return out;
}

} // namespace

std::vector<glm::vec4> computeLandformAttributes(const terrain::LandformMasks& masks, const meshing::TriangleMesh& mesh)
{
    return perVertex<glm::vec4>(mesh, [&](const double* x, const double*, const double* z, std::size_t n,
                                          glm::vec4* out) { masks.landformMasks(x, z, n, out); });
}

std::vector<glm::vec2> computeRockAttributes(const terrain::RockMasks& masks, const meshing::TriangleMesh& mesh)
{
    return perVertex<glm::vec2>(mesh, [&](const double* x, const double* y, const double* z, std::size_t n,
                                          glm::vec2* out) { masks.rockMasks(x, y, z, n, out); });
}

} // namespace strata::world
