// The [[layer]] tables and `pbr` folders of the scene file (SceneMaterial.cpp).

#include <strata/scene/Scene.h>
#include <strata/scene/Quality.h>
#include <strata/scene/SceneMaterial.h>

#include <strata/Error.h>

#include "SceneParseError.h"

#include <gtest/gtest.h>

#include <filesystem>
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
