// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The generate pipeline as library stages (strata/scene/Pipeline.h): the
// stages called one by one give the same bytes as generate(); observers hear
// every stage and can interrupt; errors carry their kind and place.

#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include "SmallScene.h"
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/terrain/NodeRegistry.h>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace strata;
using namespace strata::scene;

namespace {

using strata::test::SMALL_SCENE;

std::string readBytes(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct RecordingObserver : PipelineObserver
{
    std::vector<std::string> begun, ended;
    int progressCalls = 0;
    bool stopAtFirstProgress = false;
    void beginStage(const std::string& stage) override { begun.push_back(stage); }
    bool progress(double) override
    {
        ++progressCalls;
        return !stopAtFirstProgress;
    }
    void endStage(const std::string& stage, double seconds, const std::string&) override
    {
        EXPECT_GE(seconds, 0.0);
        ended.push_back(stage);
    }
};

} // namespace

TEST(Pipeline, StagesInMemoryGiveTheBytesOfGenerate)
{
    const std::filesystem::path dir = test::freshTestDir();
    const Scene scene = parseScene(SMALL_SCENE, "small.toml");

    GenerateOptions options;
    options.outputDir = dir / "generate";
    options.snapshot = false;
    RecordingObserver observer;
    const GenerateResult result = generate(scene, options, &observer);
    EXPECT_EQ(observer.begun, (std::vector<std::string>{"generate", "mesh", "write"}));
    EXPECT_EQ(observer.ended, observer.begun);
    EXPECT_GT(observer.progressCalls, 0);

    // The same stages by hand, as a game would call them.
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(applyQuality(scene, quality));
    ASSERT_TRUE(terrain.grid);
    EXPECT_EQ(terrain.grid->activeVoxelCount(), result.activeVoxels);
    const meshing::TriangleMesh mesh = meshTerrain(applyQuality(scene, quality), quality, terrain);
    EXPECT_EQ(mesh.triangleCount(), result.triangles);
    EXPECT_GT(mesh.triangleCount(), 1000u);
    std::filesystem::create_directories(dir / "stages");
    writeTerrain(terrain, mesh, dir / "stages");
    for (const char* file : {"terrain.vdb", "terrain.glb"}) {
        const std::string a = readBytes(dir / "generate" / file), b = readBytes(dir / "stages" / file);
        EXPECT_FALSE(a.empty()) << file;
        EXPECT_TRUE(a == b) << file << " differs between generate() and the stages";
    }
    EXPECT_TRUE(std::filesystem::exists(dir / "generate" / "report.json"));
}

TEST(Pipeline, AnotherSeedRebuildsTheTree)
{
    const Scene scene = parseScene(SMALL_SCENE, "small.toml");
    const SampledTerrain a = sampleTerrain(scene);
    const SampledTerrain b = sampleTerrain(scene, 8);
    EXPECT_EQ(a.seed, 7u);
    EXPECT_EQ(b.seed, 8u);
    EXPECT_NE(a.field, b.field);
    EXPECT_NE(a.grid->activeVoxelCount(), b.grid->activeVoxelCount());
}

TEST(Pipeline, AnObserverCanInterruptAndNothingIsWritten)
{
    const std::filesystem::path dir = test::freshTestDir();
    const Scene scene = parseScene(SMALL_SCENE, "small.toml");
    GenerateOptions options;
    options.outputDir = dir / "out";
    options.snapshot = false;
    RecordingObserver observer;
    observer.stopAtFirstProgress = true;
    try {
        generate(scene, options, &observer);
        FAIL() << "generate() went on after the observer asked to stop";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Interrupted) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "terrain.vdb"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "terrain.glb"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "report.json"));
}

TEST(Pipeline, NoSurfaceInTheRegionIsBadInput)
{
    std::string text = SMALL_SCENE;
    text.replace(text.find("min = [-12.0, -10.0, -12.0]"), 27, "min = [-12.0, 50.0, -12.0]");
    text.replace(text.find("max = [12.0, 10.0, 12.0]"), 24, "max = [12.0, 60.0, 12.0]");
    const Scene scene = parseScene(text, "air.toml");
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const SampledTerrain terrain = sampleTerrain(scene);
    try {
        meshTerrain(scene, quality, terrain);
        FAIL() << "an empty region meshed";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_EQ(e.place().file, "air.toml");
    }
}

TEST(SceneErrors, CarryKindFileLineKeyAndValue)
{
    const std::string text = "[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"sphere\"\nradius = -1.5\n";
    try {
        parseScene(text, "bad.toml");
        FAIL() << "a negative radius was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_EQ(e.place().file, "bad.toml");
        EXPECT_EQ(e.place().line, 5);
        EXPECT_EQ(e.place().key, "terrain.nodes.a.radius");
        EXPECT_EQ(e.place().value, "-1.5");
        EXPECT_NE(std::string(e.what()).find("bad.toml:5: terrain.nodes.a.radius"), std::string::npos) << e.what();
    }
    // A check across keys (the registration's NodeArgs::fail) points at its key's line.
    const std::string box = "[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"box\"\nsize = [2.0, 2.0, 2.0]\n"
                            "rounding = 1.5\n";
    try {
        parseScene(box, "box.toml");
        FAIL() << "rounding above half the box was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.place().line, 6) << e.what();
        EXPECT_EQ(e.place().key, "terrain.nodes.a.rounding") << e.what();
    }
}

/// A chain of `depth` translate nodes over a sphere.
std::string translateChain(int depth)
{
    std::string text = "[terrain]\nroot = \"n0\"\n";
    for (int i = 0; i < depth; ++i) {
        text += "[terrain.nodes.n" + std::to_string(i) + "]\ntype = \"translate\"\nchild = \"n" +
                std::to_string(i + 1) + "\"\n";
    }
    text += "[terrain.nodes.n" + std::to_string(depth) + "]\ntype = \"sphere\"\n";
    return text;
}

