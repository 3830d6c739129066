// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Scene.h>

#include <strata/Error.h>

#include <glm/trigonometric.hpp>
#include "SceneParseError.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using strata::scene::parseScene;
using strata::scene::Scene;

namespace {

using strata::test::parseError;

} // namespace

TEST(Scene, DefaultSceneParses)
{
    const Scene scene = parseScene(strata::scene::defaultSceneText(), "<default scene>");
    EXPECT_EQ(scene.terrain.seed, 1u);
    EXPECT_DOUBLE_EQ(scene.voxelSize, 0.5);
    EXPECT_GE(scene.halfWidth, 3);
    EXPECT_TRUE(scene.terrain.caves.enabled);
    EXPECT_LT(scene.region.min.x, scene.region.max.x);
    EXPECT_EQ(scene.snapshot.width, 1280);
}

TEST(Scene, EmptySceneUsesDefaults)
{
    const Scene scene = parseScene("", "empty.toml");
    EXPECT_DOUBLE_EQ(scene.voxelSize, 0.5);
    EXPECT_EQ(scene.terrain.height.fbm.octaves, strata::terrain::HeightfieldOptions{}.fbm.octaves);
}

TEST(Scene, ValuesAreRead)
{
    const Scene scene = parseScene(R"(
seed = 99
[sampling]
voxel_size = 0.25
[terrain.height]
octaves = 3
[terrain.caves]
enabled = false
[camera]
position = [1, 2, 3]
target = [0, 0, 0]
)", "t.toml");
    EXPECT_EQ(scene.terrain.seed, 99u);
    EXPECT_DOUBLE_EQ(scene.voxelSize, 0.25);
    EXPECT_EQ(scene.terrain.height.fbm.octaves, 3);
    EXPECT_FALSE(scene.terrain.caves.enabled);
    ASSERT_TRUE(scene.camera.position.has_value());
    EXPECT_EQ(*scene.camera.position, glm::dvec3(1, 2, 3));
}

TEST(Scene, ErrorsNameFileLineAndKey)
{
    EXPECT_EQ(parseError("[sampling]\nvoxel_size = -1\n"),
              "test.toml:2: sampling.voxel_size = -1 is out of range [0.0001, 10000]");
    EXPECT_EQ(parseError("[sampling]\nvoxel_size = nan\n"), "test.toml:2: sampling.voxel_size = nan must be finite");
    EXPECT_EQ(parseError("[sampling]\nvoxel_size = inf\n"), "test.toml:2: sampling.voxel_size = inf must be finite");
    EXPECT_EQ(parseError("seed = 1\n[terrain.height]\noctaves = 100\n"),
              "test.toml:3: terrain.height.octaves = 100 is out of range [1, 24]");
    EXPECT_EQ(parseError("[terrain.height]\noctaves = 2.5\n"), "test.toml:2: terrain.height.octaves = 2.5 must be an integer");
    EXPECT_EQ(parseError("[terrain.caves]\nradiuss = 2\n"), "test.toml:2: unknown key 'terrain.caves.radiuss'");
    EXPECT_EQ(parseError("seeds = 2\n"), "test.toml:1: unknown key 'seeds'");
    EXPECT_EQ(parseError("[camera]\nposition = [1, 2]\n"),
              "test.toml:2: camera.position = [ 1, 2 ] must be an array of three numbers [x, y, z]");
    EXPECT_EQ(parseError("[material]\ntexture_size = 300\n"), "test.toml:2: material.texture_size = 300 must be a power of two");
    EXPECT_EQ(parseError("[region]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n"),
              "test.toml:3: region.max must be greater than region.min on every axis (axis y: 0 >= 0)");
}

