// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The members World documents as thread-safe, called from several threads at
// once (run this test under ThreadSanitizer: see docs/world-library.md).

#include "WorldTestUtil.h"

#include <strata/terrain/Primitives.h>

#include <atomic>
#include <thread>

namespace strata::test {
namespace {

using world::EditShape;
using world::World;
using world::WorldOptions;

WorldOptions threadOptions()
{
    WorldOptions o;
    o.voxelSize = 0.5;
    o.chunkSize = 16;
    o.levels = 2;
    o.lodDistance = 28.0;
    o.viewRadius = 40.0;
    o.threads = 2;
    return o;
}

EditShape holeFor(int thread, int i)
{
    return EditShape::sphere(glm::dvec3(-14.0 + 9.0 * thread, -2.0 - 0.1 * i, -12.0 + 3.0 * i), 1.2);
}

constexpr int THREADS = 4, EDITS = 8;

TEST(WorldThreads, ConcurrentCallsGiveTheSequentialResult)
{
    auto field = std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2);
    World w(field, threadOptions());
    w.setPointsOfInterest({glm::dvec3(0.0)});
    std::atomic<std::size_t> updates{0}, hits{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < THREADS; ++t) {
        threads.emplace_back([&, t] {
            for (int i = 0; i < EDITS; ++i) {
                w.dig(holeFor(t, i));
                if (w.raycast(glm::dvec3(t, 10.0, i), glm::dvec3(0, -1, 0), 50.0)) ++hits;
                (void)w.density(glm::dvec3(i, -1.0, t));
                (void)w.isBoxSolid(glm::dvec3(t, -6.0, i), glm::dvec3(t + 1.0, -5.0, i + 1.0));
                updates += w.poll().size();
                (void)w.stats();
                (void)w.residentChunks();
                if (i % 3 == 0) w.setPointsOfInterest({glm::dvec3(0.0, 0.0, (t + i) % 2 ? 8.0 : 0.0)});
            }
        });
    }
    for (std::thread& th : threads) th.join();
    EXPECT_EQ(hits.load(), std::size_t(THREADS * EDITS));
    w.setPointsOfInterest({glm::dvec3(0.0)});
    w.waitIdle();

    World sequential(field, threadOptions());
    sequential.setPointsOfInterest({glm::dvec3(0.0)});
    for (int t = 0; t < THREADS; ++t)
        for (int i = 0; i < EDITS; ++i) sequential.dig(holeFor(t, i));
    sequential.waitIdle();
    EXPECT_EQ(w.stats().editVoxels, sequential.stats().editVoxels);
    const MeshMap a = currentMeshes(w), b = currentMeshes(sequential);
    EXPECT_EQ(a.size(), b.size());
    EXPECT_TRUE(differingChunks(a, b).empty());
}

} // namespace
} // namespace strata::test
