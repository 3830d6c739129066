// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The rock masks per mesh vertex (strata/world/LandformAttributes.h,
// computeRockAttributes) and how the pipeline carries them from a `beds`
// node to the layer rules, the debug views, offset scenes and other seeds.

#include <strata/world/LandformAttributes.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include <strata/scene/Bake.h>
#include <strata/scene/SceneOffset.h>
#include <strata/meshing/GltfIO.h>

#include <strata/Error.h>

#include "TestDir.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace strata;
using namespace strata::scene;

namespace {

/// Known rock at (x, y, z): hardness frac(y / 10), bed floor(y / 10) + a
/// thousandth of x (so x and z count too), in double. Counts its calls.
class KnownRock final : public terrain::RockMasks
{
public:
    void rockMasks(const double* x, const double* y, const double* z, std::size_t n, glm::vec2* out) const override
    {
        ++calls;
        for (std::size_t i = 0; i < n; ++i) out[i] = at(x[i], y[i], z[i]);
    }
    static glm::vec2 at(double x, double y, double z)
    {
        const double s = y / 10.0;
        return {float(s - std::floor(s)), float(std::floor(s) + x * 1e-3 + z * 1e-6)};
    }
    mutable std::atomic<int> calls{0};
};

/// A ball of 20 m cut into beds 4 m (soft, 0.2) and 6 m (hard, 0.9) thick,
/// over a 48 m region at 1 m voxels; `extra` is appended (layers, keys).
std::string bedsScene(const std::string& terrainKeys = "", const std::string& extra = "")
{
    return "seed = 5\n[sampling]\nvoxel_size = 1.0\n[region]\nmin = [-24, -24, -24]\nmax = [24, 24, 24]\n"
           "[terrain]\nroot = \"rock\"\n" + terrainKeys +
           "[terrain.nodes.rock]\ntype = \"beds\"\nchild = \"ball\"\nbeds = [[4, 0.2], [6, 0.9]]\nretreat = 2\n"
           "fold_amplitude = 3\nfold_wavelength = 40\n"
           "[terrain.nodes.ball]\ntype = \"sphere\"\nradius = 20\n"
           "[material]\ntexture_size = 32\nside = \"rock\"\ntop = \"none\"\n" + extra;
}

const char* CAPROCK_LAYER = "[[layer]]\nside = \"none\"\ntop = \"none\"\nalbedo_tint = [0.9, 0.3, 0.05]\nhardness_min = 0.6\n";

} // namespace

TEST(RockAttributes, EachVertexReadsItsWorldPointInDoubleOnAnyThreadCount)
{
    // Far from the origin, where float positions alone would lose the
    // metres: the masks read origin + position in double.
    meshing::TriangleMesh mesh;
    mesh.origin = glm::dvec3(1e6, -3e5, 2e6);
    for (int i = 0; i < 5000; ++i)
        mesh.positions.push_back(glm::vec3(float(i % 97) * 0.25f, float(i % 13) * 3.5f, float(i / 97) * 0.5f));
    const KnownRock rock;
    std::vector<glm::vec2> one, three;
    {
        tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
        one = world::computeRockAttributes(rock, mesh);
    }
    {
        tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 3);
        three = world::computeRockAttributes(rock, mesh);
    }
    ASSERT_EQ(one.size(), mesh.positions.size());
    EXPECT_EQ(rock.calls.load(), 2 * 5); // blocks of 1024 vertices
    for (std::size_t i = 0; i < one.size(); ++i) {
        const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
        ASSERT_EQ(one[i], KnownRock::at(p.x, p.y, p.z)) << i;
        ASSERT_EQ(one[i], three[i]) << i;
    }
}

TEST(RockAttributes, ABedsNodeFillsTheMeshWhenALayerReadsThem)
{
    const Scene plain = parseScene(bedsScene(), "beds.toml");
    ASSERT_TRUE(plain.rockMasks);
    const SampledTerrain sampled = sampleTerrain(plain);
    ASSERT_TRUE(sampled.rockMasks);
    // No layer reads them: the mesh goes without.
    const QualitySettings quality = resolveQuality(plain, std::nullopt, {});
    EXPECT_TRUE(meshTerrain(plain, quality, sampled).rock.empty());
    EXPECT_TRUE(meshTerrain(plain, quality, sampled, nullptr, {.rock = true}).rock.size() > 0); // a rock view
    // A caprock layer: every vertex carries the beds node's hardness and bed at its world point.
    const Scene scene = parseScene(bedsScene("", CAPROCK_LAYER), "beds.toml");
    const meshing::TriangleMesh mesh = meshTerrain(scene, quality, sampleTerrain(scene));
    ASSERT_EQ(mesh.rock.size(), mesh.positions.size());
    int hard = 0, soft = 0;
    std::vector<int> beds(2, 0);
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
        glm::vec2 expected;
        scene.rockMasks->rockMasks(&p.x, &p.y, &p.z, 1, &expected);
        ASSERT_EQ(mesh.rock[i], expected) << i;
        ASSERT_GE(mesh.rock[i].x, 0.2f - 1e-6f);
        ASSERT_LE(mesh.rock[i].x, 0.9f + 1e-6f);
        ASSERT_TRUE(mesh.rock[i].y == 0.0f || mesh.rock[i].y == 1.0f) << mesh.rock[i].y;
        hard += mesh.rock[i].x > 0.85f;
        soft += mesh.rock[i].x < 0.25f;
        ++beds[std::size_t(mesh.rock[i].y)];
    }
    // A 40 m ball crosses several beds of each kind.
    EXPECT_GT(hard, int(mesh.positions.size() / 10));
    EXPECT_GT(soft, int(mesh.positions.size() / 10));
    EXPECT_GT(beds[0], 0);
    EXPECT_GT(beds[1], 0);
    // Another seed moves the folds: the masks follow the tree rebuilt for it.
    const SampledTerrain other = sampleTerrain(scene, 99);
    ASSERT_TRUE(other.rockMasks);
    int moved = 0;
    for (double y = -20.0; y <= 20.0; y += 0.37) {
        const glm::dvec3 q(3.0, y, -2.0);
        glm::vec2 a, b;
        scene.rockMasks->rockMasks(&q.x, &q.y, &q.z, 1, &a);
        other.rockMasks->rockMasks(&q.x, &q.y, &q.z, 1, &b);
        moved += a != b;
    }
    EXPECT_GT(moved, 5);
}

