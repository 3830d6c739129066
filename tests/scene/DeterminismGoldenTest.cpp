// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The golden table of issue 39: small crops sampled, meshed, baked into
// tiles and exported for an engine, each stage's bytes hashed and held to
// the digests recorded here. It is its own executable (determinism_tests)
// so the extra builds of scripts/determinism-builds.sh (clang, gcc -O0,
// aarch64 under qemu-user) build only it and the libraries; CI's main run
// (gcc, Release) and its sanitizer run (clang, ASan + UBSan) run it too.
// A build that changes one bit fails it, naming the crop and the stage.

#include "TestDir.h"

#include <strata/Sha256.h>
#include <strata/scene/Bake.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>
#include <strata/scene/TerrainExport.h>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using namespace strata::scene;

/// Every node kind that decides values in ways a compiler could change:
/// landscape evolution, droplet erosion, terraces, rock beds with folds,
/// worm caves, a smooth subtraction. The crop holds the ground (about 72 m
/// up) and worms 5 to 15 m under it: before 2026-12-07 it lay 20 m below
/// the ground, so only the worms reached its bytes.
constexpr const char* GEOLOGY = R"toml(
[region]
min = [-20.0, 40.0, -20.0]
max = [20.0, 100.0, 20.0]

[sampling]
voxel_size = 0.5
half_width = 3

[terrain]
root = "world"

[terrain.nodes.world]
type = "subtract"
children = ["rock", "caves"]
smooth = 1.0

[terrain.nodes.rock]
type = "beds"
child = "terraced"
beds = [[3.0, 0.9], [4.0, 0.2], [2.0, 0.7]]
dip = 12.0
dip_direction = 40.0
fold_amplitude = 2.0
fold_wavelength = 80.0
retreat = 3.0

[terrain.nodes.terraced]
type = "terrace"
child = "detailed"
step = 4.0
sharpness = 3

[terrain.nodes.detailed]
type = "erode_detail"
height = "eroded"
cell_size = 1.0
max_depth = 1.0

[terrain.nodes.eroded]
type = "erode"
height = "initial"
min = [-128.0, -128.0]
max = [128.0, 128.0]
cell_size = 4.0
years = 2.0e5
time_step = 2.0e4

[terrain.nodes.initial]
type = "heightfield"
seed = 1
amplitude = 30.0
wavelength = 120.0

[terrain.nodes.caves]
type = "worms"
cell_size = 32.0
min_y = 56.0
max_y = 66.0
)toml";

/// The default scene cropped to a square of `side` metres about (x, z), at
/// noise version `noiseVersion`.
Scene defaultCrop(double x, double z, double side, int noiseVersion)
{
    // The default scene is version 2 since 2026-12-07; its version-1 rows
    // take its text without that line: the text it had before, byte for
    // byte, so they hold the bytes it gave then.
    std::string text(defaultSceneText());
    if (noiseVersion == 1) {
        const std::size_t key = text.find("\nnoise_version = 2");
        EXPECT_NE(key, std::string::npos) << "the default scene no longer sets noise_version = 2";
        if (key != std::string::npos) text.erase(key, text.find('\n', key + 1) - key);
    }
    Scene scene = parseScene(text, "<default scene>");
    scene.region.min = glm::dvec3(x - side / 2, scene.region.min.y, z - side / 2);
    scene.region.max = glm::dvec3(x + side / 2, scene.region.max.y, z + side / 2);
    return scene;
}

/// An example world cropped to the box [min, max], with `edit` applied to
/// its TOML first (the crops keep the examples' node trees and parameters;
/// only what makes them quick enough for qemu is changed, and named).
Scene exampleCrop(const char* file, const glm::dvec3& min, const glm::dvec3& max,
                  const std::function<void(toml::table&)>& edit = {})
{
    const fs::path path = fs::path(STRATA_SOURCE_DIR) / "examples/worlds" / file;
    toml::table table = toml::parse_file(path.string());
    table.insert_or_assign("region", toml::table{{"min", toml::array{min.x, min.y, min.z}},
                                                 {"max", toml::array{max.x, max.y, max.z}}});
    if (edit) edit(table);
    std::ostringstream text;
    text << table;
    return parseScene(text.str(), path.string());
}