TEST(Scene, NoiseVersionIsChosenPerSceneAndVersion1StaysTheDefault)
{
    const Scene unversioned = parseScene("", "a.toml");
    const Scene one = parseScene("noise_version = 1\n", "b.toml");
    const Scene two = parseScene("noise_version = 2\n", "c.toml");
    EXPECT_EQ(unversioned.noiseVersion, 1);
    EXPECT_EQ(two.noiseVersion, 2);
    int differ = 0;
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 p(-90.0 + 2.9 * i, -20.0 + 0.6 * i, 70.0 - 2.3 * i);
        const double a = unversioned.field->density(p), b = one.field->density(p), c = two.field->density(p);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "a scene without the key is version 1, bit for bit";
        differ += a != c;
        EXPECT_TRUE(std::isfinite(c));
    }
    EXPECT_GT(differ, 24) << "version 2 is another pattern";
    // Rebuilt for another seed, the tree keeps its version.
    const auto oneAt5 = one.buildField(5), twoAt5 = two.buildField(5);
    int differAt5 = 0;
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 p(-90.0 + 2.9 * i, -20.0 + 0.6 * i, 70.0 - 2.3 * i);
        differAt5 += oneAt5->density(p) != twoAt5->density(p);
    }
    EXPECT_GT(differAt5, 24);
}

TEST(Scene, NoiseVersionErrorsNameTheKey)
{
    EXPECT_EQ(parseError("seed = 1\nnoise_version = 3\n"), "test.toml:2: noise_version = 3 is out of range [1, 2]");
}

TEST(Scene, TheShorthandTakesTheNoiseVersion)
{
    // [terrain.height] and [terrain.caves] (TerrainField) at version 2: another
    // pattern than version 1, kept when the field is rebuilt for another seed.
    const std::string text = "[terrain.height]\noctaves = 3\n[terrain.caves]\nradius = 6.0\n";
    const Scene one = parseScene(text, "one.toml");
    const Scene two = parseScene("noise_version = 2\n" + text, "two.toml");
    EXPECT_EQ(one.terrain.noiseVersion, 1);
    EXPECT_EQ(two.terrain.noiseVersion, 2);
    int differ = 0, differAt5 = 0;
    const auto oneAt5 = one.buildField(5), twoAt5 = two.buildField(5);
    for (int i = 0; i < 64; ++i) {
        const glm::dvec3 p(-90.0 + 2.9 * i, -20.0 + 0.6 * i, 70.0 - 2.3 * i);
        differ += one.field->density(p) != two.field->density(p);
        differAt5 += oneAt5->density(p) != twoAt5->density(p);
        EXPECT_TRUE(std::isfinite(two.field->density(p)));
    }
    EXPECT_GT(differ, 24);
    EXPECT_GT(differAt5, 24);
}

TEST(Scene, SyntaxErrorsGiveTheLine)
{
    const std::string message = parseError("seed = 1\n[sampling\nvoxel_size = 1\n");
    EXPECT_EQ(message.rfind("test.toml:2: ", 0), 0u) << message;
}

TEST(Scene, MissingFileIsAnError)
{
    EXPECT_THROW(strata::scene::loadScene("/nonexistent/scene.toml"), strata::Error);
}

// --- Materials (SceneMaterial.cpp) ---------------------------------------------

#include <strata/scene/SceneMaterial.h>
#include "TestDir.h"

#include <strata/render/Image.h>
#include <strata/render/Material.h>

#include <fstream>

TEST(SceneMaterial, DefaultSceneIsRockWithGrassTopsAndHeightBlending)
{
    const Scene scene = parseScene(strata::scene::defaultSceneText(), "<default scene>");
    EXPECT_EQ(scene.material.side, "rock");
    EXPECT_EQ(scene.material.top, "grass");
    const strata::render::Material m = strata::scene::buildMaterial(scene.material);
    namespace f = strata::render::feature;
    EXPECT_EQ(strata::render::materialFeatures(m), f::MASK_MAP | f::HEIGHT_BLEND | f::NORMAL_MAP | f::TOP_MAPS);
}

