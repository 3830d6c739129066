// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// writeBakeViewer(): DIR/viewer/ holds the page, the material's uniform
// values as the GL renderer sets them (strata.json) and the maps' texture
// arrays with their mip levels (maps/*.png); without a page nothing is
// written. The page drawing them in a browser: tests/web/WebViewerTest.cpp.

#include <strata/render/Image.h>
#include <strata/render/Material.h>
#include <strata/scene/BakeViewer.h>
#include <strata/scene/Scene.h>
#include <strata/scene/SceneMaterial.h>

#include "../SmallScene.h"
#include "../TestDir.h"
#ifdef STRATA_EXECUTABLE
#include "RunStrata.h"
#endif

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace strata;

namespace {

std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void writeText(const fs::path& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

} // namespace

TEST(BakeViewer, WritesThePageTheMaterialAndItsMaps)
{
    const fs::path dir = test::freshTestDir();
    const fs::path page = dir / "page";
    fs::create_directories(page);
    writeText(page / "index.html", "<!DOCTYPE html>");
    writeText(page / "viewer.js", "// bundle");
    const scene::Scene s = scene::parseScene(scene::defaultSceneText(), "<default scene>");
    const fs::path bake = dir / "bake";
    fs::create_directories(bake);

    ASSERT_TRUE(scene::writeBakeViewer(bake, s, page));
    EXPECT_EQ(readText(bake / "viewer" / "index.html"), "<!DOCTYPE html>");
    EXPECT_EQ(readText(bake / "viewer" / "viewer.js"), "// bundle");
    const nlohmann::json json = nlohmann::json::parse(readText(bake / "viewer" / "strata.json"));
    EXPECT_EQ(json.at("format"), "strata-viewer");
    EXPECT_EQ(json.at("tileset"), "../tileset.json");
    EXPECT_EQ(json.at("features").get<std::uint32_t>(), render::effectiveFeatures(scene::buildMaterial(s.material), render::feature::ALL));
    const nlohmann::json& u = json.at("uniforms");
    EXPECT_EQ(u.at("uMaterial.blendExponent").at("type"), "float");
    EXPECT_EQ(u.at("uLighting.lights[0].direction").at("value").size(), 3u);
    EXPECT_EQ(u.at("uLighting.lightCount").at("value").get<int>(), 1);
    EXPECT_EQ(u.at("uAtmosphere.enabled").at("value").get<int>(), s.lighting.atmosphere.enabled ? 1 : 0);
    EXPECT_EQ(u.count("uAtmosphere.skyRayMatrix"), 0u) << "per frame: the viewer's";
    // Nine slots, each an existing PNG holding every layer's mip chain.
    ASSERT_EQ(json.at("maps").size(), 9u);
    for (const nlohmann::json& map : json.at("maps")) {
        const fs::path file = bake / "viewer" / map.at("file").get<std::string>();
        ASSERT_TRUE(fs::exists(file)) << file;
        const render::Image image = render::readImage(file);
        int chain = 0;
        for (const nlohmann::json& level : map.at("levels")) chain += level.at(1).get<int>();
        EXPECT_EQ(image.width, map.at("levels").at(0).at(0).get<int>()) << file;
        EXPECT_EQ(image.height, chain * map.at("layers").get<int>()) << file;
    }
    EXPECT_TRUE(json.at("maps").at(0).at("srgb").get<bool>()) << "albedo is sRGB";
    EXPECT_FALSE(json.at("maps").at(2).at("srgb").get<bool>()) << "normals are linear";

    // The same bytes again.
    const std::string first = readText(bake / "viewer" / "strata.json");
    ASSERT_TRUE(scene::writeBakeViewer(bake, s, page));
    EXPECT_EQ(readText(bake / "viewer" / "strata.json"), first);
}

TEST(BakeViewer, WithoutAPageNothingIsWritten)
{
    const fs::path dir = test::freshTestDir();
    const scene::Scene s = scene::parseScene(scene::defaultSceneText(), "<default scene>");
    EXPECT_FALSE(scene::writeBakeViewer(dir, s, fs::path()));
    EXPECT_FALSE(scene::writeBakeViewer(dir, s, dir / "no-such-page"));
    EXPECT_FALSE(fs::exists(dir / "viewer"));
}

#ifdef STRATA_EXECUTABLE
// The CLI: a strata that finds no page bakes as before, writes no viewer/
// and says so once.
TEST(BakeViewer, ABakeWithoutThePageSaysSoOnce)
{
    const fs::path dir = test::freshTestDir();
    writeText(dir / "small.toml", test::SMALL_SCENE);
    const test::CommandResult r = test::runStrataWithEnvironment(
        "STRATA_VIEWER_DIR=" + (dir / "no-page").string(),
        "bake " + (dir / "small.toml").string() + " -o " + (dir / "bake").string() + " --tile-size 12 --lods 1 --no-grids",
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(fs::exists(dir / "bake" / "tileset.json"));
    EXPECT_FALSE(fs::exists(dir / "bake" / "viewer"));
    const std::string notice = "no web viewer";
    const std::size_t first = r.output.find(notice);
    ASSERT_NE(first, std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(notice, first + 1), std::string::npos) << "said more than once: " << r.output;
}
#endif
