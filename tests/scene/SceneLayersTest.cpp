// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The [[layer]] tables and `pbr` folders of the scene file (SceneMaterial.cpp).

#include <strata/scene/Scene.h>
#include <strata/scene/Quality.h>
#include <strata/scene/SceneMaterial.h>

#include <strata/Error.h>

#include "ErodedScene.h"
#include "SceneParseError.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iterator>
#include <set>
#include <string>

using strata::scene::parseScene;
using strata::scene::Scene;

namespace {

using strata::test::parseError;

const char* const FOUR_LAYERS = R"(
[material]
side = "rock"
top = "none"
layer_blend_depth = 0.3

[materials.wet]
side = "soil"
smoothness = 0.8

[[layer]]
name = "sand"
side = "sand"
altitude_max = 5
altitude_softness = 2
cavity_min = 0.2

[[layer]]
use = "wet"
cover_min = 0.5
cover_softness = 0

[[layer]]
name = "snow"
side = "snow"
map_scale = 0.25
altitude_min = 120
slope_max = 35
noise_scale = 40
noise_threshold = 0.3
noise_seed = 9
opacity = 0.9
)";

} // namespace

TEST(SceneLayers, FourLayersAreReadInOrderWithTheirRules)
{
    const Scene scene = parseScene(FOUR_LAYERS, "layers.toml");
    const auto& layers = scene.material.layers;
    ASSERT_EQ(layers.size(), 3u);
    EXPECT_FLOAT_EQ(scene.material.parameters.layerBlendDepth, 0.3f);
    EXPECT_EQ(layers[0].material.name, "sand");
    EXPECT_EQ(layers[0].material.side, "sand");
    EXPECT_EQ(layers[0].material.top, "none");
    EXPECT_TRUE(layers[0].rule.altitude.enabled);
    EXPECT_TRUE(std::isinf(layers[0].rule.altitude.min));
    EXPECT_FLOAT_EQ(layers[0].rule.altitude.max, 5.0f);
    EXPECT_FLOAT_EQ(layers[0].rule.altitude.softness, 2.0f);
    EXPECT_TRUE(layers[0].rule.cavity.enabled);
    EXPECT_FALSE(layers[0].rule.slope.enabled);
    EXPECT_EQ(layers[1].material.name, "wet");
    EXPECT_EQ(layers[1].material.side, "soil");
    EXPECT_FLOAT_EQ(layers[1].material.parameters.smoothness, 0.8f);
    EXPECT_FLOAT_EQ(layers[1].rule.cover.softness, 0.0f);
    EXPECT_FLOAT_EQ(layers[2].rule.noiseFrequency, 1.0f / 40.0f);
    EXPECT_EQ(layers[2].rule.noiseSeed, 9u);
    EXPECT_FLOAT_EQ(layers[2].rule.opacity, 0.9f);
    EXPECT_FLOAT_EQ(layers[2].material.parameters.mapScale, 0.25f);

    const strata::render::Material m = strata::scene::buildMaterial(scene.material);
    ASSERT_EQ(m.layers.size(), 3u);
    EXPECT_EQ(m.layers[2].name, "snow");
    EXPECT_TRUE(m.layers[2].material.albedo);
    EXPECT_TRUE(strata::render::materialFeatures(m) & strata::render::feature::LAYERS);
}

TEST(SceneLayers, ErrorsNameFileLineAndKey)
{
    EXPECT_EQ(parseError("[[layer]]\nslope_min = 40\nslope_max = 20\n"),
              "test.toml:3: layer[1].slope_max = 20 must be >= slope_min (40)");
    EXPECT_EQ(parseError("[[layer]]\nname = \"a\"\n[[layer]]\nopacity = 2\n"),
              "test.toml:4: layer[2].opacity = 2 is out of range [0, 1]");
    EXPECT_EQ(parseError("[[layer]]\nslope = 30\n"), "test.toml:2: unknown key 'layer[1].slope'");
    EXPECT_EQ(parseError("layer = 3\n"), "test.toml:1: layer = 3 must be an array of tables ([[layer]] ... )");
    std::string eight;
    for (int i = 0; i < 8; ++i) eight += "[[layer]]\n";
    EXPECT_NE(parseError(eight).find("at most 7 layers over [material]"), std::string::npos);
    EXPECT_EQ(parseError("[[layer]]\nuse = \"none\"\n"), "test.toml:2: layer[1].use = 'none': no [materials.none] table");
    EXPECT_EQ(parseError("[material]\nlayer_blend_depth = 0\n"),
              "test.toml:2: material.layer_blend_depth = 0 is out of range [0.001, 100]");
    EXPECT_EQ(parseError("[[layer]]\npbr = \"/nonexistent/set\"\n"),
              "test.toml:2: layer[1].pbr = '/nonexistent/set': no such folder (a PBR texture set)");
    EXPECT_EQ(parseError("[material]\npbr_max_size = 1000\n"),
              "test.toml:2: material.pbr_max_size = 1000 must be 0 (keep) or a power of two");
}

