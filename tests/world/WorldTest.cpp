// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Streaming, LOD seams, eviction and determinism of strata::world::World.

#include "WorldTestUtil.h"

#include <strata/Error.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/TerrainField.h>

#include <glm/geometric.hpp>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <set>
#include <thread>

namespace strata::test {
namespace {

using world::ChunkKey;
using world::World;
using world::WorldOptions;

WorldOptions smallOptions()
{
    return smallWorldOptions(96.0);
}

TEST(World, RejectsBadOptions)
{
    auto field = std::make_shared<terrain::SphereField>(glm::dvec3(0.0), 10.0);
    WorldOptions o = smallOptions();
    EXPECT_THROW(World(nullptr, o), Error);
    o.chunkSize = 12;
    EXPECT_THROW(World(field, o), Error);
    o = smallOptions();
    o.lodDistance = 20.0; // below 2·sqrt(3)·8 m: neighbours could differ by two levels
    EXPECT_THROW(World(field, o), Error);
    o = smallOptions();
    o.voxelSize = -1.0;
    EXPECT_THROW(World(field, o), Error);
    o = smallOptions();
    o.editBand = 0;
    EXPECT_THROW(World(field, o), Error);
    World w(field, smallOptions());
    EXPECT_THROW(w.setPointsOfInterest({glm::dvec3(NAN, 0.0, 0.0)}), Error);
    EXPECT_THROW(w.setPointsOfInterest({glm::dvec3(1e12, 0.0, 0.0)}), Error);
}

TEST(World, NothingResidentWithoutPointsOfInterest)
{
    World w(std::make_shared<terrain::SphereField>(glm::dvec3(0.0), 10.0), smallOptions());
    EXPECT_TRUE(w.poll().empty());
    w.waitIdle();
    EXPECT_TRUE(w.residentChunks().empty());
    EXPECT_TRUE(w.idle());
}

// The union of all chunk meshes of a closed shape, at three LOD levels, is
// closed: no boundary edge anywhere, in particular none between levels.
TEST(World, LodBordersAreClosedOnASphere)
{
    const glm::dvec3 centre(0.3, 0.2, 0.1);
    const double radius = 40.0;
    World w(std::make_shared<terrain::SphereField>(centre, radius), smallOptions());
    w.setPointsOfInterest({centre + glm::dvec3(radius, 0.0, 0.0)});
    w.waitIdle();
    const MeshMap meshes = currentMeshes(w);

    std::set<int> levelsWithSurface;
    for (const auto& [key, mesh] : meshes)
        if (mesh && !mesh->mesh.indices.empty()) levelsWithSurface.insert(key.level);
    EXPECT_EQ(levelsWithSurface, (std::set<int>{0, 1, 2}));

    std::map<std::size_t, int> levels;
    const meshing::TriangleMesh all = weld(meshes, &levels);
    std::size_t seamTriangles = 0;
    for (std::size_t t = 0; t < all.indices.size(); t += 3) {
        const int a = levels[all.indices[t]], b = levels[all.indices[t + 1]], c = levels[all.indices[t + 2]];
        if (a != b || b != c) ++seamTriangles;
    }
    EXPECT_GT(seamTriangles, 100u); // the test does cross LOD borders

    const meshing::MeshTopology topology = meshing::analyzeTopology(all);
    EXPECT_EQ(topology.boundaryEdges, 0u);
    EXPECT_EQ(topology.inconsistentEdges, 0u);
    EXPECT_EQ(topology.nonManifoldEdges, 0u);
    const double volume = meshing::signedVolume(all);
    const double exact = 4.0 / 3.0 * M_PI * radius * radius * radius;
    EXPECT_NEAR(volume, exact, 0.02 * exact);

    // Every vertex lies near the sphere (coarse cells of 2 voxels: within a cell).
    for (const glm::vec3& p : all.positions) EXPECT_NEAR(glm::length(glm::dvec3(p) - centre), radius, 1.0);

    // A crater dug across a border between levels keeps the union closed.
    glm::dvec3 seam(0.0);
    for (std::size_t t = 0; t < all.indices.size(); t += 3)
        if (levels[all.indices[t]] != levels[all.indices[t + 1]]) {
            seam = glm::dvec3(all.positions[all.indices[t]]);
            break;
        }
    const world::EditResult crater = w.dig(world::EditShape::sphere(seam, 3.0), 0.5);
    std::set<int> markedLevels;
    for (const ChunkKey& key : crater.markedChunks) markedLevels.insert(key.level);
    EXPECT_GE(markedLevels.size(), 2u);
    w.waitIdle();
    const meshing::TriangleMesh dug = weld(currentMeshes(w));
    const meshing::MeshTopology dugTopology = meshing::analyzeTopology(dug);
    EXPECT_EQ(dugTopology.boundaryEdges, 0u);
    EXPECT_EQ(dugTopology.inconsistentEdges, 0u);
    EXPECT_LT(meshing::signedVolume(dug), volume);
}

// A field that fails far from the origin: the failure reaches the caller.
class FailingField final : public terrain::DensityField
{
public:
    double density(const glm::dvec3& p) const override
    {
        if (p.x > 40.0) throw Error(ErrorKind::BadInput, "FailingField: no terrain east of x = 40");
        return p.y;
    }
    double lipschitz() const override { return 1.0; }
};

TEST(World, FieldErrorsReachTheCaller)
{
    World w(std::make_shared<FailingField>(), smallOptions());
    w.setPointsOfInterest({glm::dvec3(0.0)});
    try {
        w.waitIdle();
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("FailingField"), std::string::npos);
    }
}

/// A sphere that counts its evaluations and the calls running now, and is
/// slow (a block of points takes about 0.2 ms), so chunk tasks are still
/// running when the World is destroyed.
class WatchedSphere final : public terrain::DensityField
{
public:
    double density(const glm::dvec3& p) const override
    {
        const Running running(*this);
        return mSphere.density(p);
    }
    void densities(const terrain::PointBlock& points, double* out) const override
    {
        const Running running(*this);
        if (hold) {
            ++held;
            while (hold) std::this_thread::sleep_for(std::chrono::microseconds(100));
            --held;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        mSphere.densities(points, out);
    }
    double lipschitz() const override { return 1.0; }
    terrain::Interval bounds(const terrain::WorldBox& box) const override
    {
        const Running running(*this);
        return mSphere.bounds(box);
    }

    mutable std::atomic<int> running{0};      ///< calls in progress now
    mutable std::atomic<long> calls{0};       ///< calls so far
    mutable std::atomic<long> lateCalls{0};   ///< calls that began after `closed` was set
    std::atomic<bool> closed{false};          ///< set by the test once the World is gone
    std::atomic<bool> hold{false};            ///< block evaluations wait while this is set
    mutable std::atomic<int> held{0};         ///< block evaluations waiting on `hold` now

private:
    struct Running
    {
        explicit Running(const WatchedSphere& f)
            : field(f)
        {
            ++field.running;
            ++field.calls;
            if (field.closed) ++field.lateCalls;
        }
        ~Running() { --field.running; }
        const WatchedSphere& field;
    };
    terrain::SphereField mSphere{glm::dvec3(0.0), 30.0};
};

// Destroying a World while its chunk tasks run waits for the running ones,
// cancels the queued ones, and leaves nothing behind: no evaluation running
// or starting afterwards, the field released by every task, and far less
// work done than meshing the whole resident set would take.
TEST(World, DestroyedWhileChunksAreMeshed)
{
    // The work of meshing the whole resident set, for comparison.
    long fullCalls = 0;
    {
        auto field = std::make_shared<WatchedSphere>();
        {
            World w(field, smallOptions());
            w.setPointsOfInterest({glm::dvec3(30.0, 0.0, 0.0)});
            w.waitIdle();
            EXPECT_GT(w.stats().generated, 8u);
        }
        fullCalls = field->calls;
    }
    for (int i = 0; i < 3; ++i) {
        auto field = std::make_shared<WatchedSphere>();
        // Block evaluations wait at a gate, so one is surely running when the
        // destructor starts; a second thread opens the gate while ~World waits.
        field->hold = true;
        std::thread opener;
        std::size_t inFlight = 0;
        {
            World w(field, smallOptions());
            w.setPointsOfInterest({glm::dvec3(30.0, 0.0, 0.0)});
            // The resident set is computed off this thread: poll until tasks run.
            const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
            while (inFlight == 0 && std::chrono::steady_clock::now() < deadline) {
                w.poll();
                inFlight = w.stats().inFlight;
                if (inFlight == 0) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            }
            ASSERT_GT(inFlight, 0u) << "no chunk task ever started";
            while (field->held == 0 && std::chrono::steady_clock::now() < deadline) std::this_thread::yield();
            if (field->held == 0) field->hold = false; // let ~World finish before failing
            ASSERT_GT(field->held.load(), 0) << "no block evaluation ever started";
            opener = std::thread([&field] {
                std::this_thread::sleep_for(std::chrono::milliseconds(50));
                field->hold = false;
            });
        } // ~World, with an evaluation held at the gate
        opener.join();
        EXPECT_EQ(field->running.load(), 0) << "an evaluation was still running after ~World returned";
        const long atDestruction = field->calls;
        field->closed = true;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
        EXPECT_EQ(field->lateCalls.load(), 0) << "a task evaluated the field after ~World returned";
        EXPECT_EQ(field->calls.load(), atDestruction);
        EXPECT_EQ(field.use_count(), 1) << "a task or the World still holds the field";
        EXPECT_LT(atDestruction, fullCalls / 2) << "the destructor ran the queued tasks instead of cancelling them";
        std::printf("destroyed with %zu tasks in flight after %ld of the %ld field calls of a full run\n", inFlight,
                    atDestruction, fullCalls);
    }
}

// Chunks that come into view with nothing to show are meshed before the
// chunks whose old or retired meshes stand in for them: when the pool falls
// behind, the backlog is refinement and the view has no hole.
TEST(World, HolesAreMeshedBeforeChunksWithAStandIn)
{
    WorldOptions o = smallOptions();
    o.threads = 1;
    o.maxInFlight = 2;
    o.lookAhead = false;
    World w(std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2), o);
    w.setPointsOfInterest({glm::dvec3(0.0)});
    w.waitIdle();
    w.poll();
    ASSERT_EQ(w.stats().holes, 0u);
    // A move of 40 m: new ground at the far edge, LOD changes all along.
    w.setPointsOfInterest({glm::dvec3(40.0, 0.0, 0.0)});
    // The new resident set is computed off this thread: poll until it is in.
    world::WorldStats start = w.stats();
    for (auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
         start.holes == 0 && std::chrono::steady_clock::now() < until; start = w.stats()) {
        w.poll();
        std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    ASSERT_GT(start.holes, 0u) << "the move brought no new ground: the test proves less";
    ASSERT_GT(start.pending, start.holes + 8) << "the move changed no LOD: the test proves less";
    std::size_t standInsWhenWhole = 0;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
        w.poll();
        const world::WorldStats s = w.stats();
        if (s.holes == 0) {
            standInsWhenWhole = s.pending;
            break;
        }
        std::this_thread::sleep_for(std::chrono::microseconds(200));
    }
    std::printf("after the move: %zu holes and %zu chunks with a stand-in pending; %zu of those still pending when "
                "the view was whole\n",
                start.holes, start.pending - start.holes, standInsWhenWhole);
    EXPECT_GE(standInsWhenWhole, (start.pending - start.holes) / 2)
        << "the chunks with a stand-in were meshed before the holes";
    w.waitIdle();
    EXPECT_EQ(w.stats().holes, 0u);
    EXPECT_EQ(w.stats().pending, 0u);
}

TEST(World, PollReportsEveryMeshOnceAndEvictions)
{
    World w(std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2), smallOptions());
    w.setPointsOfInterest({glm::dvec3(4.0, 0.0, 4.0)});
    w.waitIdle();
    std::map<ChunkKey, int> held;
    for (const world::ChunkUpdate& u : w.poll()) {
        ASSERT_TRUE(u.mesh);
        EXPECT_EQ(u.mesh->key, u.key);
        EXPECT_FALSE(u.mesh->mesh.indices.empty());
        ++held[u.key];
    }
    const world::WorldStats stats = w.stats();
    EXPECT_EQ(held.size(), stats.withSurface);
    EXPECT_EQ(stats.generated, stats.resident);
    EXPECT_EQ(stats.pending, 0u);
    for (const auto& [key, n] : held) EXPECT_EQ(n, 1);
    EXPECT_TRUE(w.poll().empty());

