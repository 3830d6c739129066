// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Bad scene values through the real CLI: one key of each kind of check that
// the scene library makes in-process (tests/scene: SceneTest, SceneTerrainTest,
// QualityTest, PipelineTest), each in its own scene file given to
// `strata generate`. Every one must exit 2 with exactly one line,
// `strata: error: FILE:LINE: KEY ...` naming the value where the key has one,
// and leave no output folder. One case per kind: each run costs about 0.6 s
// of CPU, nearly all of it the dynamic loader (OpenImageIO's dependencies).

#include "RunStrata.h"
#include "TestDir.h"

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <future>
#include <sstream>
#include <string>
#include <vector>

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

struct BadValue
{
    const char* kind;  ///< what the check is about
    std::string text;  ///< the scene file
    int line;          ///< the line the message must name
    std::string key;   ///< the key it must name (empty: a TOML syntax error, which has none)
    std::string value; ///< the value it must name (empty: the key alone is the culprit)
};

/// A scene whose [terrain] is node `a` of `type` with `keys`: `type` is on line 4.
std::string oneNode(const std::string& type, const std::string& keys)
{
    return "[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"" + type + "\"\n" + keys;
}

/// Writes a width x height image with `channels` channels (a ramp) through OpenImageIO.
void writeImage(const std::filesystem::path& path, int width, int height, int channels)
{
    std::vector<unsigned char> pixels(std::size_t(width) * height * channels);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i * 7);
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << path;
    ASSERT_TRUE(out->open(path.string(), OIIO::ImageSpec(width, height, channels, OIIO::TypeDesc::UINT8))) << path;
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data())) << path;
    out->close();
}

std::vector<std::string> nonEmptyLines(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty()) lines.push_back(line);
    }
    return lines;
}

} // namespace

