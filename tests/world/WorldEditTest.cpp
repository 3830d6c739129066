// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Edits of strata::world::World: which chunks they mark, undo by the inverse
// edit, persistence across eviction and in .vdb files.

#include "WorldTestUtil.h"

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/terrain/Primitives.h>

#include <fstream>
#include <iterator>

namespace strata::test {
namespace {

using world::ChunkKey;
using world::EditShape;
using world::World;
using world::WorldOptions;

WorldOptions editOptions()
{
    return smallWorldOptions(64.0);
}

std::shared_ptr<terrain::DensityField> ground()
{
    return std::make_shared<terrain::PlaneField>(glm::dvec3(0.0, 1.0, 0.0), 0.2); // rock below y = 0.2
}

const glm::dvec3 POI(4.0, 0.0, 4.0);

TEST(WorldEdit, DigInsideOneChunkMarksOnlyIt)
{
    World w(ground(), editOptions());
    w.setPointsOfInterest({POI});
    w.waitIdle();
    const MeshMap before = currentMeshes(w);
    // Changed samples span x, z in [0.9, 6.3], y in [-6.7, -1.3]: inside chunk
    // (0, -1, 0) and outside every neighbour's footprint [k·8 − 1, k·8 + 8].
    const world::EditResult r = w.dig(EditShape::sphere(glm::dvec3(3.6, -4.0, 3.6), 1.2));
    EXPECT_GT(r.changedVoxels, 100u);
    EXPECT_EQ(r.markedChunks, (std::vector<ChunkKey>{{0, 0, -1, 0}}));
    w.waitIdle();
    const MeshMap after = currentMeshes(w);
    EXPECT_EQ(differingChunks(before, after), r.markedChunks);
    EXPECT_EQ(w.stats().remeshed, 1u);
    EXPECT_TRUE(before.at({0, 0, -1, 0})->mesh.indices.empty()); // a closed cavity appeared in solid rock
    EXPECT_FALSE(after.at({0, 0, -1, 0})->mesh.indices.empty());
}

TEST(WorldEdit, DigAtAChunkCornerMarksTheEightAround)
{
    World w(ground(), editOptions());
    w.setPointsOfInterest({POI});
    w.waitIdle();
    const MeshMap before = currentMeshes(w);
    const world::EditResult r = w.dig(EditShape::sphere(glm::dvec3(8.1, -8.2, 8.05), 1.2));
    std::vector<ChunkKey> expected;
    for (int x = 0; x <= 1; ++x)
        for (int y = -2; y <= -1; ++y)
            for (int z = 0; z <= 1; ++z) expected.push_back({0, x, y, z});
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(r.markedChunks, expected);
    w.waitIdle();
    // Each of the eight owns part of the cavity: all their meshes change, no other.
    EXPECT_EQ(differingChunks(before, currentMeshes(w)), expected);
    // The cavity is closed across the chunk borders.
    MeshMap cavityChunks;
    for (const ChunkKey& key : expected) cavityChunks[key] = w.chunkMesh(key);
    const meshing::TriangleMesh cavity = weld(cavityChunks);
    EXPECT_GT(cavity.triangleCount(), 50u);
    EXPECT_TRUE(meshing::analyzeTopology(cavity).watertight());
}

TEST(WorldEdit, FillAfterTheSameDigRestoresTheMeshes)
{
    World w(ground(), editOptions());
    w.setPointsOfInterest({POI});
    w.waitIdle();
    const MeshMap original = currentMeshes(w);
    const EditShape shapes[] = {EditShape::sphere(glm::dvec3(6.0, -6.0, 7.5), 2.0),
                                EditShape::box(glm::dvec3(-3.0, -7.0, 2.0), glm::dvec3(2.0, 1.0, 3.0), 0.5),
                                EditShape::capsule(glm::dvec3(-5.0, -9.0, -5.0), glm::dvec3(5.0, -6.0, 5.0), 1.5)};
    for (const EditShape& shape : shapes) {
        const world::EditResult dug = w.dig(shape);
        EXPECT_FALSE(dug.markedChunks.empty());
        w.waitIdle();
        EXPECT_FALSE(differingChunks(original, currentMeshes(w)).empty());
        w.fill(shape);
        w.waitIdle();
        const std::vector<ChunkKey> differ = differingChunks(original, currentMeshes(w));
        EXPECT_TRUE(differ.empty());
        for (const ChunkKey& k : differ) {
            const auto a = original.at(k), b = w.chunkMesh(k);
            ADD_FAILURE() << "chunk " << k.level << " " << k.x << " " << k.y << " " << k.z << ": "
                          << a->mesh.triangleCount() << " vs " << b->mesh.triangleCount();
        }
    }
}

TEST(WorldEdit, DigAndFillChangeTheDensityAsExpected)
{
    World w(ground(), editOptions());
    const glm::dvec3 c(1.3, 0.2, 2.1); // on the surface
    EXPECT_NEAR(w.density(c), 0.0, 1e-6);
    w.dig(EditShape::sphere(c, 3.0));
    EXPECT_GT(w.density(c), 1.4);                        // clamped to the band: 3 voxels
    EXPECT_NEAR(w.density(c + glm::dvec3(0, -3.0, 0)), 0.0, 0.05); // the bottom of the crater
    EXPECT_LT(w.density(c + glm::dvec3(0, -4.0, 0)), -0.9);
    w.fill(EditShape::box(c + glm::dvec3(0, 5.0, 0), glm::dvec3(1.0, 1.0, 1.0)));
    EXPECT_LT(w.density(c + glm::dvec3(0, 5.0, 0)), -0.5); // a floating block
    // Smooth digging widens the crater rim.
    const glm::dvec3 d(20.3, 0.2, 2.1);
    World hard(ground(), editOptions()), smooth(ground(), editOptions());
    hard.dig(EditShape::path({d, d + glm::dvec3(6.0, 0.0, 0.0)}, 2.0));
    smooth.dig(EditShape::path({d, d + glm::dvec3(6.0, 0.0, 0.0)}, 2.0), 1.0);
    const glm::dvec3 rim = d + glm::dvec3(3.0, -0.3, 2.1);
    EXPECT_LT(hard.density(rim), 0.0);
    EXPECT_GT(smooth.density(rim), hard.density(rim));
    EXPECT_THROW(w.dig(EditShape::sphere(c, -1.0)), Error);
    EXPECT_THROW(w.dig(EditShape::path({}, 1.0)), Error);
    EXPECT_THROW(w.dig(EditShape::box(c, glm::dvec3(1.0), 2.0)), Error);
    EXPECT_THROW(w.dig(EditShape::sphere(c, 1.0), -0.5), Error);
}

TEST(WorldEdit, EditsSurviveEvictionAndReload)
{
    World w(ground(), editOptions());
    w.setPointsOfInterest({POI});
    w.dig(EditShape::path({glm::dvec3(-6.0, 0.0, 1.0), glm::dvec3(0.0, -2.0, 3.0), glm::dvec3(7.0, -3.0, 9.0)}, 1.5));
    w.waitIdle();
    const MeshMap first = currentMeshes(w);
    w.setPointsOfInterest({glm::dvec3(3000.0, 0.0, 0.0)});
    w.waitIdle();
    EXPECT_EQ(w.chunkMesh({0, 0, -1, 0}), nullptr); // evicted
    w.setPointsOfInterest({POI});
    w.waitIdle();
    const MeshMap second = currentMeshes(w);
    EXPECT_EQ(first.size(), second.size());
    EXPECT_TRUE(differingChunks(first, second).empty());
}

std::string readAll(const std::filesystem::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(WorldEdit, SaveAndLoadEdits)
{
    const std::filesystem::path dir = freshTestDir();
    World w(ground(), editOptions());
    w.setPointsOfInterest({POI});
    w.dig(EditShape::capsule(glm::dvec3(-4.0, 0.0, 0.0), glm::dvec3(6.0, -3.0, 5.0), 2.0), 0.5);
    w.fill(EditShape::sphere(glm::dvec3(2.0, 2.0, 2.0), 1.5));
    w.waitIdle();
    w.saveEdits(dir / "edits.vdb");
    w.saveEdits(dir / "again.vdb");
    EXPECT_EQ(readAll(dir / "edits.vdb"), readAll(dir / "again.vdb"));

    World loaded(ground(), editOptions());
    loaded.setPointsOfInterest({POI});
    loaded.waitIdle();
    const world::EditResult r = loaded.loadEdits(dir / "edits.vdb");
    EXPECT_EQ(r.changedVoxels, w.stats().editVoxels);
    EXPECT_FALSE(r.markedChunks.empty());
    loaded.waitIdle();
    EXPECT_TRUE(differingChunks(currentMeshes(w), currentMeshes(loaded)).empty());
    EXPECT_EQ(loaded.stats().editVoxels, w.stats().editVoxels);

    try {
        loaded.loadEdits(dir / "missing.vdb");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missing.vdb"), std::string::npos);
    }
    WorldOptions other = editOptions();
    other.voxelSize = 0.25;
    other.lodDistance = 14.0;
    World finer(ground(), other);
    EXPECT_THROW(finer.loadEdits(dir / "edits.vdb"), Error);
    std::ofstream(dir / "junk.vdb") << "not a vdb";
    EXPECT_THROW(loaded.loadEdits(dir / "junk.vdb"), Error);
    // A failed load leaves the edits as they were.
    EXPECT_EQ(loaded.stats().editVoxels, w.stats().editVoxels);
}

} // namespace
} // namespace strata::test
