// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata export-terrain` (apps/strata/ExportTerrainCommand.cpp) as a user
// runs it: from a scene and from a bake folder, and its errors' exit codes.

#include "RunStrata.h"
#include "SmallScene.h"
#include "TestDir.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

using strata::test::CommandResult;
using strata::test::runStrata;
namespace fs = std::filesystem;

namespace {

fs::path writeScene(const fs::path& dir)
{
    const fs::path path = dir / "caves.toml";
    std::ofstream(path) << strata::test::SMALL_SCENE;
    return path;
}

nlohmann::json readJson(const fs::path& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

} // namespace

TEST(ExportTerrainCommand, HelpNamesTheEnginesAndFlags)
{
    const auto dir = strata::test::freshTestDir();
    const CommandResult run = runStrata("export-terrain --help", dir);
    EXPECT_EQ(run.exitCode, 0);
    for (const char* text : {"unreal, unity, godot or raw", "--resolution", "--height-step", "--tiles", "--no-meshes"})
        EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;
    EXPECT_NE(runStrata("--help", dir).output.find("export-terrain"), std::string::npos);
}

TEST(ExportTerrainCommand, SceneToUnityWritesEveryTileAndTheImportNumbers)
{
    const auto dir = strata::test::freshTestDir();
    const fs::path scene = writeScene(dir);
    const CommandResult run =
        runStrata("export-terrain " + scene.string() + " -o " + (dir / "out").string() + " --engine unity --tile-size 8", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("hole cells"), std::string::npos) << run.output;
    const nlohmann::json manifest = readJson(dir / "out" / "terrain.json");
    EXPECT_EQ(manifest["engine"], "unity");
    // 16 voxels + 1 = 17 samples is below Unity's smallest heightmap: 33.
    EXPECT_EQ(manifest["resolution"], 33);
    EXPECT_EQ(manifest["spacing"], 0.25);
    ASSERT_EQ(manifest["tiles"].size(), 9u) << "24 m in tiles of 8 m";
    for (const auto& tile : manifest["tiles"]) {
        EXPECT_TRUE(fs::exists(dir / "out" / tile["files"]["heightmap"].get<std::string>()));
        EXPECT_EQ(fs::file_size(dir / "out" / tile["files"]["heightmap"].get<std::string>()), 33u * 33u * 2u);
    }
}

TEST(ExportTerrainCommand, BakeFolderKeepsItsTilesAndSeed)
{
    const auto dir = strata::test::freshTestDir();
    const fs::path scene = writeScene(dir);
    const CommandResult bake = runStrata(
        "bake " + scene.string() + " -o " + (dir / "bake").string() + " --tile-size 20 --lods 2 --seed 11 -q", dir);
    ASSERT_EQ(bake.exitCode, 0) << bake.output;
    const CommandResult run =
        runStrata("export-terrain " + (dir / "bake").string() + " -o " + (dir / "out").string() + " --engine raw", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const nlohmann::json manifest = readJson(dir / "out" / "terrain.json");
    EXPECT_EQ(manifest["tile_size"], 20.0);
    EXPECT_EQ(manifest["seed"], 11);
    ASSERT_EQ(manifest["tiles"].size(), 4u);
    // Every baked tile has its export tile of the same name.
    for (const auto& tile : manifest["tiles"])
        EXPECT_TRUE(fs::exists(dir / "bake" / "tiles" / "0" / (tile["name"].get<std::string>() + ".glb")))
            << tile["name"];
    // A different tile size than the bake's is refused.
    const CommandResult other = runStrata("export-terrain " + (dir / "bake").string() + " -o " +
                                              (dir / "other").string() + " --tile-size 10",
                                          dir);
    EXPECT_EQ(other.exitCode, 2) << other.output;
    EXPECT_NE(other.output.find("--tile-size"), std::string::npos) << other.output;
}

TEST(ExportTerrainCommand, BadFlagsExitTwoAndWriteNothing)
{
    const auto dir = strata::test::freshTestDir();
    const fs::path scene = writeScene(dir);
    const fs::path out = dir / "out";
    const auto refused = [&](const std::string& flags, const std::string& expected) {
        const CommandResult run = runStrata("export-terrain " + scene.string() + " -o " + out.string() + " " + flags, dir);
        EXPECT_EQ(run.exitCode, 2) << flags << "\n" << run.output;
        EXPECT_NE(run.output.find(expected), std::string::npos) << flags << "\n" << run.output;
        EXPECT_FALSE(fs::exists(out / "terrain.json")) << flags;
    };
    refused("--engine cryengine", "--engine cryengine: unknown engine");
    refused("--engine unity --resolution 100", "--resolution 100");
    refused("--engine unreal --resolution 257", "Unreal takes");
    // 20 m of region in 16 bits at 0.1 mm: 200000 steps.
    refused("--height-step 0.0001", "200000 steps");
    refused("--tiles 99", "--tiles 99");
    refused("--max-memory 1KiB", "--max-memory");
    const CommandResult missing = runStrata("export-terrain " + scene.string(), dir);
    EXPECT_EQ(missing.exitCode, 2) << missing.output;
    EXPECT_NE(missing.output.find("--output is required"), std::string::npos) << missing.output;
}

TEST(ExportTerrainCommand, AnUnwritableOutputExitsOne)
{
    const auto dir = strata::test::freshTestDir();
    const fs::path scene = writeScene(dir);
    std::ofstream(dir / "file") << "in the way";
    const CommandResult run =
        runStrata("export-terrain " + scene.string() + " -o " + (dir / "file" / "out").string(), dir);
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find((dir / "file" / "out").string()), std::string::npos) << run.output;
}