TEST(CliSceneErrors, OneKeyOfEachKindExitsTwoWithOneLineNamingFileLineKeyAndValueAndWritesNothing)
{
    const auto dir = strata::test::freshTestDir();
    writeImage(dir / "rgb.png", 8, 8, 3);        // a mask map with too few channels (3 of 4)
    writeImage(dir / "wide.png", 9000, 1, 1);    // wider than a material map may be (8192)
    writeImage(dir / "thin.png", 1, 8, 1);       // narrower than a heightmap may be (2)
    {
        std::ofstream(dir / "broken.png", std::ios::binary) << "this is not a PNG image";
    }
    const std::vector<BadValue> cases = {
        // The TOML itself.
        {"syntax error", "seed = 1\n[sampling\nvoxel_size = 1\n", 2, "", ""},
        {"duplicate key", "seed = 1\nseed = 2\n", 2, "seed", ""},
        // Types.
        {"integer expected", "[terrain.height]\noctaves = 2.5\n", 2, "terrain.height.octaves", "2.5"},
        {"number expected", "[camera]\nzoom = \"far\"\n", 2, "camera.zoom", "'far'"},
        {"table expected", "seed = 4\nsampling = 3\n", 2, "sampling", "3"},
        // Ranges and numbers.
        {"number out of range", "[sampling]\nvoxel_size = -1\n", 2, "sampling.voxel_size", "-1"},
        {"integer out of range", "seed = 1\n[terrain.height]\noctaves = 100\n", 3, "terrain.height.octaves", "100"},
        {"not finite (nan)", "[sampling]\nvoxel_size = nan\n", 2, "sampling.voxel_size", "nan"},
        {"node integer out of range", oneNode("heightfield", "octaves = 1000\n"), 5, "terrain.nodes.a.octaves",
         "1000"},
        {"array element out of range", "[region]\nmin = [0, 0, 2e9]\n", 2, "region.min[2]", "2e+09"},
        {"not a power of two", "[material]\ntexture_size = 300\n", 2, "material.texture_size", "300"},
        // Arrays.
        {"vec3 length", "[camera]\nposition = [1, 2]\ntarget = [0, 0, 0]\n", 2, "camera.position", "[ 1, 2 ]"},
        {"vec3 element type", "[camera]\nposition = [1, 2, \"x\"]\ntarget = [0, 0, 0]\n", 2, "camera.position",
         "[ 1, 2, 'x' ]"},
        {"array of tables", "[light]\nextra = 3\n", 2, "light.extra", "3"},
        {"negative colour", "[light]\nsun_color = [1, -1, 1]\n", 2, "light.sun_color", "[ 1, -1, 1 ]"},
        {"non-positive size", oneNode("box", "size = [1, -2, 3]\n"), 5, "terrain.nodes.a.size", "[ 1, -2, 3 ]"},
        // Names.
        {"unknown key", "seeds = 2\n", 1, "'seeds'", ""},
        {"unknown node type", oneNode("blob", ""), 4, "terrain.nodes.a.type", "'blob'"},
        {"unknown normal blend", "[material]\nnormal_blend = \"best\"\n", 2, "material.normal_blend", "'best'"},
        {"unknown preset", "[quality]\npreset = \"ultra\"\n", 2, "quality.preset", "'ultra'"},
        // References between keys.
        {"unknown material", "[material]\nuse = \"nope\"\n", 2, "material.use", "'nope'"},
        {"unknown node", oneNode("union", "children = [\"b\", \"c\"]\n[terrain.nodes.b]\ntype = \"sphere\"\n"), 5,
         "terrain.nodes.a.children", "'c'"},
        {"node cycle", oneNode("warp", "child = \"a\"\n"), 5, "terrain.nodes.a.child", "'a'"},
        {"unused node", oneNode("sphere", "[terrain.nodes.b]\ntype = \"sphere\"\n"), 5, "terrain.nodes.b", ""},
        {"missing root", "[terrain.nodes.a]\ntype = \"sphere\"\n", 1, "terrain.root", ""},
        {"missing node key", oneNode("image_heightfield", ""), 3, "terrain.nodes.a.file", ""},
        // The height graph.
        {"3D node as a height", oneNode("height_add", "children = [\"b\", \"c\"]\n[terrain.nodes.b]\ntype = "
                                                      "\"sphere\"\n[terrain.nodes.c]\ntype = \"height_constant\"\n"),
         5, "terrain.nodes.a.children", ""},
        {"curve not increasing", oneNode("height_curve", "child = \"b\"\npoints = [[0, 0], [0, 1]]\n"
                                                         "[terrain.nodes.b]\ntype = \"height_constant\"\n"),
         6, "terrain.nodes.a.points", ""},
        {"empty erode domain", oneNode("erode", "height = \"b\"\nmin = [0, 0]\nmax = [0, 10]\n"
                                                "[terrain.nodes.b]\ntype = \"height_constant\"\n"),
         7, "terrain.nodes.a.max", ""},
        {"noise keys beside a height", oneNode("heightfield", "height = \"b\"\namplitude = 3\n"
                                                              "[terrain.nodes.b]\ntype = \"height_constant\"\n"),
         6, "terrain.nodes.a.amplitude", ""},
        // Checks across keys.
        {"min not below max", "[region]\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n", 3, "region.max", "0 >= 0"},
        {"key beyond another", oneNode("box", "size = [2.0, 2.0, 2.0]\nrounding = 1.5\n"), 6,
         "terrain.nodes.a.rounding", "1.5"},
        {"exclusive keys", "[quality]\nvoxel_size = 0.5\nvoxel_scale = 2\n", 3, "quality.voxel_scale", ""},
        // Files.
        {"missing map file", "[material.maps.normal]\nfile = \"/nonexistent/n.png\"\n", 2,
         "material.maps.normal.file", "/nonexistent/n.png"},
        {"missing heightmap", oneNode("image_heightfield", "file = \"/nonexistent/h.png\"\n"), 5,
         "terrain.nodes.a.file", "/nonexistent/h.png"},
        {"unreadable heightmap", oneNode("image_heightfield", "file = \"../broken.png\"\n"), 5, "terrain.nodes.a.file",
         "broken.png"},
        {"heightmap too small", oneNode("image_heightfield", "file = \"../thin.png\"\n"), 5, "terrain.nodes.a.file",
         "thin.png"},
        {"unreadable map", "[material.maps.albedo]\nfile = \"../broken.png\"\n", 1, "material.maps.albedo",
         "broken.png"},
        {"map with too few channels", "[material.maps.mask]\nfile = \"../rgb.png\"\n", 1, "material.maps.mask",
         "rgb.png"},
        {"map too large", "[material.maps.albedo]\nfile = \"../wide.png\"\n", 1, "material.maps.albedo", "wide.png"},
        // Depth.
        {"node tree too deep",
         [] {
             std::string text = "[terrain]\nroot = \"n0\"\n";
             for (int i = 0; i < 300; ++i) {
                 text += "[terrain.nodes.n" + std::to_string(i) + "]\ntype = \"translate\"\nchild = \"n" +
                         std::to_string(i + 1) + "\"\n";
             }
             return text + "[terrain.nodes.n300]\ntype = \"sphere\"\n";
         }(),
         770, "terrain.nodes.n255.child", "'n256'"},
    };

    // Each run is mostly the process's start (about 0.5 s here: some 270
    // shared libraries), so four run at a time; the results are checked in order.
    struct Run
    {
        std::filesystem::path scene, out;
        CommandResult result;
    };
    std::vector<Run> runs(cases.size());
    for (std::size_t first = 0; first < cases.size(); first += 4) {
        std::vector<std::future<void>> batch;
        for (std::size_t i = first; i < std::min(cases.size(), first + 4); ++i) {
            const std::filesystem::path caseDir = dir / ("case-" + std::to_string(i));
            std::filesystem::create_directories(caseDir);
            runs[i].scene = caseDir / "bad.toml";
            runs[i].out = caseDir / "out";
            {
                std::ofstream(runs[i].scene) << cases[i].text;
            }
            batch.push_back(std::async(std::launch::async, [&runs, i, caseDir] {
                runs[i].result = runStrata(
                    "generate " + runs[i].scene.string() + " -o " + runs[i].out.string() + " -q --backend cpu", caseDir);
            }));
        }
        for (auto& done : batch) done.get();
    }
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const BadValue& c = cases[i];
        const CommandResult& run = runs[i].result;
        SCOPED_TRACE(c.kind);
        EXPECT_EQ(run.exitCode, 2) << run.output;
        const std::vector<std::string> lines = nonEmptyLines(run.output);
        ASSERT_EQ(lines.size(), 1u) << run.output;
        const std::string prefix = "strata: error: " + runs[i].scene.string() + ":" + std::to_string(c.line) + ": ";
        EXPECT_EQ(lines[0].rfind(prefix, 0), 0u) << lines[0] << "\nexpected to start with: " << prefix;
        if (!c.key.empty()) {
            EXPECT_NE(lines[0].find(c.key), std::string::npos) << lines[0];
        }
        if (!c.value.empty()) {
            EXPECT_NE(lines[0].find(c.value), std::string::npos) << lines[0];
        }
        EXPECT_FALSE(std::filesystem::exists(runs[i].out)) << lines[0];
    }
}

TEST(CliSceneErrors, AnErosionPassOverTheMemoryBudgetIsRefusedBeforeItRuns)
{
    // 8193² cells at 1 m over 8 km: gigabytes of working memory, far over
    // 64 MiB. generate and bake --plan exit 2 at once, naming cell_size, and
    // write nothing (the pass itself would take many minutes and gigabytes).
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream(dir / "big.toml") << oneNode("erode", "height = \"b\"\nmin = [-4096, -4096]\nmax = [4096, 4096]\n"
                                                            "cell_size = 1.0\n[terrain.nodes.b]\n"
                                                            "type = \"height_constant\"\n");
    }
    for (const std::string& command : {"generate " + (dir / "big.toml").string() + " -o " + (dir / "out").string() +
                                          " -q --max-memory 64MiB",
                                      "bake " + (dir / "big.toml").string() + " --plan --max-memory 64MiB"}) {
        const CommandResult run = runStrata(command, dir);
        EXPECT_EQ(run.exitCode, 2) << command << "\n" << run.output;
        EXPECT_NE(run.output.find("terrain.nodes.a.cell_size"), std::string::npos) << run.output;
        EXPECT_NE(run.output.find("memory budget of 64 MiB"), std::string::npos) << run.output;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}
