// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Look-ahead: the chunks a moving point of interest will need after its
// next level-0 chunk border are meshed before it crosses, with the same
// bytes as meshes made on arrival, and dropped when the point turns or an
// edit changes their samples.

#include "WorldTestUtil.h"

#include "MotionLookAhead.h"

#include <strata/terrain/Primitives.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace strata::test {
namespace {

using world::ChunkKey;
using world::World;
using world::WorldOptions;
using world::detail::LodParams;
using world::detail::nextChunk;

WorldOptions lookAheadOptions(bool lookAhead)
{
    WorldOptions o = smallWorldOptions(64.0);
    o.lookAhead = lookAhead;
    return o;
}

const glm::dvec3 kCentre(0.3, 0.2, 0.1);
constexpr double kRadius = 20.0;

std::shared_ptr<terrain::SphereField> sphere()
{
    return std::make_shared<terrain::SphereField>(kCentre, kRadius);
}

/// Walks the point to `to` in 1 m steps from `from` (the direction of motion
/// is the last step's), then waits until the world is idle.
void walk(World& w, glm::dvec3 from, const glm::dvec3& to)
{
    const glm::dvec3 d = to - from;
    const int steps = std::max(1, int(std::ceil(glm::length(d))));
    for (int i = 0; i <= steps; ++i) w.setPointsOfInterest({from + d * (double(i) / steps)});
    w.waitIdle();
    w.poll();
}

/// The resident meshes of a world without look-ahead whose point stands at `p`.
MeshMap reference(const glm::dvec3& p, const std::vector<world::Edit>& edits = {})
{
    World w(sphere(), lookAheadOptions(false));
    for (const world::Edit& e : edits) w.apply(e);
    w.setPointsOfInterest({p});
    w.waitIdle();
    return currentMeshes(w);
}

} // namespace

TEST(MotionLookAhead, NextChunkIsTheOneTheRayEntersFirst)
{
    const LodParams params{0.5, 32, 4, 64.0, 384.0}; // 16 m level-0 chunks
    const glm::dvec3 p(3.0, 5.0, 7.0);
    EXPECT_EQ(nextChunk(p, glm::dvec3(1.0, 0.0, 0.0), params), (ChunkKey{0, 1, 0, 0}));
    EXPECT_EQ(nextChunk(p, glm::dvec3(-1.0, 0.0, 0.0), params), (ChunkKey{0, -1, 0, 0}));
    EXPECT_EQ(nextChunk(p, glm::dvec3(0.0, 0.0, -2.0), params), (ChunkKey{0, 0, 0, -1}));
    // The nearer face wins: x leaves after 13 m, y after 11 m.
    EXPECT_EQ(nextChunk(p, glm::dvec3(1.0, 1.0, 0.0), params), (ChunkKey{0, 0, 1, 0}));
    // Through an edge and through a corner exactly: both or all three axes step.
    const glm::dvec3 mid(8.0, 8.0, 8.0);
    EXPECT_EQ(nextChunk(mid, glm::dvec3(1.0, -1.0, 0.0), params), (ChunkKey{0, 1, -1, 0}));
    EXPECT_EQ(nextChunk(mid, glm::dvec3(-1.0, 1.0, 1.0), params), (ChunkKey{0, -1, 1, 1}));
    // At rest: its own chunk. On a lower face moving down: the chunk below.
    EXPECT_EQ(nextChunk(p, glm::dvec3(0.0), params), (ChunkKey{0, 0, 0, 0}));
    EXPECT_EQ(nextChunk(glm::dvec3(16.0, 5.0, 5.0), glm::dvec3(-1.0, 0.0, 0.0), params), (ChunkKey{0, 0, 0, 0}));
    // Far from the origin, in a negative chunk.
    EXPECT_EQ(nextChunk(glm::dvec3(-1.0e6 + 0.5, 0.0, 0.0), glm::dvec3(-1.0, 0.0, 0.0), params),
              (ChunkKey{0, -62501, 0, 0}));
}

TEST(MotionLookAhead, DirectionsComeFromTheLastMove)
{
    const LodParams params{0.5, 32, 4, 64.0, 384.0};
    world::detail::MotionLookAhead motion;
    motion.update({glm::dvec3(3.0, 5.0, 7.0), glm::dvec3(40.0, 5.0, 7.0)});
    // Nothing moved yet: the next chunks are the current ones.
    EXPECT_EQ(motion.nextInterest(params), (std::vector<ChunkKey>{{0, 0, 0, 0}, {0, 2, 0, 0}}));
    motion.update({glm::dvec3(4.0, 5.0, 7.0), glm::dvec3(40.0, 5.0, 7.0)});
    EXPECT_EQ(motion.nextInterest(params), (std::vector<ChunkKey>{{0, 1, 0, 0}, {0, 2, 0, 0}}));
    // Standing still keeps the last direction; the second point now moves down.
    motion.update({glm::dvec3(4.0, 5.0, 7.0), glm::dvec3(40.0, 4.0, 7.0)});
    EXPECT_EQ(motion.nextInterest(params), (std::vector<ChunkKey>{{0, 1, 0, 0}, {0, 2, -1, 0}}));
    // Another number of points: directions forgotten.
    motion.update({glm::dvec3(4.0, 5.0, 7.0)});
    EXPECT_EQ(motion.nextInterest(params), (std::vector<ChunkKey>{{0, 0, 0, 0}}));
}

