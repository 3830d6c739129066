// Streaming, LOD seams, eviction and determinism of strata::world::World.

#include "WorldTestUtil.h"

#include <strata/Error.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/TerrainField.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <set>

namespace strata::test {
namespace {

using world::ChunkKey;
using world::World;
using world::WorldOptions;

WorldOptions smallOptions()
{
    WorldOptions o;
    o.voxelSize = 0.5;
    o.chunkSize = 16; // 8 m chunks at level 0
    o.levels = 3;
    o.lodDistance = 28.0;
    o.viewRadius = 96.0;
    o.threads = 2;
    return o;
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
        if (p.x > 40.0) throw Error("FailingField: no terrain east of x = 40");
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

TEST(World, DestroyedWhileChunksAreMeshed)
{
    for (int i = 0; i < 3; ++i) {
        World w(std::make_shared<terrain::SphereField>(glm::dvec3(0.0), 30.0), smallOptions());
        w.setPointsOfInterest({glm::dvec3(30.0, 0.0, 0.0)});
        w.poll(); // queues tasks; the destructor cancels or waits for them
    }
    SUCCEED();
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

    // Move far away: every chunk with a surface comes back as a removal.
    w.setPointsOfInterest({glm::dvec3(1000.0, 0.0, 0.0)});
    std::size_t removed = 0;
    for (const world::ChunkUpdate& u : w.poll())
        if (!u.mesh && held.count(u.key)) ++removed;
    EXPECT_EQ(removed, held.size());
    EXPECT_GE(w.stats().evicted, stats.resident);
    w.waitIdle();
    for (const ChunkKey& key : w.residentChunks()) {
        glm::dvec3 lo, hi;
        w.chunkBounds(key, lo, hi);
        EXPECT_GT(hi.x, 1000.0 - 96.0 - 1e-9);
    }
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