    // Move far away: every chunk with a surface comes back as a removal (the
    // new resident set is computed off the polling thread: wait for it).
    w.setPointsOfInterest({glm::dvec3(1000.0, 0.0, 0.0)});
    w.waitIdle();
    std::size_t removed = 0;
    for (const world::ChunkUpdate& u : w.poll())
        if (!u.mesh && held.count(u.key)) ++removed;
    EXPECT_EQ(removed, held.size());
    EXPECT_GE(w.stats().evicted, stats.resident);
    EXPECT_EQ(w.stats().retained, 0u); // evicted at once, not kept for a replacement
    for (const ChunkKey& key : w.residentChunks()) {
        glm::dvec3 lo, hi;
        w.chunkBounds(key, lo, hi);
        EXPECT_GT(hi.x, 1000.0 - 96.0 - 1e-9);
    }
}

bool containsChunk(const ChunkKey& a, const ChunkKey& b)
{
    if (a.level < b.level) return false;
    const int shift = a.level - b.level;
    return (b.x >> shift) == a.x && (b.y >> shift) == a.y && (b.z >> shift) == a.z;
}

// While a point of interest moves so that chunks split and merge, the meshes
// the caller holds cover the surface after EVERY poll(): a chunk replaced by
// an LOD change stays until all chunks replacing it are meshed, then the
// removals and the new meshes come in the same poll().
//
// Old and new meshes do not weld exactly while they are mixed (a chunk's seam
// follows the levels of its lower neighbours when it was meshed), so during
// the transition the check is coverage, not closedness: every sample point of
// the sphere lies in the box of a held chunk. The sample points are those
// whose cell at every level is crossed by the surface (some corners in, some
// out) and lies well inside every chunk holding it (at least a cell diagonal
// from the chunk borders of each level), so any chunk holding one has
// triangles, whatever its level and its neighbours: the check is exact, with
// no tolerance. After the motion the union is closed again.
namespace {

/// A point crossing a sphere and back, polled every few milliseconds: the
/// caller never holds overlapping chunks or a hole, and at rest holds the
/// resident meshes, closed. With look-ahead, chunks arrive meshed ahead, so
/// replacements seldom wait; without it, many polls see one half done.
void expectNoHolesWhileChunksSplitAndMerge(bool lookAhead)
{
    const glm::dvec3 centre(0.3, 0.2, 0.1);
    const double radius = 20.0;
    auto field = std::make_shared<terrain::SphereField>(centre, radius);
    WorldOptions o = smallOptions();
    o.threads = 1;
    o.maxInFlight = 2; // meshes trickle in: many polls see a transition half done
    o.lookAhead = lookAhead;
    World w(field, o);

    std::vector<glm::dvec3> samples;
    const int count = 20000;
    for (int i = 0; i < count; ++i) {
        const double y = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - y * y), phi = i * 2.399963229728653;
        const glm::dvec3 p = centre + radius * glm::dvec3(r * std::cos(phi), y, r * std::sin(phi));
        bool robust = true;
        for (int level = 0; level < o.levels && robust; ++level) {
            const double cell = o.voxelSize * (1 << level), width = cell * o.chunkSize;
            for (int a = 0; a < 3 && robust; ++a) {
                const double m = p[a] - std::floor(p[a] / width) * width;
                robust = m > std::sqrt(3.0) * cell && m < width - std::sqrt(3.0) * cell;
            }
            int inside = 0;
            const glm::dvec3 lo = glm::floor(p / cell) * cell;
            for (int c = 0; c < 8; ++c)
                inside += field->density(lo + cell * glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1)) < 0.0;
            robust = robust && inside > 0 && inside < 8;
        }
        if (robust) samples.push_back(p);
    }
    ASSERT_GT(samples.size(), 2000u);

    MeshMap held;
    auto uncovered = [&](const MeshMap& set) {
        std::size_t n = 0;
        for (const glm::dvec3& p : samples) {
            bool in = false;
            for (const auto& [key, mesh] : set) {
                glm::dvec3 lo, hi;
                w.chunkBounds(key, lo, hi);
                if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThan(p, hi))) {
                    in = true;
                    break;
                }
            }
            n += !in;
        }
        return n;
    };
    int splits = 0, merges = 0, polls = 0, midTransition = 0;
    auto pollAndCheck = [&](std::size_t maxUpdates) {
        const std::vector<world::ChunkUpdate> updates = w.poll(maxUpdates);
        std::vector<ChunkKey> added, removed;
        for (const world::ChunkUpdate& u : updates) {
            if (u.mesh) {
                held[u.key] = u.mesh;
                added.push_back(u.key);
            } else {
                ASSERT_EQ(held.erase(u.key), 1u) << "removal of a chunk the caller does not hold";
                removed.push_back(u.key);
            }
        }
        for (const ChunkKey& r : removed)
            for (const ChunkKey& a : added) {
                splits += containsChunk(r, a) && r != a;
                merges += containsChunk(a, r) && r != a;
            }
        for (auto i = held.begin(); i != held.end(); ++i)
            for (auto j = std::next(i); j != held.end(); ++j)
                ASSERT_FALSE(containsChunk(i->first, j->first) || containsChunk(j->first, i->first))
                    << "the caller holds overlapping chunks";
        ASSERT_EQ(uncovered(held), 0u) << "a hole after poll " << polls;
        midTransition += w.stats().retained > 0;
        ++polls;
    };

    w.setPointsOfInterest({centre + glm::dvec3(44.0, 0.0, 0.0)});
    w.waitIdle();
    pollAndCheck(SIZE_MAX);
    // Across the sphere and back: chunks near the path split, those behind merge.
    for (int step = 0; step <= 60; ++step) {
        const double x = 44.0 - 3.0 * double(step <= 30 ? step : 60 - step);
        w.setPointsOfInterest({centre + glm::dvec3(x, 3.0, -2.0)});
        for (int i = 0; i < 3; ++i) {
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            pollAndCheck(i == 1 ? 2 : SIZE_MAX); // a replacement is never split by maxUpdates
            if (::testing::Test::HasFatalFailure()) return;
        }
    }
    while (!w.idle()) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        pollAndCheck(SIZE_MAX);
        if (::testing::Test::HasFatalFailure()) return;
    }
    pollAndCheck(SIZE_MAX);
    EXPECT_GT(splits, 0);
    EXPECT_GT(merges, 0);
    if (!lookAhead) {
        EXPECT_GT(midTransition, 0); // some polls did see a replacement waiting
    } else {
        EXPECT_GT(w.stats().prefetched, 0u);
    }
    EXPECT_EQ(w.stats().retained, 0u);

    // At rest the caller holds exactly the resident chunks with surface, and
    // their union is closed.
    MeshMap withSurface;
    for (const auto& [key, mesh] : currentMeshes(w))
        if (mesh && !mesh->mesh.indices.empty()) withSurface[key] = mesh;
    EXPECT_EQ(held.size(), withSurface.size());
    EXPECT_TRUE(differingChunks(held, withSurface).empty());
    const meshing::MeshTopology topology = meshing::analyzeTopology(weld(held));
    EXPECT_EQ(topology.boundaryEdges, 0u);

    // The check does find a hole: drop each held chunk that holds a sample.
    std::set<ChunkKey> holding;
    for (const auto& [key, mesh] : held) {
        glm::dvec3 lo, hi;
        w.chunkBounds(key, lo, hi);
        for (const glm::dvec3& p : samples)
            if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThan(p, hi))) holding.insert(key);
    }
    std::set<int> holdingLevels;
    for (const ChunkKey& key : holding) {
        holdingLevels.insert(key.level);
        MeshMap holed = held;
        holed.erase(key);
        EXPECT_GT(uncovered(holed), 0u);
    }
    EXPECT_GE(holdingLevels.size(), 2u); // holes at several levels are seen
}

} // namespace