/// The active voxels in the tree's order: coordinates and value bits.
std::string gridDigest(const openvdb::FloatGrid& grid)
{
    std::string bytes;
    for (auto it = grid.cbeginValueOn(); it; ++it) {
        const openvdb::Coord c = it.getCoord();
        const float v = *it;
        bytes.append(reinterpret_cast<const char*>(c.data()), 3 * sizeof(openvdb::Int32));
        bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
    }
    return strata::sha256Hex(bytes);
}

std::string meshDigest(const strata::meshing::TriangleMesh& mesh)
{
    std::string bytes;
    const auto append = [&bytes](const auto& v) {
        bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(v[0]));
    };
    bytes.append(reinterpret_cast<const char*>(&mesh.origin), sizeof mesh.origin);
    append(mesh.positions);
    append(mesh.normals);
    append(mesh.indices);
    return strata::sha256Hex(bytes);
}

/// A file's bytes for the digest: the bake's and the export's JSON name the
/// scene file where it lies on this machine (bake.json and manifest.json:
/// scene.source; terrain.json: scene), which the golden leaves out, so the
/// table holds in any checkout; everything else is hashed as written.
std::string bytesForDigest(const fs::path& file, const std::string& path)
{
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (path == "bake.json" || path == "manifest.json" || path == "terrain.json") {
        nlohmann::json json = nlohmann::json::parse(bytes);
        if (path == "terrain.json")
            json.erase("scene");
        else
            json.at("scene").erase("source");
        bytes = json.dump();
    }
    return bytes;
}

/// Every file under `dir` but the lock and the bake's viewer page (the web
/// build's files and the material's pictures, not terrain): its path and
/// its bytes' SHA-256, in path order.
std::string folderDigest(const fs::path& dir, std::size_t& files)
{
    std::vector<std::string> paths;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(dir)) {
        const std::string path = fs::relative(e.path(), dir).generic_string();
        if (e.is_regular_file() && e.path().filename() != ".strata.lock" && !path.starts_with("viewer/"))
            paths.push_back(path);
    }
    std::sort(paths.begin(), paths.end());
    std::string listing;
    for (const std::string& p : paths) listing += p + '\0' + strata::sha256Hex(bytesForDigest(dir / p, p)) + '\n';
    files = paths.size();
    return strata::sha256Hex(listing);
}

struct Crop
{
    const char* name;
    std::function<Scene()> scene;
    double tileSize; ///< metres: 2 × 2 tiles over x and z for the bake and the export
};

struct Golden
{
    const char* grid;
    const char* mesh;
    const char* tiles;  ///< the bake folder: 2 levels, grids, compact tiles, manifest and tileset
    const char* export_; ///< a Unity export: raw heightmaps, splat and hole PNGs, cave meshes
};

const Crop CROPS[] = {
    {"default", [] { return defaultCrop(0.0, 0.0, 24.0, 1); }, 12.0},
    {"default far out (1e6 m)", [] { return defaultCrop(1e6, -1e6, 24.0, 1); }, 12.0},
    {"geology", [] { return parseScene(GEOLOGY, "<geology golden>"); }, 20.0},
    // mountains4k: erode over the whole 4 km at 32 m cells (the example's
    // 8 m takes minutes under qemu), then erode_detail, the rock relief and
    // the worms, on a 32 m crop where a worm tunnel runs 3 to 15 m under the
    // ground (the surface about 121 m up).
    // The examples are at noise version 2; these two crops drop the key (and
    // mountains4k's outcrops go back to 28 m), so they stay the version 1
    // scenes they were recorded from.
    {"mountains4k crop",
     [] {
         return exampleCrop("mountains4k.toml", {-360.0, 90.0, 296.0}, {-328.0, 154.0, 328.0}, [](toml::table& t) {
             t.erase("noise_version");
             t["terrain"]["nodes"]["outcrops"].as_table()->insert_or_assign("amplitude", 28.0);
             t["terrain"]["nodes"]["eroded"].as_table()->insert_or_assign("cell_size", 32.0);
         });
     },
     16.0},
    {"world4k crop",
     [] {
         return exampleCrop("world4k.toml", {-16.0, -44.0, -16.0}, {16.0, 44.0, 16.0},
                            [](toml::table& t) { t.erase("noise_version"); });
     },
     16.0},
    // Noise version 2 (float lanes, 32-bit hashing): the default scene at the
    // origin and 1e6 m out, and every geology node on its noise.
    {"default v2", [] { return defaultCrop(0.0, 0.0, 24.0, 2); }, 12.0},
    {"default v2 far out (1e6 m)", [] { return defaultCrop(1e6, -1e6, 24.0, 2); }, 12.0},
    {"geology v2", [] { return parseScene(std::string("noise_version = 2\n") + GEOLOGY, "<geology golden>"); }, 20.0},
    // The example as it is (version 2), erode at 32 m cells as above, on a
    // 32 m crop where a worm tunnel runs 3 to 15 m under the ground (the
    // surface 155 to 169 m up).
    {"mountains4k v2 crop",
     [] {
         return exampleCrop("mountains4k.toml", {-1408.0, 128.0, 512.0}, {-1376.0, 192.0, 544.0}, [](toml::table& t) {
             t["terrain"]["nodes"]["eroded"].as_table()->insert_or_assign("cell_size", 32.0);
         });
     },
     16.0},
};

