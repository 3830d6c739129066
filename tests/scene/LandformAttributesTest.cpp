// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The landform masks per mesh vertex (strata/world/LandformAttributes.h) and
// how the pipeline carries them from the terrain's landform source to the
// layer rules and debug views, with a known stand-in for an `erode` node.

#include <strata/world/LandformAttributes.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include <strata/scene/SceneOffset.h>

#include <strata/Error.h>

#include "ErodedScene.h"
#include "TestDir.h"

#include <tbb/global_control.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace strata;
using namespace strata::scene;

namespace {

/// Known masks of the world column (x, z): flow 3.5 + x/4, wear |z|,
/// deposition |x + z|/2, water 1 east of x = 0. Counts its calls.
class KnownMasks final : public terrain::LandformMasks
{
public:
    void landformMasks(const double* x, const double* z, std::size_t n, glm::vec4* out) const override
    {
        ++calls;
        largestBlock = std::max<std::size_t>(largestBlock, n);
        for (std::size_t i = 0; i < n; ++i) out[i] = at(x[i], z[i]);
    }
    static glm::vec4 at(double x, double z)
    {
        return {float(3.5 + x / 4.0), float(std::abs(z)), float(std::abs(x + z) / 2.0), x > 0.0 ? 1.0f : 0.0f};
    }
    mutable std::atomic<int> calls{0};
    mutable std::atomic<std::size_t> largestBlock{0};
};

/// Rolling hills over a 32 m region (the eroded scene's input, no erode
/// node), small maps, with `masks` as its landform source.
Scene hillsWith(std::shared_ptr<const terrain::LandformMasks> masks)
{
    const std::string text = "seed = 3\n[terrain]\nroot = \"land\"\n" + std::string(test::ERODE_LAND) +
                             "[material]\ntexture_size = 32\nside = \"rock\"\ntop = \"grass\"\n";
    Scene scene = parseScene(text, "hills.toml");
    scene.landformMasks = std::move(masks);
    return scene;
}

/// A [[layer]] painting `tint` where the flow is at least `flowMin`.
LayerSettings riverLayer(float flowMin)
{
    LayerSettings layer;
    layer.material.name = "river";
    layer.material.side = "none";
    layer.material.top = "none";
    layer.material.parameters.albedoTint = glm::vec3(0.05f, 0.1f, 0.9f);
    layer.rule.flow = {true, flowMin, std::numeric_limits<float>::infinity(), 0.25f};
    return layer;
}

} // namespace

TEST(LandformAttributes, EachVertexReadsItsWorldColumnInDouble)
{
    meshing::TriangleMesh mesh;
    mesh.origin = glm::dvec3(1.0e6, 5.0, -2.0e6);
    for (int i = 0; i < 5000; ++i) { // several blocks and a partial one
        mesh.positions.emplace_back(float(i % 97) * 0.37f - 17.0f, float(i % 13), float(i / 97) * 0.61f - 15.0f);
    }
    KnownMasks masks;
    const std::vector<glm::vec4> out = world::computeLandformAttributes(masks, mesh);
    ASSERT_EQ(out.size(), mesh.positions.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const glm::dvec3 world = mesh.origin + glm::dvec3(mesh.positions[i]);
        ASSERT_EQ(out[i], KnownMasks::at(world.x, world.z)) << i;
    }
    EXPECT_EQ(masks.calls.load(), 5); // blocks of 1024
    EXPECT_EQ(masks.largestBlock.load(), 1024u);
    // The same values on one thread.
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        EXPECT_EQ(world::computeLandformAttributes(masks, mesh), out);
    }
    EXPECT_TRUE(world::computeLandformAttributes(masks, meshing::TriangleMesh{}).empty());
}

TEST(LandformAttributes, MeshTerrainFillsThemWhenALayerReadsThem)
{
    auto masks = std::make_shared<KnownMasks>();
    Scene scene = hillsWith(masks);
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(scene);
    EXPECT_EQ(terrain.landformMasks, scene.landformMasks);

    // No rule reads them: no landform (nor surface) on the mesh.
    const meshing::TriangleMesh plain = meshTerrain(scene, quality, terrain);
    EXPECT_TRUE(plain.landform.empty());
    EXPECT_FALSE(meshView(plain).landform);
    EXPECT_FALSE(needsLandform(scene));

    scene.material.layers.push_back(riverLayer(5.0f));
    EXPECT_TRUE(needsLandform(scene));
    const meshing::TriangleMesh mesh = meshTerrain(scene, quality, terrain);
    ASSERT_EQ(mesh.landform.size(), mesh.positions.size());
    EXPECT_TRUE(mesh.surface.empty()); // no cavity or cover band
    for (std::size_t i = 0; i < mesh.positions.size(); i += 97) {
        const glm::dvec3 world = mesh.origin + glm::dvec3(mesh.positions[i]);
        EXPECT_EQ(mesh.landform[i], KnownMasks::at(world.x, world.z)) << i;
    }
    EXPECT_EQ(meshView(mesh).landform, mesh.landform.data());

    // A landform debug view asks for them without any rule.
    scene.material.layers.clear();
    EXPECT_EQ(meshTerrain(scene, quality, terrain, nullptr, {.landform = true}).landform, mesh.landform);
}