TEST(World, NoHolesWhileChunksSplitAndMerge)
{
    expectNoHolesWhileChunksSplitAndMerge(false);
}

TEST(World, NoHolesWhileChunksSplitAndMergeWithLookAhead)
{
    expectNoHolesWhileChunksSplitAndMerge(true);
}

// Points of interest jumping back and forth (chunks split, merge, come back
// before their replacement is handed out, leave the view) never leave the
// caller with overlapping chunks, a removal of a chunk it does not hold, or,
// once at rest, a stale mesh.
TEST(World, JumpingPointsKeepTheHeldSetConsistent)
{
    const glm::dvec3 centre(0.3, 0.2, 0.1);
    WorldOptions o = smallOptions();
    o.threads = 2;
    o.maxInFlight = 3;
    o.viewRadius = 60.0;
    World w(std::make_shared<terrain::SphereField>(centre, 20.0), o);
    const std::vector<std::vector<glm::dvec3>> stops = {
        {glm::dvec3(30.0, 0.0, 0.0)},
        {glm::dvec3(-25.0, 5.0, 3.0)},
        {glm::dvec3(30.0, 0.0, 0.0), glm::dvec3(0.0, 0.0, -28.0)},
        {glm::dvec3(200.0, 0.0, 0.0)}, // everything leaves the view
        {glm::dvec3(10.0, 20.0, 0.0)},
    };
    MeshMap held;
    std::uint64_t state = 12345;
    for (int step = 0; step < 60; ++step) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        w.setPointsOfInterest(stops[(state >> 33) % stops.size()]);
        for (int i = 0; i < 2; ++i) {
            std::this_thread::sleep_for(std::chrono::microseconds((state >> 40) % 4000));
            for (const world::ChunkUpdate& u : w.poll()) {
                if (u.mesh) held[u.key] = u.mesh;
                else ASSERT_EQ(held.erase(u.key), 1u);
            }
            for (auto a = held.begin(); a != held.end(); ++a)
                for (auto b = std::next(a); b != held.end(); ++b)
                    ASSERT_FALSE(containsChunk(a->first, b->first) || containsChunk(b->first, a->first));
        }
    }
    w.setPointsOfInterest(stops[1]);
    w.waitIdle();
    for (const world::ChunkUpdate& u : w.poll()) {
        if (u.mesh) held[u.key] = u.mesh;
        else ASSERT_EQ(held.erase(u.key), 1u);
    }
    EXPECT_EQ(w.stats().retained, 0u);
    MeshMap withSurface;
    for (const auto& [key, mesh] : currentMeshes(w))
        if (mesh && !mesh->mesh.indices.empty()) withSurface[key] = mesh;
    EXPECT_FALSE(withSurface.empty());
    EXPECT_TRUE(differingChunks(held, withSurface).empty());
    EXPECT_EQ(meshing::analyzeTopology(weld(held)).boundaryEdges, 0u);
}