// Recorded with gcc 12 Release on x86_64; every other build must agree.
// A change that moves these must say why in its commit and record the new
// digests (each test prints its row).
const Golden GOLDEN[] = {
    {"87ff90cb0b46199d7c1b43068d3d22c396bcb521526beb0ff2cc90a0ac5151fd",
     "8e049dff95c54be0d57e8eeb628c40d665b0f14018ffffb03dc1399f4238fd09",
     "eb5c08f61f4a59aecf247af62326cd83ad1086f6ba8a4d87735ca9bb46aa237f",
     "73c808bc2dc6be4fd6a63a9dc8cf229deffd0035e294706c55c7f35aff016de7"},
    {"2c4e3fd67a08f763b9828302a7050c28f17f38b3f8863cbfd9068f590eec306d",
     "0103197acff02e80be69e67c75d9437e79872523688991650819f2a797851e30",
     "cc235e7ef28e3707aa522c4ab40d3c15732c99df9a48a5ca7db056e3ebd3a9ee",
     "1e7a8dcb02fa6c08e8300be5f2224a947d991091a695d5c681937460e8400f74"},
    {"ffe2884cb71688ed76d2183ffbb6fd17d0f6562a1437fcd3c589d865e6db3dd9",
     "c3ef5e0b059182c1035004043c003a33e2bbfb5e620c17dc84140dddb99fac4a",
     "6dae068bb3135106e57ddff80f6d4834ba7f69868d5cf57af54905607a0df8c8",
     "bb394932de2044b0d5306ec56c6e6dcb48e25736e733c9429874a8c6673b21c3"},
    {"124b6b01ef2644bb4391e57f0912df76bb846476c2c4c0413d8066f83c7c95d7",
     "d6bc826998fe1e31a77cfe67fbdcc4555a5b6d5d85957fca388265143c1c5f9f",
     "6bdfaf62794c011b677dceb85a2d6b0236cb9171e682fbe8eb757c8909e7e02f",
     "66379f6474f87ba810466b29b69886329953cb352b0525ba10c00dbc2e139cfb"},
    {"f8bdbb43a3c63c6fe4f8765932857f07d8acd1660e994374b1ca64b4663d864d",
     "7855f3abce5f75f2ed89cf7a2077351cbf00c7cb7bc1254cab3c93240cf78980",
     "c5e3eff0bef74d9eb0f2d2702237393a5dfdac4cdc93312408333ed993b59f6f",
     "50bcd89b7b36795da6093b0f356ed537f28bf529305d14b640604cb5b13e98e7"},
    {"10568dea143f90b362a02859a1c01771b3a22bd551f881038b4c5c5a1265df11",
     "69c71a56b7e7e7cd08adae0cea8b2feebf3622adda7b4de5cda2375fb8e4f553",
     "6d1d16673b1c1ab6fed59375b92192d5b7a9f4d9b45e2845c543b3880162466c",
     "6463046d3f4e9f53088ac00e6048acb51d177f5a9fb96b9f782b3961ed61e43e"},
    {"1160fe488e4a7a225d0020e9231add3540e8b7d3291fecb6b32d24bb9ccdf432",
     "bfd239e6a1447208cd0f8f0ac53c03b53bd3560205d62fe722180bef09086738",
     "1477653449e89539468aa6b24870d31110d43c1d7576776e592e438e22cd5d5e",
     "31a510cb86585e21ff2137a6059f4ef65fe4540c392cf4b8fc3fc61d5bf992bc"},
    {"5c46ed13d3bc34cd1fcdadd0ceebaa1225669ed247021c12a564839a153d3237",
     "e855f5476bd45b38637d9915377f08e7fee35403d9c8e9c2f8e46fec9d10d076",
     "a1c96e3c94d7a85cb2d39770f954f080c4442c4ee7e020325fff310b3100fc95",
     "67db85d791f3ee6a0f3ed01f380e4f4aa442f882bff4a85aa41021b4663d45cb"},
    {"285b1cab55e211fdcbbbcd0845f83ad553acf1523dd427f9eeea55c9a3b6d824",
     "32f9e3b0bef4b6820120bde3ed372d38c75fac5b479e5dee9050198b09b159b5",
     "cc7a8403d2cac259b311a42a5867365ddda2bef5a3270a74963f54110f999f90",
     "4dc7115ef9f240d3b5ed07200b8f0d0c49b4927f506c60c57a82366af32dc513"},
};
static_assert(std::size(CROPS) == std::size(GOLDEN));