TEST(SceneMaterial, EveryParameterIsRead)
{
    const Scene scene = parseScene(R"(
[material]
side = "circuitry"
top = "none"
detail = "sand"
emission = "circuitry"
detail_normals = true
height_strength = 0.99
normal_blend = "rnm"
normal_strength = 0.5
occlusion_strength = 0.25
metallic = 0.5
smoothness = 0.75
mask_layout = "mods"
detail_scale = 8.0
detail_albedo = 0.3
detail_smoothness = 0.4
detail_normal_strength = 0.6
detail_fade_start = 2
detail_fade_end = 4
emission_color = [4.0, 2.0, 1.0]
albedo_tint = [1.0, 0.9, 0.8]
fresnel_strength = 0.5
texture_size = 64
)",
                                   "m.toml");
    const strata::scene::MaterialSettings& s = scene.material;
    const strata::render::Material& p = s.parameters;
    EXPECT_EQ(s.side, "circuitry");
    EXPECT_EQ(s.top, "none");
    EXPECT_FLOAT_EQ(p.heightStrength, 0.99f);
    EXPECT_EQ(p.normalBlend, strata::render::NormalBlend::Rnm);
    EXPECT_EQ(p.maskLayout, strata::render::MaskLayout::Mods);
    EXPECT_FLOAT_EQ(p.detailScale, 8.0f);
    EXPECT_FLOAT_EQ(p.emissionColor.x, 4.0f);
    EXPECT_FLOAT_EQ(p.albedoTint.z, 0.8f);
    EXPECT_FLOAT_EQ(s.detailFadeEnd, 4.0f);
    const strata::render::Material m = strata::scene::buildMaterial(s);
    namespace f = strata::render::feature;
    EXPECT_EQ(strata::render::materialFeatures(m), f::MASK_MAP | f::MODS | f::NORMAL_MAP | f::DETAIL |
                                                       f::DETAIL_NORMAL | f::EMISSION | f::NORMAL_RNM);
}

TEST(SceneMaterial, NamedMaterialsAreSelectedWithUse)
{
    const Scene scene = parseScene(R"(
[materials.desert]
side = "sand"
top = "none"
blend_exponent = 8.0

[material]
use = "desert"
map_scale = 0.5
)",
                                   "m.toml");
    EXPECT_EQ(scene.material.name, "desert");
    EXPECT_EQ(scene.material.side, "sand");
    EXPECT_FLOAT_EQ(scene.material.parameters.blendExponent, 8.0f);
    EXPECT_FLOAT_EQ(scene.material.parameters.mapScale, 0.5f);
    EXPECT_EQ(parseError("[material]\nuse = \"nope\"\n"), "test.toml:2: material.use = 'nope': no [materials.nope] table");
}

TEST(SceneMaterial, ErrorsNameFileLineKeyMaterialAndMap)
{
    EXPECT_EQ(parseError("[material]\nheight_strength = 1.0\n"),
              "test.toml:2: material.height_strength = 1 is out of range [0, 0.99]");
    EXPECT_EQ(parseError("[material]\nside = \"marble\"\n"),
              "test.toml:2: material.side = 'marble' is not a built-in texture set (rock, grass, soil, sand, snow, "
              "circuitry or none)");
    EXPECT_EQ(parseError("[material]\nnormal_blend = \"best\"\n"),
              "test.toml:2: material.normal_blend = 'best' must be \"whiteout\", \"udn\" or \"rnm\"");
    EXPECT_EQ(parseError("[materials.a]\nblend_offset = 0.7\n"),
              "test.toml:2: materials.a.blend_offset = 0.7 is out of range [0, 0.5]");
    EXPECT_EQ(parseError("[material.maps.normal]\nfile = \"/nonexistent/n.png\"\n"),
              "test.toml:2: material.maps.normal.file = '/nonexistent/n.png': no such file (material 'material', map "
              "normal)");
    EXPECT_EQ(parseError("[material.maps.albedo]\nfile = \"a.png\"\ncolour = 1\n"),
              "test.toml:3: unknown key 'material.maps.albedo.colour'");
    EXPECT_EQ(parseError("[material.maps.mask]\nfile = \"a.png\"\nchannels = [\"r\", \"q\", \"b\", \"a\"]\n"),
              "test.toml:3: material.maps.mask.channels = 'q' must be r, g, b, a, 0, 1 or 1-r, 1-g, 1-b, 1-a");
    EXPECT_EQ(parseError("[material.maps.bump]\nfile = \"a.png\"\n"), "test.toml:1: unknown key 'material.maps.bump'");
}