TEST(SceneErrors, DeepNodeChainsAreRefusedNotCrashed)
{
    EXPECT_NO_THROW(parseScene(translateChain(200), "chain.toml"));
    for (int depth : {300, 10000}) {
        try {
            parseScene(translateChain(depth), "chain.toml");
            FAIL() << "a chain of " << depth << " nodes was accepted";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            EXPECT_NE(std::string(e.what()).find("levels deep"), std::string::npos) << e.what();
        }
    }
}

TEST(NodeRegistry, EveryKeyIsDocumentedAndEveryDefaultIsInRange)
{
    const terrain::NodeRegistry& registry = terrain::NodeRegistry::builtin();
    ASSERT_GE(registry.types().size(), 15u);
    for (const terrain::NodeType* type : registry.types()) {
        EXPECT_FALSE(type->description.empty()) << type->name;
        EXPECT_TRUE(type->build) << type->name;
        for (const terrain::NodeKey& key : type->keys) {
            EXPECT_FALSE(key.description.empty()) << type->name << "." << key.name;
            EXPECT_FALSE(key.defaultText().empty()) << type->name << "." << key.name;
            if (const auto* d = std::get_if<double>(&key.defaultValue)) {
                EXPECT_GE(*d, key.min) << type->name << "." << key.name;
                EXPECT_LE(*d, key.max) << type->name << "." << key.name;
            }
            if (const auto* i = std::get_if<std::int64_t>(&key.defaultValue)) {
                EXPECT_GE(double(*i), key.min) << type->name << "." << key.name;
                EXPECT_LE(double(*i), key.max) << type->name << "." << key.name;
            }
            if (key.type == terrain::NodeKeyType::Choice) {
                const std::string& d = std::get<std::string>(key.defaultValue);
                EXPECT_NE(std::find(key.choices.begin(), key.choices.end(), d), key.choices.end())
                    << type->name << "." << key.name;
            }
        }
    }
}

TEST(NodeRegistry, AnUnknownTypeListsTheRegisteredOnes)
{
    try {
        parseScene("[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"blob\"\n", "t.toml");
        FAIL();
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("'blob' is not a node type"), std::string::npos) << what;
        for (const terrain::NodeType* type : terrain::NodeRegistry::builtin().types()) {
            EXPECT_NE(what.find(type->name), std::string::npos) << type->name;
        }
    }
}

TEST(Pipeline, ABadMaterialMapFailsBeforeAnythingIsWritten)
{
    const std::filesystem::path dir = test::freshTestDir();
    {
        std::ofstream png(dir / "broken.png", std::ios::binary);
        png << "this is not a PNG image";
    }
    const std::string text = std::string(SMALL_SCENE) + "[material.maps.albedo]\nfile = \"" +
                             (dir / "broken.png").string() + "\"\n";
    const Scene scene = parseScene(text, (dir / "maps.toml").string());
    for (const bool snapshot : {true, false}) {
        GenerateOptions options;
        options.outputDir = dir / (snapshot ? "with" : "without");
        options.snapshot = snapshot;
        options.request.backend = "cpu";
        RecordingObserver observer;
        try {
            generate(scene, options, &observer);
            FAIL() << "a broken map was accepted (snapshot " << snapshot << ")";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
            EXPECT_NE(std::string(e.what()).find("broken.png"), std::string::npos) << e.what();
        }
        // Found before sampling: no stage ran, no folder was made.
        EXPECT_TRUE(std::find(observer.begun.begin(), observer.begun.end(), "generate") == observer.begun.end());
        EXPECT_FALSE(std::filesystem::exists(options.outputDir)) << options.outputDir;
    }
}

TEST(Pipeline, MaterialMapsCountAgainstTheMemoryBudget)
{
    const std::filesystem::path dir = test::freshTestDir();
    const Scene scene = parseScene(SMALL_SCENE, "small.toml");
    GenerateOptions options;
    options.outputDir = dir / "out";
    options.request.backend = "cpu";
    options.maxMemoryBytes = 4u << 20; // the built-in 512² maps alone take more than 4 MiB
    try {
        generate(scene, options);
        FAIL() << "the maps fit a 4 MiB budget?";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("the material's maps take"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(options.outputDir));
}

TEST(Pipeline, AMapLargerThanTheLimitIsRefusedBeforeDecoding)
{
    const std::filesystem::path dir = test::freshTestDir();
    // A valid PNG header that claims 20000 x 20000 pixels: only the header is read.
    const std::filesystem::path huge = dir / "huge.png";
    {
        auto out = OIIO::ImageOutput::create(huge.string());
        ASSERT_TRUE(out);
        OIIO::ImageSpec spec(20000, 20000, 1, OIIO::TypeDesc::UINT8);
        ASSERT_TRUE(out->open(huge.string(), spec));
        std::vector<unsigned char> row(20000, 128);
        for (int y = 0; y < 20000; ++y) ASSERT_TRUE(out->write_scanline(y, 0, OIIO::TypeDesc::UINT8, row.data()));
        out->close();
    }
    const std::string text = std::string(SMALL_SCENE) + "[material.maps.albedo]\nfile = \"" + huge.string() + "\"\n";
    const Scene scene = parseScene(text, "huge.toml");
    GenerateOptions options;
    options.outputDir = dir / "out";
    options.snapshot = false;
    try {
        generate(scene, options);
        FAIL() << "a 20000² map was accepted";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find("20000x20000 pixels: maps may be at most 8192"), std::string::npos)
            << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(options.outputDir));
}