TEST(World, LookAheadMeshesTheNextPartitionWithTheSameBytes)
{
    World w(sphere(), lookAheadOptions(true));
    // Heading +x inside chunk x = 5 (40..48 m), towards x = 6.
    walk(w, glm::dvec3(41.0, 1.0, -1.0), glm::dvec3(46.0, 1.0, -1.0));
    world::WorldStats before = w.stats();
    EXPECT_EQ(before.pending, 0u);
    EXPECT_GT(before.prefetchHeld, 0u);
    EXPECT_GT(before.prefetchBytes, 0u);
    EXPECT_EQ(before.prefetched, 0u);

    // Crossing the border: every chunk the new partition meshes was meshed ahead.
    const glm::dvec3 there(49.0, 1.0, -1.0);
    walk(w, glm::dvec3(46.0, 1.0, -1.0), there);
    const world::WorldStats after = w.stats();
    const std::uint64_t made = (after.generated + after.remeshed) - (before.generated + before.remeshed);
    EXPECT_GT(after.prefetched, 0u);
    EXPECT_EQ(after.prefetched - before.prefetched, made) << "a chunk of the crossing was meshed on arrival";
    EXPECT_TRUE(differingChunks(currentMeshes(w), reference(there)).empty());
}

TEST(World, LookAheadDropsMeshesWhenThePointTurns)
{
    World w(sphere(), lookAheadOptions(true));
    walk(w, glm::dvec3(41.0, 1.0, -1.0), glm::dvec3(46.0, 1.0, -1.0)); // towards x = 6
    const world::WorldStats ahead = w.stats();
    ASSERT_GT(ahead.prefetchHeld, 0u);
    walk(w, glm::dvec3(46.0, 1.0, -1.0), glm::dvec3(42.0, 1.0, -1.0)); // now towards x = 4
    const world::WorldStats turned = w.stats();
    EXPECT_GT(turned.prefetchDropped, 0u);
    EXPECT_GT(turned.prefetchHeld, 0u);
    EXPECT_EQ(turned.generated + turned.remeshed, ahead.generated + ahead.remeshed); // nothing resident changed

    const glm::dvec3 there(39.0, 1.0, -1.0);
    walk(w, glm::dvec3(42.0, 1.0, -1.0), there);
    EXPECT_GT(w.stats().prefetched, 0u);
    EXPECT_TRUE(differingChunks(currentMeshes(w), reference(there)).empty());
}

TEST(World, LookAheadMeshesAnEditTouchesAreMadeAgain)
{
    World w(sphere(), lookAheadOptions(true));
    // Towards x = 4 (32..40 m): the level-1 chunk over x 0..16 m splits
    // there, so the sphere's surface near x = 12 m is meshed ahead at level 0.
    walk(w, glm::dvec3(47.0, 1.0, -1.0), glm::dvec3(41.0, 1.0, -1.0));
    const world::WorldStats ahead = w.stats();
    ASSERT_GT(ahead.prefetchHeld, 0u);
    const world::Edit dig{world::EditShape::sphere(kCentre + glm::dvec3(12.0, 0.0, 16.0), 3.0), world::EditMode::DIG,
                          0.0};
    w.apply(dig);
    EXPECT_GT(w.stats().prefetchDropped, ahead.prefetchDropped) << "the edit touched no mesh made ahead";
    w.waitIdle();
    w.poll();

    const glm::dvec3 there(39.0, 1.0, -1.0);
    walk(w, glm::dvec3(41.0, 1.0, -1.0), there);
    EXPECT_GT(w.stats().prefetched, 0u);
    EXPECT_TRUE(differingChunks(currentMeshes(w), reference(there, {dig})).empty());
}

// A chunk keeps its samples (WorldOptions::sampleCacheLevels) across
// signatures, and a signature with a coarser neighbour prunes with a wider
// margin: the meshes after a walk there and back must still be those of a
// world that never moved. (They were not: normals differed where an octant
// the narrower margin prunes came from the cache, exact.)
TEST(World, MeshesAfterAWalkAreThoseOfAWorldThatNeverMoved)
{
    for (const bool lookAhead : {false, true}) {
        SCOPED_TRACE(lookAhead ? "look-ahead" : "no look-ahead");
        World w(sphere(), lookAheadOptions(lookAhead));
        walk(w, glm::dvec3(41.0, 1.0, -1.0), glm::dvec3(46.0, 1.0, -1.0));
        walk(w, glm::dvec3(46.0, 1.0, -1.0), glm::dvec3(42.0, 1.0, -1.0));
        const glm::dvec3 there(39.0, 1.0, -1.0);
        walk(w, glm::dvec3(42.0, 1.0, -1.0), there);
        walk(w, there, glm::dvec3(55.0, 1.0, -1.0));
        walk(w, glm::dvec3(55.0, 1.0, -1.0), there);
        EXPECT_TRUE(differingChunks(currentMeshes(w), reference(there)).empty());
    }
}

} // namespace strata::test
