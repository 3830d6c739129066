#include "Scene.h"

#include <strata/Error.h>

#include <gtest/gtest.h>

using strata::app::parseScene;
using strata::app::Scene;

namespace {

// The message of the strata::Error that parsing `text` throws.
std::string parseError(const std::string& text)
{
    try {
        parseScene(text, "test.toml");
    } catch (const strata::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for:\n" << text;
    return {};
}

} // namespace

TEST(Scene, DefaultSceneParses)
{
    const Scene scene = parseScene(strata::app::defaultSceneText(), "<default scene>");
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
    EXPECT_EQ(parseError("[terrain.height]\noctaves = 2.5\n"), "test.toml:2: terrain.height.octaves must be an integer");
    EXPECT_EQ(parseError("[terrain.caves]\nradiuss = 2\n"), "test.toml:2: unknown key 'terrain.caves.radiuss'");
    EXPECT_EQ(parseError("seeds = 2\n"), "test.toml:1: unknown key 'seeds'");
    EXPECT_EQ(parseError("[camera]\nposition = [1, 2]\n"),
              "test.toml:2: camera.position must be an array of three numbers [x, y, z]");
    EXPECT_EQ(parseError("[material]\ntexture_size = 300\n"), "test.toml:2: material.texture_size = 300 must be a power of two");
    EXPECT_EQ(parseError("[region]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n"),
              "test.toml:3: region.max must be greater than region.min on every axis (axis y: 0 >= 0)");
}

TEST(Scene, SyntaxErrorsGiveTheLine)
{
    const std::string message = parseError("seed = 1\n[sampling\nvoxel_size = 1\n");
    EXPECT_EQ(message.rfind("test.toml:2: ", 0), 0u) << message;
}

TEST(Scene, MissingFileIsAnError)
{
    EXPECT_THROW(strata::app::loadScene("/nonexistent/scene.toml"), strata::Error);
}