class DeterminismGolden : public testing::TestWithParam<int>
{};

TEST_P(DeterminismGolden, TheCropGivesTheRecordedBytesAtEveryStage)
{
    const Crop& crop = CROPS[GetParam()];
    const Golden& golden = GOLDEN[GetParam()];
    const Scene scene = crop.scene();

    const SampledTerrain terrain = sampleTerrain(scene);
    ASSERT_GT(terrain.grid->activeVoxelCount(), 1000u) << crop.name;
    const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
    const strata::meshing::TriangleMesh mesh = meshTerrain(scene, quality, terrain);
    ASSERT_GT(mesh.triangleCount(), 100u) << crop.name;
    const std::string grid = gridDigest(*terrain.grid), meshed = meshDigest(mesh);

    const fs::path dir = strata::test::freshTestDir();
    BakeOptions bakeOptions;
    bakeOptions.outputDir = dir / "bake";
    bakeOptions.tileSize = crop.tileSize;
    bakeOptions.lods = 2;
    bakeOptions.threads = 2;
    const BakePlan bakePlan = planBake(scene, bakeOptions);
    ASSERT_EQ(bakePlan.counts[0], 2) << crop.name;
    ASSERT_EQ(bakePlan.counts[2], 2) << crop.name;
    const BakeSummary baked = bake(scene, bakeOptions, bakePlan);
    EXPECT_EQ(baked.baked, bakePlan.tileCount());
    std::size_t bakeFiles = 0;
    const std::string tiles = folderDigest(bakeOptions.outputDir, bakeFiles);
    EXPECT_GT(bakeFiles, 8u) << crop.name;

    TerrainExportOptions exportOptions;
    exportOptions.outputDir = dir / "export";
    exportOptions.engine = TerrainEngine::Unity;
    exportOptions.tileSize = crop.tileSize;
    exportOptions.threads = 2;
    const TerrainExportPlan exportPlan = planTerrainExport(scene, exportOptions);
    ASSERT_EQ(exportPlan.tilesX * exportPlan.tilesZ, 4) << crop.name;
    exportTerrain(scene, exportOptions, exportPlan);
    std::size_t exportFiles = 0;
    const std::string exported = folderDigest(exportOptions.outputDir, exportFiles);
    EXPECT_GE(exportFiles, 9u) << crop.name;

    std::cout << "the row of this build (" << crop.name << "):\n    {\"" << grid << "\",\n     \"" << meshed
              << "\",\n     \"" << tiles << "\",\n     \"" << exported << "\"},\n";
    EXPECT_EQ(grid, golden.grid) << crop.name << ": the sampled grid parts from the recorded one";
    EXPECT_EQ(meshed, golden.mesh) << crop.name << ": the mesh parts from the recorded one";
    EXPECT_EQ(tiles, golden.tiles) << crop.name << ": the baked tile set parts from the recorded one";
    EXPECT_EQ(exported, golden.export_) << crop.name << ": the engine export parts from the recorded one";
}

INSTANTIATE_TEST_SUITE_P(Crops, DeterminismGolden, testing::Range(0, int(std::size(CROPS))),
                         [](const testing::TestParamInfo<int>& info) {
                             std::string name = CROPS[info.param].name;
                             name.erase(std::remove_if(name.begin(), name.end(),
                                                       [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }),
                                        name.end());
                             return name;
                         });

} // namespace
