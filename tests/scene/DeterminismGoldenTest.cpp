// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The golden table of issue 39: small crops sampled and meshed, each
// stage's bytes hashed and held to the digests recorded here. It runs in
// CI's main run (gcc, Release, -O3) and again under ASan + UBSan (clang,
// -O2), so a compiler, an optimisation level or a sanitizer that changes one
// bit of a grid or a mesh fails it, naming the crop and the stage.

#include <strata/Sha256.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>

#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace strata::scene;

/// Every node kind that decides values in ways a compiler could change:
/// landscape evolution, droplet erosion, terraces, rock beds with folds,
/// worm caves, a smooth subtraction.
constexpr const char* GEOLOGY = R"toml(
[region]
min = [-20.0, -30.0, -20.0]
max = [20.0, 50.0, 20.0]

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
min_y = -20.0
max_y = 10.0
)toml";

/// The default scene cropped to a square of `side` metres about (x, z).
Scene defaultCrop(double x, double z, double side)
{
    Scene scene = defaultScene();
    scene.region.min = glm::dvec3(x - side / 2, scene.region.min.y, z - side / 2);
    scene.region.max = glm::dvec3(x + side / 2, scene.region.max.y, z + side / 2);
    return scene;
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

struct Golden
{
    const char* crop;
    const char* grid;
    const char* mesh;
};

// Recorded with gcc 12 Release on x86_64; every other build must agree.
// A change that moves these must say why in its commit and record the new
// digests (the test prints the table).
const Golden GOLDEN[] = {
    {"default", "87ff90cb0b46199d7c1b43068d3d22c396bcb521526beb0ff2cc90a0ac5151fd",
     "8e049dff95c54be0d57e8eeb628c40d665b0f14018ffffb03dc1399f4238fd09"},
    {"default far out (1e6 m)", "2c4e3fd67a08f763b9828302a7050c28f17f38b3f8863cbfd9068f590eec306d",
     "0103197acff02e80be69e67c75d9437e79872523688991650819f2a797851e30"},
    {"geology", "bb69987a2b3b2709881597e93fd79f519492739c604d19f2392fdd495ff16068",
     "b28f0988584ef0ed535c025aadfc11511ef3d3ba6f0414371c04ee3651f2f2fc"},
};

TEST(DeterminismGolden, EveryCropGivesTheRecordedBytesAtEveryStage)
{
    const std::vector<std::pair<std::string, Scene>> crops = {
        {"default", defaultCrop(0.0, 0.0, 24.0)},
        {"default far out (1e6 m)", defaultCrop(1e6, -1e6, 24.0)},
        {"geology", parseScene(GEOLOGY, "<geology golden>")},
    };
    ASSERT_EQ(crops.size(), std::size(GOLDEN));
    std::string table;
    for (std::size_t i = 0; i < crops.size(); ++i) {
        const auto& [name, scene] = crops[i];
        const SampledTerrain terrain = sampleTerrain(scene);
        ASSERT_GT(terrain.grid->activeVoxelCount(), 1000u) << name;
        const QualitySettings quality = resolveQuality(scene, std::nullopt, {});
        const strata::meshing::TriangleMesh mesh = meshTerrain(scene, quality, terrain);
        ASSERT_GT(mesh.triangleCount(), 100u) << name;
        const std::string grid = gridDigest(*terrain.grid), meshed = meshDigest(mesh);
        table += "    {\"" + name + "\", \"" + grid + "\", \"" + meshed + "\"},\n";
        EXPECT_EQ(name, GOLDEN[i].crop);
        EXPECT_EQ(grid, GOLDEN[i].grid) << name << ": the sampled grid parts from the recorded one";
        EXPECT_EQ(meshed, GOLDEN[i].mesh) << name << ": the mesh parts from the recorded one";
    }
    std::cout << "the table of this build:\n" << table;
}

} // namespace