TEST(RockAttributes, WithoutABedsNodeTheBandsAndViewsAreRefusedByName)
{
    const std::string noBeds = "[terrain]\nroot = \"ball\"\n[terrain.nodes.ball]\ntype = \"sphere\"\n"
                               "[material]\nside = \"rock\"\n[[layer]]\nbed_min = 2\n";
    try {
        parseScene(noBeds, "ball.toml");
        FAIL() << "a bed band without a beds node was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("ball.toml:8: layer[1].bed_min = 2 needs the rock masks of rock beds: "
                                             "add a `beds` node"),
                  std::string::npos)
            << e.what();
    }
    const Scene ball = parseScene("[terrain]\nroot = \"ball\"\n[terrain.nodes.ball]\ntype = \"sphere\"\n", "ball.toml");
    EXPECT_FALSE(ball.rockMasks);
    EXPECT_FALSE(needsRock(ball));
    try {
        needsRock(ball, "hardness");
        FAIL() << "the hardness view without a beds node was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("the debug view 'hardness' needs the rock masks"), std::string::npos)
            << e.what();
    }
    // `[terrain] rock` must name a beds node.
    try {
        parseScene(bedsScene("rock = \"ball\"\n"), "beds.toml");
        FAIL() << "rock = 'ball' was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("terrain.rock = 'ball' is not a node with rock masks (one of 'rock')"),
                  std::string::npos)
            << e.what();
    }
    EXPECT_TRUE(parseScene(bedsScene("rock = \"rock\"\n"), "beds.toml").rockMasks);
    // The views need them even without a layer.
    const Scene beds = parseScene(bedsScene(), "beds.toml");
    EXPECT_TRUE(needsRock(beds, "bed"));
    EXPECT_FALSE(needsRock(beds, "flow"));
    EXPECT_TRUE(neededMasks(beds, "hardness").rock);
}

TEST(RockAttributes, OffsetScenesMoveTheMasksWithTheTerrain)
{
    const Scene scene = parseScene(bedsScene(), "beds.toml");
    const glm::dvec3 offset(1e5, -40.0, 3e5);
    const Scene moved = offsetScene(scene, offset);
    ASSERT_TRUE(moved.rockMasks);
    ASSERT_TRUE(moved.buildRockMasks);
    const auto reseeded = rockMasksForSeed(moved, 7);
    const auto reseededHere = rockMasksForSeed(scene, 7);
    for (const glm::dvec3& p : {glm::dvec3(0.0, 0.0, 0.0), glm::dvec3(3.5, 11.25, -7.0), glm::dvec3(-19.0, 4.0, 2.0)}) {
        const glm::dvec3 q = p + offset;
        glm::vec2 here, there, hereOther, thereOther;
        scene.rockMasks->rockMasks(&p.x, &p.y, &p.z, 1, &here);
        moved.rockMasks->rockMasks(&q.x, &q.y, &q.z, 1, &there);
        reseededHere->rockMasks(&p.x, &p.y, &p.z, 1, &hereOther);
        reseeded->rockMasks(&q.x, &q.y, &q.z, 1, &thereOther);
        EXPECT_EQ(here, there);
        EXPECT_EQ(hereOther, thereOther);
    }
}

TEST(RockAttributes, BakedTilesCarryThemAtEveryVertex)
{
    // Plain tiles keep the float positions the masks were taken at, so each
    // vertex's masks can be checked against the beds node at its world point.
    const Scene scene = parseScene(bedsScene("", CAPROCK_LAYER), "beds.toml");
    const std::filesystem::path dir = test::freshTestDir();
    BakeOptions options;
    options.tileSize = 16.0;
    options.lods = 2;
    options.threads = 2;
    options.grids = false;
    options.tileFormat = TileFormat::Plain;
    options.outputDir = dir;
    bake(scene, options, planBake(scene, options));
    std::size_t tiles = 0, vertices = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
        if (entry.path().extension() != ".glb") continue;
        const meshing::TriangleMesh mesh = meshing::readGltf(entry.path());
        if (mesh.positions.empty()) continue;
        ++tiles;
        ASSERT_EQ(mesh.rock.size(), mesh.positions.size()) << entry.path();
        for (std::size_t i = 0; i < mesh.positions.size(); ++i, ++vertices) {
            const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
            glm::vec2 expected;
            scene.rockMasks->rockMasks(&p.x, &p.y, &p.z, 1, &expected);
            ASSERT_EQ(mesh.rock[i], expected) << entry.path() << " vertex " << i;
        }
    }
    EXPECT_GT(tiles, 8u);
    EXPECT_GT(vertices, 1000u);
}
