// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The [terrain] node tree of the scene file (scene/src/SceneTerrain.h).

#include <strata/scene/Scene.h>
#include "SceneTerrain.h"
#include "TestDir.h"
#include "RunStrata.h"

#include <strata/Error.h>

#include <OpenImageIO/imageio.h>
#include "SceneParseError.h"
#include "ErodedScene.h"
#include <strata/terrain/ErodedHeightfield.h>
#ifdef STRATA_TEST_WITH_GDAL
#include "DemTestFiles.h"
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iterator>
#include <set>
#include <vector>

using strata::scene::parseScene;
using strata::scene::Scene;

namespace {

using strata::test::parseError;

/// A scene whose root is one node of `type` with extra `keys`.
std::string oneNode(const std::string& type, const std::string& keys)
{
    return "[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"" + type + "\"\n" + keys;
}

/// Writes a width×height grey ramp (value x / (width − 1)) as 8- or 16-bit PNG.
void writeRamp(const std::filesystem::path& path, int width, int height, bool sixteenBit)
{
    std::vector<float> pixels;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) pixels.push_back(float(x) / float(width - 1));
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    const OIIO::ImageSpec spec(width, height, 1, sixteenBit ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
}

/// The surface height of a heightfield-like field at (x, z), by bisection.
double surfaceHeight(const strata::terrain::DensityField& field, double x, double z)
{
    double lo = -200.0, hi = 200.0;
    for (int i = 0; i < 80; ++i) {
        const double mid = 0.5 * (lo + hi);
        (field.density({x, mid, z}) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

} // namespace

TEST(SceneTerrain, DefaultSceneIsANodeTree)
{
    const Scene scene = parseScene(std::string(strata::scene::defaultSceneText()), "<default scene>");
    ASSERT_TRUE(scene.field);
    ASSERT_TRUE(scene.buildField);
    const auto other = scene.buildField(2);
    int differ = 0;
    for (double x = -90; x <= 90; x += 10) differ += other->density({x, 0, 3}) != scene.field->density({x, 0, 3});
    EXPECT_GT(differ, 10) << "--seed must change the terrain";
    EXPECT_EQ(scene.buildField(1)->density({3, 4, 5}), scene.field->density({3, 4, 5}));
}

TEST(SceneTerrain, ShorthandStillWorks)
{
    const Scene scene = parseScene("[terrain.height]\namplitude = 20\n[terrain.caves]\nenabled = false\n", "t.toml");
    ASSERT_TRUE(scene.field);
    EXPECT_GT(scene.field->density({0, 100, 0}), 0.0);
    EXPECT_LT(scene.field->density({0, -100, 0}), 0.0);
    EXPECT_EQ(parseError("[terrain]\nroot = \"a\"\n[terrain.height]\namplitude = 3\n[terrain.nodes.a]\ntype = \"sphere\"\n"),
              "test.toml:3: terrain.height cannot be combined with terrain.root and [terrain.nodes]: describe the "
              "heightfield and caves as nodes");
}

TEST(SceneTerrain, EveryNodeTypeIsReachableFromTheSceneFile)
{
    const auto dir = strata::test::freshTestDir();
    writeRamp(dir / "ramp.png", 64, 64, false);
    std::string text = R"(
[terrain]
root = "all"
masks = "scree"
[terrain.nodes.all]
type = "union"
children = ["cut", "shapes", "stepped", "moved", "image", "graph", "layered", "rubble", "real", "crested"]
[terrain.nodes.crested]
type = "crests"
height = "lowest"
mask = "band"
beds = "layered"
[terrain.nodes.rubble]
type = "scree"
child = "moved"
talus = "scree"
[terrain.nodes.layered]
type = "beds"
child = "moved"
beds = [[3, 0.9], [5, 0.1], [0, 0.5]]
dip = 10
fold_amplitude = 2
fault_throw = 3
retreat = 2
[terrain.nodes.graph]
type = "heightfield"
height = "scree"
[terrain.nodes.scree]
type = "talus"
height = "detail"
block = 32
[terrain.nodes.detail]
type = "erode_detail"
height = "eroded"
block = 16
droplet_steps = 8
[terrain.nodes.eroded]
type = "erode"
height = "blend"
uplift_map = "mask"
min = [-64, -64]
max = [64, 64]
cell_size = 8
years = 1e5
time_step = 2e4
[terrain.nodes.blend]
type = "height_blend"
a = "sum"
b = "curve"
mask = "mask"
[terrain.nodes.sum]
type = "height_add"
children = ["hills", "flat"]
[terrain.nodes.flat]
type = "height_constant"
value = 2
[terrain.nodes.curve]
type = "height_curve"
child = "diff"
points = [[-10, -5], [0, 0], [10, 20]]
[terrain.nodes.diff]
type = "height_subtract"
children = ["hills", "flat"]
[terrain.nodes.mask]
type = "height_multiply"
children = ["slopes", "curvature"]
[terrain.nodes.slopes]
type = "mask_slope"
child = "warped"
max = 1
[terrain.nodes.curvature]
type = "mask_curvature"
child = "lowest"
min = -1
max = 1
[terrain.nodes.lowest]
type = "height_min"
children = ["hills", "highest"]
[terrain.nodes.highest]
type = "height_max"
children = ["scaled", "clamped"]
[terrain.nodes.scaled]
type = "height_scale"
child = "hills"
scale = 0.5
[terrain.nodes.clamped]
type = "height_clamp"
child = "terraced"
min = -5
max = 5
[terrain.nodes.terraced]
type = "height_terrace"
child = "hills"
step = 4
[terrain.nodes.warped]
type = "height_warp"
child = "band"
amplitude = 3
wavelength = 30
[terrain.nodes.band]
type = "mask_height"
child = "hills"
min = -5
max = 5
[terrain.nodes.cut]
type = "subtract"
children = ["land", "worms", "cheese", "spaghetti"]
smooth = 1.0
[terrain.nodes.land]
type = "warp"
child = "hills"
amplitude = 4.0
[terrain.nodes.hills]
type = "heightfield"
noise = "simplex"
fractal = "ridged"
octaves = 3
[terrain.nodes.worms]
type = "worms"
[terrain.nodes.cheese]
type = "cheese"
noise = "cellular_f1"
invert = true
threshold = -0.5
[terrain.nodes.spaghetti]
type = "spaghetti"
noise = "value"
fractal = "billow"
[terrain.nodes.shapes]
type = "intersect"
children = ["ball", "brick", "pill", "floor"]
smooth = 0.5
[terrain.nodes.ball]
type = "sphere"
center = [0, 30, 0]
radius = 8
[terrain.nodes.brick]
type = "box"
center = [0, 30, 0]
size = [12, 12, 12]
rounding = 1
[terrain.nodes.pill]
type = "capsule"
a = [-10, 30, 0]
b = [10, 30, 0]
radius = 6
[terrain.nodes.floor]
type = "plane"
normal = [0, 1, 0]
offset = 40
[terrain.nodes.stepped]
type = "terrace"
child = "hills"
step = 3
sharpness = 4
[terrain.nodes.moved]
type = "translate"
child = "ball"
offset = [40, 0, 0]
[terrain.nodes.image]
type = "image_heightfield"
file = "ramp.png"
min = [-50, -50]
max = [50, 50]
height_scale = 10
)";
#ifdef STRATA_TEST_WITH_GDAL
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", {}));
    text += "[terrain.nodes.real]\ntype = \"dem_heightfield\"\nfile = \"dem.tif\"\nbase = -150\n";
#else
    text += "[terrain.nodes.real]\ntype = \"plane\"\n"; // a build without GDAL reads no DEM
#endif
    std::set<std::string> used;
    for (const std::string& type : strata::scene::terrainNodeTypes()) {
        if (text.find("type = \"" + type + "\"") != std::string::npos) used.insert(type);
    }
#ifndef STRATA_TEST_WITH_GDAL
    used.insert("dem_heightfield");
#endif
    EXPECT_EQ(used.size(), strata::scene::terrainNodeTypes().size()) << "a node type is missing from this test";
    {
        std::ofstream(dir / "all.toml") << text;
    }
    const Scene scene = strata::scene::loadScene(dir / "all.toml");
    ASSERT_TRUE(scene.field);
    EXPECT_LT(scene.field->density({0, 30, 0}), 0.0); // inside the shapes
    EXPECT_LT(scene.field->density({40, 30, 0}), 0.0); // the translated ball
    EXPECT_GT(scene.field->density({0, 200, 0}), 0.0);
}

TEST(SceneTerrain, ImageHeightfieldReproducesARampWithinOneStep)
{
    const auto dir = strata::test::freshTestDir();
    for (const bool sixteen : {false, true}) {
        const std::string name = sixteen ? "ramp16.png" : "ramp8.png";
        writeRamp(dir / name, 256, 8, sixteen);
        {
            std::ofstream(dir / "scene.toml") << oneNode("image_heightfield", "file = \"" + name +
                                                                                  "\"\nmin = [0, 0]\nmax = [255, 7]\n"
                                                                                  "height_scale = 51\nbase = -5\n");
        }
        const Scene scene = strata::scene::loadScene(dir / "scene.toml");
        const double step = 51.0 / (sixteen ? 65535.0 : 255.0);
        double worst = 0.0;
        for (double x = 0.0; x <= 255.0; x += 0.71) {
            worst = std::max(worst, std::abs(surfaceHeight(*scene.field, x, 3.3) - (-5.0 + 51.0 * x / 255.0)));
        }
        EXPECT_LE(worst, step) << name;
    }
}

// A heightmap is opened by its extension's reader only: bytes of another
// format are refused, not handed to every other reader in turn; unknown
// extensions and folders are refused naming why.
TEST(SceneTerrain, ImageHeightfieldOpensAFileByItsExtensionOnly)
{
    const auto dir = strata::test::freshTestDir();
    writeRamp(dir / "ramp.png", 16, 8, false);
    std::filesystem::copy_file(dir / "ramp.png", dir / "ramp-really-png.tif");
    std::filesystem::copy_file(dir / "ramp.png", dir / "ramp.xyz");
    std::filesystem::copy_file(dir / "ramp.png", dir / "RAMP.PNG");
    std::filesystem::create_directory(dir / "folder.png");
    auto error = [&](const std::string& file) {
        std::ofstream(dir / "scene.toml") << oneNode("image_heightfield", "file = \"" + file + "\"\n");
        try {
            strata::scene::loadScene(dir / "scene.toml");
        } catch (const strata::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(error("ramp.png"), "no error");
    EXPECT_EQ(error("RAMP.PNG"), "no error"); // extensions in any case
    const std::string tif = error("ramp-really-png.tif");
    EXPECT_NE(tif.find("ramp-really-png.tif': cannot be read as a .tif image"), std::string::npos) << tif;
    const std::string xyz = error("ramp.xyz");
    EXPECT_NE(xyz.find("ramp.xyz': has the extension '.xyz', not an image format Strata reads (.png, .jpg"),
              std::string::npos)
        << xyz;
    const std::string folder = error("folder.png");
    EXPECT_NE(folder.find("folder.png': is not a file"), std::string::npos) << folder;
    for (const std::string& message : {tif, xyz, folder}) {
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_NE(message.find("scene.toml:5: terrain.nodes.a.file = '"), std::string::npos) << message;
    }
}

// A PNG whose header (with a valid CRC) claims 16000 x 16000 pixels in a few
// hundred bytes is refused before 1 GiB of floats is allocated for it.
TEST(SceneTerrain, ImageHeightfieldRefusesAHeaderLargerThanItsFileCanHold)
{
    const auto dir = strata::test::freshTestDir();
    writeRamp(dir / "ramp.png", 16, 8, false);
    std::string bytes;
    {
        std::ifstream in(dir / "ramp.png", std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    ASSERT_EQ(bytes.substr(12, 4), "IHDR");
    for (int field : {16, 20}) { // width, height: 16000, big-endian
        bytes[field] = 0, bytes[field + 1] = 0, bytes[field + 2] = char(16000 >> 8), bytes[field + 3] = char(16000 & 255);
    }
    std::uint32_t crc = 0xffffffffu; // CRC-32 over the chunk type and data, as PNG defines it
    for (std::size_t i = 12; i < 12 + 4 + 13; ++i) {
        crc ^= std::uint8_t(bytes[i]);
        for (int b = 0; b < 8; ++b) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
    }
    crc ^= 0xffffffffu;
    for (int b = 0; b < 4; ++b) bytes[29 + b] = char(crc >> (24 - 8 * b));
    std::ofstream(dir / "huge.png", std::ios::binary) << bytes;
    std::ofstream(dir / "scene.toml") << oneNode("image_heightfield", "file = \"huge.png\"\n");
    try {
        strata::scene::loadScene(dir / "scene.toml");
        ADD_FAILURE() << "no error";
    } catch (const strata::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("huge.png': claims 16000x16000 pixels of 1 channel(s) in a file of " +
                            std::to_string(bytes.size()) + " bytes"),
                  std::string::npos)
            << what;
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
    }
}

TEST(SceneTerrain, TunnelsReachTheSurfaceInTheDefaultScene)
{
    // Air connected to the sky that lies at least 3 m inside the land's rock
    // (the land without the tunnels) is a tunnel mouth and the tunnel behind it.
    std::string text(strata::scene::defaultSceneText());
    const Scene scene = parseScene(text, "<default scene>");
    // The same scene without worms is the land alone.
    const std::size_t worms = text.find("worms_per_cell = ");
    ASSERT_NE(worms, std::string::npos);
    text.replace(worms, text.find('\n', worms) - worms, "worms_per_cell = 0.0");
    const Scene land = parseScene(text, "<land>");

    const double h = 1.5;
    const int nx = 128, ny = 58, nz = 128;
    const auto at = [&](int i, int j, int k) {
        return glm::dvec3(-96.0 + h * (i + 0.5), -44.0 + h * (j + 0.5), -96.0 + h * (k + 0.5));
    };
    std::vector<char> air(std::size_t(nx) * ny * nz), seen(air.size(), 0);
    const auto index = [&](int i, int j, int k) { return (std::size_t(i) * ny + j) * nz + k; };
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            for (int k = 0; k < nz; ++k) air[index(i, j, k)] = scene.field->density(at(i, j, k)) > 0.0;
    std::deque<std::array<int, 3>> queue;
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k)
            if (air[index(i, ny - 1, k)]) queue.push_back({i, ny - 1, k}), seen[index(i, ny - 1, k)] = 1;
    int mouths = 0;
    while (!queue.empty()) {
        const auto [i, j, k] = queue.front();
        queue.pop_front();
        if (land.field->density(at(i, j, k)) < -3.0) ++mouths;
        const int d[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        for (const auto& o : d) {
            const int a = i + o[0], b = j + o[1], c = k + o[2];
            if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
            if (!air[index(a, b, c)] || seen[index(a, b, c)]) continue;
            seen[index(a, b, c)] = 1;
            queue.push_back({a, b, c});
        }
    }
    std::cout << "sky-connected air cells inside the land's rock: " << mouths << "\n";
    EXPECT_GT(mouths, 200);
}

TEST(SceneTerrain, BadNodesNameFileLineKeyAndValue)
{
    EXPECT_EQ(parseError(oneNode("blob", "")),
              "test.toml:4: terrain.nodes.a.type = 'blob' is not a node type (one of beds, box, capsule, cheese, crests, dem_heightfield, erode, "
              "erode_detail, height_add, height_blend, height_clamp, height_constant, height_curve, height_max, "
              "height_min, height_multiply, height_scale, height_subtract, height_terrace, height_warp, heightfield, "
              "image_heightfield, intersect, mask_curvature, mask_height, mask_slope, plane, scree, spaghetti, "
              "sphere, subtract, talus, terrace, translate, union, warp, worms)");
    const std::string notTalus = parseError(
        oneNode("scree", "child = \"b\"\ntalus = \"b\"\n[terrain.nodes.b]\ntype = \"sphere\"\nradius = 3\n"));
    EXPECT_NE(notTalus.find("test.toml:"), std::string::npos) << notTalus;
    EXPECT_NE(notTalus.find("talus"), std::string::npos) << notTalus;
    EXPECT_NE(notTalus.find("must name a `talus` node"), std::string::npos) << notTalus;
    EXPECT_EQ(parseError(oneNode("union", "children = [\"b\", \"c\"]\n[terrain.nodes.b]\ntype = \"sphere\"\n")),
              "test.toml:5: terrain.nodes.a.children = 'c' names no node: add a [terrain.nodes.c] table");
    EXPECT_EQ(parseError(oneNode("warp", "child = \"a\"\n")),
              "test.toml:5: terrain.nodes.a.child = 'a' makes a cycle: a node cannot contain itself");
    EXPECT_EQ(parseError(oneNode("heightfield", "amplitude = nan\n")),
              "test.toml:5: terrain.nodes.a.amplitude = nan must be finite");
    EXPECT_EQ(parseError(oneNode("heightfield", "wavelength = inf\n")),
              "test.toml:5: terrain.nodes.a.wavelength = inf must be finite");
    EXPECT_EQ(parseError(oneNode("worms", "radius = -2\n")),
              "test.toml:5: terrain.nodes.a.radius = -2 is out of range [0.001, 10000]");
    EXPECT_EQ(parseError(oneNode("heightfield", "octaves = 1000\n")),
              "test.toml:5: terrain.nodes.a.octaves = 1000 is out of range [1, 24]");
    EXPECT_EQ(parseError(oneNode("heightfield", "noise = \"perlin\"\n")),
              "test.toml:5: terrain.nodes.a.noise = 'perlin' is not one of gradient, simplex, value, "
              "cellular_f1, cellular_f2");
    EXPECT_EQ(parseError(oneNode("sphere", "radiuss = 3\n")), "test.toml:5: unknown key 'terrain.nodes.a.radiuss'");
    EXPECT_EQ(parseError(oneNode("box", "size = [1, -2, 3]\n")),
              "test.toml:5: terrain.nodes.a.size = [ 1, -2, 3 ] must be positive on every axis");
    EXPECT_EQ(parseError(oneNode("sphere", "[terrain.nodes.b]\ntype = \"sphere\"\n")),
              "test.toml:5: terrain.nodes.b is not used: no node's child or children, nor terrain.root, names it");
    EXPECT_EQ(parseError("[terrain.nodes.a]\ntype = \"sphere\"\n"),
              "test.toml:1: terrain.root is required with [terrain.nodes]: the name of the node to sample");
    EXPECT_EQ(parseError("[region]\nmin = [0, 0, 0]\nmax = [0, 1, 1]\n").substr(0, 32), "test.toml:3: region.max must be ");
    EXPECT_EQ(parseError(oneNode("beds", "child = \"b\"\ntransition = 5\n[terrain.nodes.b]\ntype = \"sphere\"\n")),
              "test.toml:6: terrain.nodes.a.transition = 5 must be > 0 and at most the thinnest bed (4 m)");
    EXPECT_EQ(parseError(oneNode("beds", "child = \"b\"\nbeds = [[4, 0.5], [2, 1.5]]\n[terrain.nodes.b]\ntype = \"sphere\"\n")),
              "test.toml:6: terrain.nodes.a.beds = [ [ 4, 0.5 ], [ 2, 1.5 ] ] [1] hardness = 1.5 must be in 0 .. 1");
    const std::string missing = parseError(oneNode("image_heightfield", "file = \"/nonexistent/h.png\"\n"));
    EXPECT_EQ(missing, "test.toml:5: terrain.nodes.a.file = '/nonexistent/h.png': no such file");
}

TEST(SceneTerrain, CliRefusesBadNodesAndOverBudgetScenesWithExitTwoWritingNothing)
{
    STRATA_REQUIRE_PROGRAM();
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream(dir / "bad.toml") << oneNode("blob", "");
    }
    strata::test::CommandResult run;
    run = strata::test::runStrata("generate " + (dir / "bad.toml").string() + " -o " + (dir / "out").string(), dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("bad.toml:4: terrain.nodes.a.type = 'blob'"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out"));

    run = strata::test::runStrata("generate -o " + (dir / "big").string() + " --no-snapshot --max-memory 2MiB", dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("memory budget of 2 MiB"), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("coarser voxel_size"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "big" / "terrain.vdb"));
    EXPECT_FALSE(std::filesystem::exists(dir / "big" / "report.json"));
    EXPECT_FALSE(std::filesystem::exists(dir / "big")) << "an over-budget scene leaves no folder";

    run = strata::test::runStrata("generate -o " + (dir / "x").string() + " --max-memory lots", dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("--max-memory 'lots'"), std::string::npos) << run.output;
}

TEST(SceneTerrain, TheCanyonShowcaseLoadsAndItsWallsOverhang)
{
    // examples/worlds/canyon2k.toml: the beds node over the canyon. Along a
    // canyon wall the columns a few metres inside it cross out of rock more
    // than once (hard beds over the soft beds' alcoves); the plateau's air
    // above and the rock below are where the scene puts them.
    const Scene scene = strata::scene::loadScene(std::filesystem::path(STRATA_SOURCE_DIR) / "examples/worlds/canyon2k.toml");
    ASSERT_TRUE(scene.field);
    EXPECT_GT(scene.field->density({0.0, 190.0, 0.0}), 0.0);
    EXPECT_LT(scene.field->density({0.0, -10.0, 0.0}), 0.0);
    // The floor at (-680, -336) is at about 16 m (noise version 2); along
    // x = -700 walk south to the wall and count columns with rock over air
    // up to the plateau's top (scree buries the lower part of the wall, up
    // to 60 m above its foot). 17 of these 71 columns overhang.
    int overhanging = 0, columns = 0;
    for (double z = -470.0; z <= -400.0; z += 1.0) {
        int ceilings = 0;
        bool wasRock = true;
        for (double y = 5.0; y <= 160.0; y += 0.25) {
            const bool rock = scene.field->density({-700.0, y, z}) < 0.0;
            ceilings += rock && !wasRock;
            wasRock = rock;
        }
        ++columns;
        overhanging += ceilings > 0;
    }
    std::cout << overhanging << " of " << columns << " columns overhang\n";
    EXPECT_GE(overhanging, 5);
}

// The erode pass reports its progress while the scene loads and stops when
// the progress says so (Ctrl-C in the CLI, KeyboardInterrupt in Python):
// an Interrupted error, not a bad scene, and nothing half-done is cached
// (issue 41: the pass could not be interrupted).
TEST(SceneTerrain, TheErodePassReportsProgressAndStopsWhenAsked)
{
    using strata::terrain::ErodedHeightfield;
    const std::string text = strata::test::erodedSceneToml();
    ErodedHeightfield::clearCache();
    std::vector<double> seen;
    strata::scene::SceneLoadOptions load;
    load.progress = [&](double fraction) {
        seen.push_back(fraction);
        return true;
    };
    parseScene(text, "<eroded>", load);
    ASSERT_GE(seen.size(), 10u);
    EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
    EXPECT_GT(seen.front(), 0.0);
    EXPECT_EQ(seen.back(), 1.0);

    ErodedHeightfield::clearCache();
    int calls = 0;
    load.progress = [&](double) { return ++calls < 3; };
    try {
        parseScene(text, "<eroded>", load);
        ADD_FAILURE() << "the load went on after progress returned false";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::Interrupted) << e.what();
    }
    EXPECT_EQ(calls, 3);
    seen.clear();
    load.progress = [&](double fraction) {
        seen.push_back(fraction);
        return true;
    };
    parseScene(text, "<eroded>", load);
    EXPECT_GE(seen.size(), 10u) << "an interrupted pass was cached";
}