TEST(SceneMaterial, MapFilesAreLoadedRemappedAndChecked)
{
    const auto dir = strata::test::freshTestDir();
    strata::render::Image rgb;
    rgb.width = 4;
    rgb.height = 4;
    rgb.pixels.assign(4 * 4 * 4, 200);
    strata::render::writeImage(rgb, dir / "rgba.png");
    strata::render::writeImage(rgb, dir / "rgb.jpg"); // three channels
    {
        std::ofstream(dir / "broken.png") << "not an image";
    }
    auto scene = [&](const std::string& maps) {
        std::ofstream(dir / "scene.toml") << "[material]\n" << maps;
        return strata::scene::loadScene(dir / "scene.toml");
    };
    // A gloss map's R as smoothness, height from a normal map's alpha.
    const Scene ok = scene("[material.maps.mask]\nmetallic = \"rgba.png\"\nheight = \"rgba.png\"\nheight_channel = \"a\"\n"
                           "smoothness = \"rgba.png\"\nsmoothness_channel = \"1-r\"\n"
                           "[material.maps.normal]\nfile = \"rgba.png\"\nconvention = \"directx\"\n");
    const strata::render::Material m = strata::scene::buildMaterial(ok.material);
    ASSERT_TRUE(m.mask);
    const std::uint8_t* mohs = m.mask->levels[0].texels.data();
    EXPECT_EQ(mohs[0], 200);     // metallic
    EXPECT_EQ(mohs[1], 255);     // occlusion default
    EXPECT_EQ(mohs[2], 200);     // height from alpha
    EXPECT_EQ(mohs[3], 55);      // 1 − roughness
    EXPECT_EQ(m.normal->levels[0].texels[1], 55); // DirectX green flipped

    const Scene alpha = scene("[material.maps.mask]\nfile = \"rgb.jpg\"\n");
    try {
        strata::scene::buildMaterial(alpha.material);
        ADD_FAILURE() << "no error";
    } catch (const strata::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("material.maps.mask"), std::string::npos) << what;
        EXPECT_NE(what.find("material 'material'"), std::string::npos) << what;
        EXPECT_NE(what.find("rgb.jpg"), std::string::npos) << what;
        EXPECT_NE(what.find("3 channel(s)"), std::string::npos) << what;
    }
    const Scene broken = scene("[material.maps.albedo]\nfile = \"broken.png\"\n");
    try {
        strata::scene::buildMaterial(broken.material);
        ADD_FAILURE() << "no error";
    } catch (const strata::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("material.maps.albedo"), std::string::npos) << what;
        EXPECT_NE(what.find("broken.png"), std::string::npos) << what;
    }
}

TEST(Scene, LightsAndExposure)
{
    const Scene scene = parseScene(R"(
[light]
sun_azimuth = 90
sun_elevation = 30
sun_color = [3.0, 2.9, 2.5]
exposure = 1.5
[[light.extra]]
azimuth = -90
elevation = 20
color = [0.2, 0.25, 0.4]
[[light.extra]]
azimuth = 180
)", "t.toml");
    EXPECT_FLOAT_EQ(scene.lighting.exposure, 1.5f);
    EXPECT_EQ(scene.lighting.sunColor, glm::vec3(3.0f, 2.9f, 2.5f));
    EXPECT_NEAR(scene.lighting.sunDirection.x, std::cos(glm::radians(30.0)), 1e-6);
    ASSERT_EQ(scene.lighting.extraLights.size(), 2u);
    EXPECT_NEAR(scene.lighting.extraLights[0].direction.x, -std::cos(glm::radians(20.0)), 1e-6);
    EXPECT_EQ(scene.lighting.extraLights[0].color, glm::vec3(0.2f, 0.25f, 0.4f));
    EXPECT_EQ(scene.lighting.extraLights[1].color, glm::vec3(0.5f));
}