MeshMap meshesFor(int threads, std::uint64_t orderSeed, bool withEdit, int cacheLevels = 1)
{
    terrain::TerrainOptions terrainOptions;
    terrainOptions.seed = 7;
    auto field = std::make_shared<terrain::TerrainField>(terrainOptions);
    WorldOptions o = smallOptions();
    o.threads = threads;
    o.taskOrderSeed = orderSeed;
    o.maxInFlight = orderSeed ? 3 : 0;
    o.viewRadius = 28.0;
    o.sampleCacheLevels = cacheLevels;
    World w(field, o);
    w.setPointsOfInterest({glm::dvec3(5.0, 0.0, -3.0)});
    if (withEdit) {
        // Meshed once before the edits, so cached samples are reused after them.
        w.waitIdle();
        w.dig(world::EditShape::sphere(glm::dvec3(5.0, 0.0, -3.0), 4.0), 0.5);
        w.fill(world::EditShape::box(glm::dvec3(-9.0, 2.0, 4.0), glm::dvec3(3.0, 2.0, 1.0), 0.5));
    }
    w.waitIdle();
    return currentMeshes(w);
}

// The same field, edits and points of interest give the same bytes whatever
// the thread count and the order chunk tasks run and finish in.
TEST(World, DeterministicAcrossThreadCountsAndTaskOrder)
{
    const MeshMap a = meshesFor(1, 0, true);
    const MeshMap b = meshesFor(2, 0, true);
    const MeshMap c = meshesFor(3, 987654321, true);
    const MeshMap uncached = meshesFor(2, 0, true, 0); // samples kept between re-meshes change nothing
    const MeshMap allCached = meshesFor(2, 0, true, 3);
    std::size_t triangles = 0;
    for (const auto& [key, m] : a) triangles += m ? m->mesh.triangleCount() : 0;
    EXPECT_GT(triangles, 10000u);
    EXPECT_TRUE(differingChunks(a, b).empty());
    EXPECT_TRUE(differingChunks(a, c).empty());
    EXPECT_TRUE(differingChunks(a, uncached).empty());
    EXPECT_TRUE(differingChunks(a, allCached).empty());
    EXPECT_FALSE(differingChunks(a, meshesFor(2, 0, false)).empty()); // the comparison can fail
}

} // namespace
} // namespace strata::test