TEST(SceneLayers, PbrFoldersOfTheDocsLoadAsLayers)
{
    const std::filesystem::path docs = std::filesystem::path(STRATA_SOURCE_DIR) / "docs";
    const Scene scene = strata::scene::loadScene(docs / "layers-landscape.toml");
    ASSERT_EQ(scene.material.layers.size(), 3u);
    const strata::render::Material m = strata::scene::buildMaterial(scene.material);
    ASSERT_TRUE(m.albedo && m.mask && m.normal);
    for (const auto& layer : m.layers) {
        EXPECT_TRUE(layer.material.albedo && layer.material.mask && layer.material.normal) << layer.name;
        EXPECT_LE(layer.material.albedo->width(), 512) << layer.name;
    }
}

TEST(SceneLayers, MaterialQualityKnobsReachEveryLayer)
{
    const Scene scene = parseScene(FOUR_LAYERS, "layers.toml");
    strata::scene::QualityOverrides flags;
    strata::scene::addQualityFlag("anti_tiling=on", flags);
    strata::scene::addQualityFlag("projections=2", flags);
    const Scene applied = strata::scene::applyQuality(scene, strata::scene::resolveQuality(scene, std::nullopt, flags));
    EXPECT_TRUE(applied.material.parameters.antiTiling);
    for (const auto& layer : applied.material.layers) {
        EXPECT_TRUE(layer.material.parameters.antiTiling) << layer.material.name;
        EXPECT_EQ(layer.material.parameters.projections, 2) << layer.material.name;
    }
}


TEST(SceneLayers, LandformBandsNeedAnErodeNode)
{
    // Without a landform source, any flow, wear, deposition or water bound
    // is an error at its key.
    EXPECT_EQ(parseError("[[layer]]\nname = \"river\"\nflow_min = 5\n"),
              "test.toml:3: layer[1].flow_min = 5 needs the landform masks of erosion: add an `erode` node to the "
              "terrain tree ([terrain.nodes]), or remove the flow band");
    for (const char* key : {"wear_max", "deposition_min", "water_min"}) {
        const std::string message = parseError("[[layer]]\n[[layer]]\n" + std::string(key) + " = 0.5\n");
        EXPECT_NE(message.find("test.toml:3: layer[2]." + std::string(key) + " = 0.5 needs the landform masks"),
                  std::string::npos)
            << message;
        EXPECT_NE(message.find("`erode` node"), std::string::npos) << message;
    }
    // A softness alone enables nothing: no error, no band.
    const Scene soft = parseScene("[[layer]]\nflow_softness = 2\n", "soft.toml");
    EXPECT_FALSE(soft.material.layers.at(0).rule.flow.enabled);
    EXPECT_FALSE(soft.landformMasks);
    EXPECT_FALSE(soft.buildLandformMasks);
}