TEST(Scene, LightErrorsNameTheKey)
{
    EXPECT_EQ(parseError("[light]\nexposure = 0\n"), "test.toml:2: light.exposure = 0 is out of range [0.001, 1000]");
    EXPECT_EQ(parseError("[light]\nsun_color = [1, -1, 1]\n"), "test.toml:2: light.sun_color = [ 1, -1, 1 ] must not be negative");
    EXPECT_EQ(parseError("[[light.extra]]\nazimuth = 0\ncolour = [1, 1, 1]\n"),
              "test.toml:3: unknown key 'light.extra[0].colour'");
    EXPECT_EQ(parseError("[light]\nextra = 3\n"),
              "test.toml:2: light.extra = 3 must be an array of at most 3 tables ([[light.extra]])");
    EXPECT_EQ(parseError("[[light.extra]]\n[[light.extra]]\n[[light.extra]]\n[[light.extra]]\n").rfind("test.toml:", 0), 0u);
}

TEST(Scene, AtmosphereIsOnByDefaultAndEveryKeyIsRead)
{
    EXPECT_TRUE(parseScene("", "empty.toml").lighting.atmosphere.enabled);
    EXPECT_TRUE(parseScene(strata::scene::defaultSceneText(), "<default scene>").lighting.atmosphere.enabled);
    const Scene scene = parseScene(R"(
[atmosphere]
enabled = true
zenith_color = [0.1, 0.2, 0.3]
horizon_color = [0.6, 0.7, 0.8]
fog_density = 0.002
fog_falloff = 0.01
fog_base_height = -120.5
sun_glow = 2.0
sun_disc_radius = 0
)",
                                   "atmosphere.toml");
    const strata::render::Atmosphere& a = scene.lighting.atmosphere;
    EXPECT_TRUE(a.enabled);
    EXPECT_EQ(a.zenithColor, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(a.horizonColor, glm::vec3(0.6f, 0.7f, 0.8f));
    EXPECT_FLOAT_EQ(a.fogDensity, 0.002f);
    EXPECT_FLOAT_EQ(a.fogFalloff, 0.01f);
    EXPECT_EQ(a.fogBaseHeight, -120.5);
    EXPECT_FLOAT_EQ(a.sunGlow, 2.0f);
    EXPECT_EQ(a.sunDiscRadius, 0.0f);
    EXPECT_FALSE(parseScene("[atmosphere]\nenabled = false\n", "off.toml").lighting.atmosphere.enabled);
}

TEST(Scene, AtmosphereErrorsNameTheKey)
{
    EXPECT_EQ(parseError("[atmosphere]\nfog_density = 2\n"),
              "test.toml:2: atmosphere.fog_density = 2 is out of range [0, 1]");
    EXPECT_EQ(parseError("[atmosphere]\nhorizon_color = [1, -1, 1]\n"),
              "test.toml:2: atmosphere.horizon_color = [ 1, -1, 1 ] must not be negative");
    EXPECT_EQ(parseError("[atmosphere]\nsun_disc_radius = 30\n"),
              "test.toml:2: atmosphere.sun_disc_radius = 30 is out of range [0, 20]");
    EXPECT_EQ(parseError("[atmosphere]\nenabled = 1\n"), "test.toml:2: atmosphere.enabled = 1 must be true or false");
    EXPECT_EQ(parseError("[atmosphere]\nfog = 0.1\n"), "test.toml:2: unknown key 'atmosphere.fog'");
}

TEST(SceneMaterial, ProjectionsKeyChoosesBiplanar)
{
    EXPECT_EQ(parseScene("", "empty.toml").material.parameters.projections, 3);
    EXPECT_EQ(parseScene("[material]\nprojections = 2\n", "bi.toml").material.parameters.projections, 2);
    EXPECT_EQ(parseError("[material]\nprojections = 1\n"), "test.toml:2: material.projections = 1 is out of range [2, 3]");
}