namespace strata::test {
namespace {

std::uint64_t fnv(std::uint64_t h, const void* data, std::size_t n)
{
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

template <typename T>
std::uint64_t fnvVector(std::uint64_t h, const std::vector<T>& v)
{
    const std::uint64_t n = v.size();
    h = fnv(h, &n, sizeof(n));
    return v.empty() ? h : fnv(h, v.data(), v.size() * sizeof(T));
}

// One hash over every resident chunk's mesh bytes, in key order.
std::uint64_t meshMapHash(const MeshMap& meshes)
{
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const auto& [key, data] : meshes) {
        h = fnv(h, &key, sizeof(key));
        if (!data) continue;
        h = fnv(h, &data->mesh.origin, sizeof(data->mesh.origin));
        h = fnvVector(h, data->mesh.positions);
        h = fnvVector(h, data->mesh.normals);
        h = fnvVector(h, data->mesh.indices);
        h = fnvVector(h, data->vertexCells);
    }
    return h;
}

// The chunk meshes (three levels, LOD seams, edits) hash to the values the
// World's own mesher gave before it moved into meshing's DualMesh: the move
// changed no bit.
TEST(World, ChunkMeshBytesAreUnchanged)
{
    const MeshMap edited = meshesFor(2, 0, true);
    terrain::TerrainOptions terrainOptions;
    terrainOptions.seed = 11;
    WorldOptions o = smallOptions();
    o.viewRadius = 60.0;
    World w(std::make_shared<terrain::TerrainField>(terrainOptions), o);
    w.setPointsOfInterest({glm::dvec3(-3.0, 1.0, 7.0)});
    w.waitIdle();
    const MeshMap wide = currentMeshes(w);
    std::set<int> levels;
    for (const auto& [key, mesh] : wide) levels.insert(key.level);
    EXPECT_EQ(levels.size(), 3u);
    const std::uint64_t got[] = {meshMapHash(edited), meshMapHash(wide)};
    const std::uint64_t expected[] = {0xaba7e945f39b63daull, 0x216d1c60e14fc7b1ull};
    for (std::size_t i = 0; i < std::size(got); ++i)
        EXPECT_EQ(got[i], expected[i]) << i << ": " << std::hex << got[i];
}

TEST(World, ChunkMeshesCarryTheLandformAndRockMasksWhenGiven)
{
    // A fake erode node: the masks are functions of the column, so every
    // vertex can be checked against its own world position.
    struct ColumnMasks final : terrain::LandformMasks
    {
        void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override
        {
            for (std::size_t i = 0; i < n; ++i) out[i] = glm::vec4(float(x[i]), float(z[i]), 1.0f, 0.5f);
        }
    };
    // A fake beds node: hardness and bed from the vertex's height and x.
    struct PointRock final : terrain::RockMasks
    {
        void rockMasks(const double* x, const double* y, const double* z, std::size_t n, glm::vec2* out) const override
        {
            for (std::size_t i = 0; i < n; ++i) out[i] = glm::vec2(float(y[i]), float(x[i] + z[i]));
        }
    };
    WorldOptions o = smallOptions();
    o.landform = std::make_shared<ColumnMasks>();
    o.rock = std::make_shared<PointRock>();
    World w(std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2), o);
    w.setPointsOfInterest({glm::dvec3(4.0, 0.0, 4.0)});
    w.waitIdle();
    std::size_t checked = 0;
    for (const world::ChunkUpdate& u : w.poll()) {
        ASSERT_TRUE(u.mesh);
        const meshing::TriangleMesh& mesh = u.mesh->mesh;
        ASSERT_EQ(mesh.landform.size(), mesh.positions.size());
        ASSERT_EQ(mesh.rock.size(), mesh.positions.size());
        for (std::size_t i = 0; i < mesh.positions.size(); ++i, ++checked) {
            const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
            EXPECT_EQ(mesh.landform[i].x, float(p.x));
            EXPECT_EQ(mesh.landform[i].y, float(p.z));
            EXPECT_EQ(mesh.rock[i], glm::vec2(float(p.y), float(p.x + p.z)));
        }
    }
    EXPECT_GT(checked, 100u);
    // Without masks the meshes carry none.
    World plain(std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2), smallOptions());
    plain.setPointsOfInterest({glm::dvec3(4.0, 0.0, 4.0)});
    plain.waitIdle();
    for (const world::ChunkUpdate& u : plain.poll()) {
        EXPECT_TRUE(u.mesh->mesh.landform.empty());
        EXPECT_TRUE(u.mesh->mesh.rock.empty());
    }
}

} // namespace
} // namespace strata::test