TEST(SceneLayers, LandformBandRangesNameTheirKeys)
{
    // Checked before the landform source: the bad value is the first error.
    EXPECT_EQ(parseError("[[layer]]\nflow_min = 5\nflow_max = 2\n"),
              "test.toml:3: layer[1].flow_max = 2 must be >= flow_min (5)");
    EXPECT_EQ(parseError("[[layer]]\nwater_max = 2\n"), "test.toml:2: layer[1].water_max = 2 is out of range [-1, 1]");
    EXPECT_EQ(parseError("[[layer]]\ndeposition_softness = -1\n"),
              "test.toml:2: layer[1].deposition_softness = -1 is out of range [0, 10000]");
    EXPECT_EQ(parseError("[[layer]]\nwear_min = \"deep\"\n"),
              "test.toml:2: layer[1].wear_min = 'deep' must be a number");
    EXPECT_EQ(parseError("[[layer]]\nflow = 5\n"), "test.toml:2: unknown key 'layer[1].flow'");
    // Every band key is listed.
    std::set<std::string> keys(std::begin(strata::scene::LAYER_RULE_KEYS), std::end(strata::scene::LAYER_RULE_KEYS));
    for (const char* band : {"flow", "wear", "deposition", "water"}) {
        for (const char* part : {"_min", "_max", "_softness"}) EXPECT_EQ(keys.count(std::string(band) + part), 1u);
    }
}

TEST(SceneLayers, TerrainMasksMustNameANodeWithMasks)
{
    const std::string tree = "[terrain]\nroot = \"land\"\nmasks = \"land\"\n" + std::string(strata::test::ERODE_LAND);
    EXPECT_EQ(parseError(tree), "test.toml:3: terrain.masks = 'land' is not a node with landform masks: the tree has "
                                "none (add an `erode` node)");
    // Only the node form has a tree to pick from.
    EXPECT_EQ(parseError("[terrain]\nmasks = \"a\"\n[terrain.height]\namplitude = 3.0\n"),
              "test.toml:2: unknown key 'terrain.masks'");
}

TEST(SceneLayers, AnErodeNodeIsTheLandformSource)
{
    const std::string text =
        strata::test::erodedSceneToml() + "[[layer]]\nname = \"river\"\nflow_min = 4\nwater_min = 0.5\nwear_max = 3\n";
    const Scene scene = parseScene(text, "eroded.toml");
    ASSERT_TRUE(scene.landformMasks);
    ASSERT_TRUE(scene.buildLandformMasks);
    const strata::render::LayerRule& rule = scene.material.layers.at(0).rule;
    EXPECT_TRUE(rule.flow.enabled);
    EXPECT_FLOAT_EQ(rule.flow.min, 4.0f);
    EXPECT_FLOAT_EQ(rule.flow.softness, 0.5f);
    EXPECT_TRUE(rule.water.enabled);
    EXPECT_FLOAT_EQ(rule.wear.max, 3.0f);
    EXPECT_FALSE(rule.deposition.enabled);
    // The masks are the erode node's: the root itself here.
    EXPECT_EQ(dynamic_cast<const strata::terrain::DensityField*>(scene.landformMasks.get()), scene.field.get());
    const double x = 3.0, z = -2.0;
    glm::vec4 own, again;
    scene.landformMasks->landformMasks(&x, &z, 1, &own);
    scene.buildLandformMasks(scene.terrain.seed)->landformMasks(&x, &z, 1, &again);
    EXPECT_EQ(own, again);
}

TEST(SceneLayers, SeveralErodeNodesNeedTerrainMasks)
{
    const std::string tree = "[terrain]\nroot = \"both\"\n%MASKS%[terrain.nodes.both]\ntype = \"union\"\n"
                             "children = [\"valley\", \"gorge\"]\n" +
                             strata::test::erodeNodeToml("valley", "land") +
                             strata::test::erodeNodeToml("gorge", "land") + strata::test::ERODE_LAND;
    auto withMasks = [&tree](const std::string& masks) {
        std::string text = tree;
        text.replace(text.find("%MASKS%"), 7, masks);
        return text;
    };
    EXPECT_EQ(parseError(withMasks("")),
              "test.toml:1: terrain.masks is required: the tree has 2 nodes with landform masks ('gorge', "
              "'valley'); name the one layer rules read, e.g. masks = 'gorge'");
    EXPECT_EQ(parseError(withMasks("masks = \"land\"\n")),
              "test.toml:3: terrain.masks = 'land' is not a node with landform masks (one of 'gorge', 'valley')");
    const Scene scene = parseScene(withMasks("masks = \"valley\"\n") + "[[layer]]\nwater_min = 0.5\n", "two.toml");
    EXPECT_TRUE(scene.landformMasks);
    EXPECT_TRUE(scene.material.layers.at(0).rule.water.enabled);
}