TEST(LandformAttributes, WithoutALandformSourceTheyAreAnError)
{
    Scene scene = hillsWith(nullptr);
    EXPECT_FALSE(needsLandform(scene, "albedo"));
    try {
        needsLandform(scene, "flow");
        FAIL() << "the flow view was accepted without a landform source";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("debug view 'flow' needs the landform masks"), std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("`erode` node"), std::string::npos) << e.what();
    }
    // A scene made in code (the scene file refuses the band already).
    scene.material.layers.push_back(riverLayer(5.0f));
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(scene);
    EXPECT_THROW(meshTerrain(scene, quality, terrain), Error);
    // generate() refuses before anything is written.
    GenerateOptions options;
    options.outputDir = test::freshTestDir() / "out";
    options.snapshot = false;
    EXPECT_THROW(generate(scene, options), Error);
    EXPECT_FALSE(std::filesystem::exists(options.outputDir));
}

TEST(LandformAttributes, OffsetScenesMoveTheMasksWithTheTerrain)
{
    const Scene scene = hillsWith(std::make_shared<KnownMasks>());
    EXPECT_EQ(landformMasksForSeed(scene, std::nullopt), scene.landformMasks);
    EXPECT_EQ(landformMasksForSeed(scene, 9), scene.landformMasks); // no rebuilder: the scene's own
    const glm::dvec3 offset(1024.0, 64.0, -2048.0);
    const Scene moved = offsetScene(scene, offset);
    ASSERT_TRUE(moved.landformMasks);
    const double x[2] = {3.0 + offset.x, -7.5 + offset.x}, z[2] = {2.0 + offset.z, 11.0 + offset.z};
    glm::vec4 out[2];
    moved.landformMasks->landformMasks(x, z, 2, out);
    EXPECT_EQ(out[0], KnownMasks::at(3.0, 2.0));
    EXPECT_EQ(out[1], KnownMasks::at(-7.5, 11.0));
}

TEST(LandformAttributes, TheyReachTheLayerAndTheDebugViewsOfASnapshot)
{
    Scene scene = hillsWith(std::make_shared<KnownMasks>());
    scene.material.layers.push_back(riverLayer(4.0f)); // east of x = 2 m
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(scene);
    meshing::TriangleMesh mesh = meshTerrain(scene, quality, terrain);
    SnapshotRequest request;
    request.backend = "cpu";
    auto render = [&](const meshing::TriangleMesh& m, const std::string& view) {
        request.debugView = view;
        render::Image image;
        renderSnapshots(scene, m, request, nullptr, 1, 96, 64, std::nullopt,
                        [&image](int, const render::Image& frame) { image = frame; });
        return image;
    };
    auto differingPixels = [](const render::Image& a, const render::Image& b) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < a.pixels.size(); i += 4) {
            n += std::abs(int(a.pixels[i + 2]) - int(b.pixels[i + 2])) > 8;
        }
        return n;
    };
    // The river layer shows where the flow says so, and only there.
    const render::Image layered = render(mesh, "");
    meshing::TriangleMesh dry = mesh;
    dry.landform.assign(dry.positions.size(), glm::vec4(0.0f));
    const render::Image without = render(dry, "");
    const std::size_t changed = differingPixels(layered, without);
    EXPECT_GT(changed, 96u * 64u / 20u);
    EXPECT_LT(changed, 96u * 64u * 3u / 4u);
    // The landform views differ from one another and across the terrain.
    const render::Image flow = render(mesh, "flow");
    const render::Image water = render(mesh, "water");
    EXPECT_GT(differingPixels(flow, water), 96u * 64u / 4u);
    EXPECT_GT(differingPixels(flow, render(dry, "flow")), 96u * 64u / 4u);
}

TEST(LandformAttributes, AnErodeNodeFillsTheMeshAndFollowsTheSeed)
{
    const Scene scene =
        parseScene(test::erodedSceneToml() + "[[layer]]\nname = \"gully\"\nflow_min = 2.5\n", "eroded.toml");
    ASSERT_TRUE(scene.landformMasks);
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(scene);
    const meshing::TriangleMesh mesh = meshTerrain(scene, quality, terrain);
    ASSERT_EQ(mesh.landform.size(), mesh.positions.size());
    EXPECT_EQ(world::computeLandformAttributes(*scene.landformMasks, mesh), mesh.landform);
    float flowLo = 1e30f, flowHi = -1e30f;
    for (const glm::vec4& m : mesh.landform) {
        ASSERT_TRUE(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z) && std::isfinite(m.w));
        EXPECT_GE(m.y, 0.0f);
        EXPECT_GE(m.z, 0.0f);
        EXPECT_TRUE(m.w >= 0.0f && m.w <= 1.0f) << m.w;
        flowLo = std::min(flowLo, m.x);
        flowHi = std::max(flowHi, m.x);
    }
    EXPECT_GT(flowHi, flowLo + 0.5f); // ridges and gullies
    // Another seed: the masks of the rebuilt tree, the same node as its root.
    const SampledTerrain other = sampleTerrain(scene, 8);
    ASSERT_TRUE(other.landformMasks);
    EXPECT_NE(other.landformMasks, scene.landformMasks);
    EXPECT_EQ(dynamic_cast<const terrain::DensityField*>(other.landformMasks.get()), other.field.get());
}
