// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// strata::scene::bake(): tiles are pure functions of the scene and their
// index, a level's tiles weld with boundary only on the region's border,
// cross-level seams are covered by skirts, the tileset is valid 3D Tiles
// 1.1, resume redoes exactly the missing or damaged tiles, bad input is
// refused before anything is written, and the world renders from its tiles.

#include <strata/scene/Bake.h>
#include <strata/scene/Scene.h>
#include "RunStrata.h"
#include "../SmallScene.h"
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/world/TileMesh.h>

#include <OpenImageIO/imageio.h>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <unistd.h>

#include <array>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

using namespace strata;
using namespace strata::scene;
namespace fs = std::filesystem;

namespace {

/// Hills minus worm tunnels over 40 × 20 × 40 m at 0.5 m: with 16 m tiles,
/// 3 × 3 columns (the last 8 m wide) of two slabs (16 m and 4 m).
const char* const CAVE_SCENE = strata::test::BAKE_CAVE_SCENE;

/// Hills only (every vertical line meets the surface once).
const char* HILL_SCENE = R"(
seed = 5
[terrain]
root = "land"
[terrain.nodes.land]
type = "heightfield"
amplitude = 5.0
wavelength = 20.0
[region]
min = [-16.0, -8.0, -16.0]
max = [16.0, 8.0, 16.0]
[sampling]
voxel_size = 0.5
)";

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Every file under `dir` (relative path → bytes).
std::map<std::string, std::string> filesUnder(const fs::path& dir)
{
    std::map<std::string, std::string> out;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
        if (entry.is_regular_file() && entry.path().filename() != ".strata.lock")
            out[fs::relative(entry.path(), dir).string()] = readBytes(entry.path());
    return out;
}

BakeSummary bakeInto(const Scene& scene, const fs::path& dir, BakeOptions options)
{
    options.outputDir = dir;
    return bake(scene, options, planBake(scene, options));
}

BakeOptions smallBake(int threads = 0)
{
    BakeOptions options;
    options.tileSize = 16.0;
    options.lods = 3;
    options.threads = threads;
    return options;
}

nlohmann::json readJson(const fs::path& path) { return nlohmann::json::parse(readBytes(path)); }

} // namespace

TEST(Bake, ATextScenesNameIsKeptAndTheBakeJsonIsTheSameFromAnyWorkingDirectory)
{
    const Scene scene = parseScene(HILL_SCENE, "<hills from text>");
    const fs::path dir = test::freshTestDir();
    BakeOptions options = smallBake(1);
    options.lods = 1;
    options.tiles = "0";
    const fs::path before = fs::current_path();
    bakeInto(scene, dir / "a", options);
    fs::current_path(dir); // another working directory
    bakeInto(scene, dir / "b", options);
    fs::current_path(before);
    EXPECT_EQ(readJson(dir / "a" / "bake.json").at("scene").at("source"), "<hills from text>");
    EXPECT_EQ(readBytes(dir / "a" / "bake.json"), readBytes(dir / "b" / "bake.json"));
}

TEST(Bake, PlansTilesSlabsAndNamesFromTheRegion)
{
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    const BakePlan plan = planBake(scene, smallBake());
    EXPECT_EQ(plan.counts, (std::array<int, 3>{3, 2, 3}));
    EXPECT_EQ(plan.tileCount(), 18);
    EXPECT_EQ(plan.selected.size(), 18u);
    const BakeTile last = plan.tile(17);
    EXPECT_EQ(last.cell, (std::array<int, 3>{2, 1, 2}));
    EXPECT_EQ(last.name, "2_1_2");
    EXPECT_EQ(last.box.size, (std::array<std::int64_t, 3>{16, 8, 16})) << "8 m and 4 m at 0.5 m voxels";
    EXPECT_EQ(last.box.neighbourFaces, 1u | 4u | 16u) << "lower faces only";
    EXPECT_EQ(plan.tile(4).box.neighbourFaces, 1u | 2u | 8u | 16u | 32u) << "both x and z faces, the top of y";
}

TEST(Bake, EveryTileIsTheSameBytesAloneInAFullBakeAndOnAnyThreadCount)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    const BakeSummary one = bakeInto(scene, dir / "one", smallBake(1));
    bakeInto(scene, dir / "two", smallBake(2));
    BakeOptions alone = smallBake(1);
    alone.tiles = "4";
    bakeInto(scene, dir / "alone", alone);

    EXPECT_EQ(one.baked, 18);
    const auto full = filesUnder(dir / "one");
    EXPECT_EQ(full, filesUnder(dir / "two")) << "thread count changed a byte";
    std::size_t compared = 0;
    for (const auto& [path, bytes] : filesUnder(dir / "alone")) {
        if (path.find("1_0_1") == std::string::npos) continue; // tile 4 = (1, 0, 1)
        ASSERT_TRUE(full.count(path)) << path;
        EXPECT_EQ(bytes, full.at(path)) << path << " differs when baked alone";
        ++compared;
    }
    EXPECT_EQ(compared, 4u) << "three levels and the grid of tile 4";
}

TEST(Bake, ALevelsTilesWeldWithBoundaryOnlyOnTheRegionBorder)
{
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    const BakePlan plan = planBake(scene, smallBake());
    const glm::dvec3 lo = glm::dvec3(plan.minVoxel[0], plan.minVoxel[1], plan.minVoxel[2]) * plan.voxelSize;
    const glm::dvec3 hi = glm::dvec3(plan.maxVoxel[0], plan.maxVoxel[1], plan.maxVoxel[2]) * plan.voxelSize;
    for (int level = 0; level < plan.lods; ++level) {
        std::map<std::array<double, 3>, std::uint32_t> index;
        std::vector<std::array<double, 3>> positions;
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        for (int i = 0; i < plan.tileCount(); ++i) {
            world::TileMeshOptions options;
            options.voxelSize = plan.voxelSize;
            options.level = level;
            options.skirtDepth = plan.skirtDepth;
            const meshing::TriangleMesh mesh = world::meshTile(*scene.field, plan.tile(i).box, options).surface;
            std::vector<std::uint32_t> local;
            for (const glm::vec3& p : mesh.positions) {
                const std::array<double, 3> key{mesh.origin.x + p.x, mesh.origin.y + p.y, mesh.origin.z + p.z};
                local.push_back(index.emplace(key, std::uint32_t(positions.size())).first->second);
                if (local.back() == positions.size()) positions.push_back(key);
            }
            for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
                for (int k = 0; k < 3; ++k)
                    ++uses[std::minmax(local[mesh.indices[t + k]], local[mesh.indices[t + (k + 1) % 3]])];
        }
        std::size_t boundary = 0, inside = 0;
        for (const auto& [edge, count] : uses) {
            if (count != 1) continue;
            ++boundary;
            const auto& p = positions[edge.first];
            const auto& q = positions[edge.second];
            bool onBorder = false;
            for (int a = 0; a < 3; ++a)
                onBorder = onBorder || (p[a] == lo[a] && q[a] == lo[a]) || (p[a] == hi[a] && q[a] == hi[a]);
            inside += !onBorder;
        }
        EXPECT_GT(boundary, 0u) << "the terrain leaves the region through its sides";
        EXPECT_EQ(inside, 0u) << "level " << level << ": boundary edges inside the region (cracks between tiles)";
    }
}

TEST(Bake, SkirtsCoverTheGapBetweenLevelsOnASharedFace)
{
    // Tile (0, 0) at level 0 beside tile (1, 0) at its coarsest level: on the
    // shared face x = X the two cut polylines differ by less than the skirt
    // depth everywhere, so the deeper skirt closes the gap from any view.
    const Scene scene = parseScene(HILL_SCENE, "hills.toml");
    const BakePlan plan = planBake(scene, smallBake());
    const BakeTile left = plan.tile(0), right = plan.tile(1);
    ASSERT_EQ(plan.counts[1], 1);
    const auto meshAt = [&](const BakeTile& tile, int level) {
        world::TileMeshOptions options;
        options.voxelSize = plan.voxelSize;
        options.level = level;
        options.skirtDepth = plan.skirtDepth;
        return world::meshTile(*scene.field, tile.box, options);
    };
    const double x = double(right.box.min[0]) * plan.voxelSize;
    /// The cut polyline on x = X: boundary edges of the surface lying on it, as (z, y) segments.
    const auto cut = [&](const world::TileMeshData& tile) {
        std::vector<std::array<double, 4>> segments;
        const meshing::TriangleMesh& m = tile.surface;
        for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3)
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 p = m.origin + glm::dvec3(m.positions[m.indices[t + k]]);
                const glm::dvec3 q = m.origin + glm::dvec3(m.positions[m.indices[t + (k + 1) % 3]]);
                if (p.x == x && q.x == x) segments.push_back({p.z, p.y, q.z, q.y});
            }
        return segments;
    };
    const world::TileMeshData fine = meshAt(left, 0), coarse = meshAt(right, plan.lods - 1);
    const auto fineCut = cut(fine), coarseCut = cut(coarse);
    ASSERT_GT(fineCut.size(), 10u);
    ASSERT_GT(coarseCut.size(), 2u);
    EXPECT_GT(fine.skirt.triangleCount(), 0u);
    EXPECT_GT(coarse.skirt.triangleCount(), 0u);
    const auto heightAt = [](const std::vector<std::array<double, 4>>& segments, double z) {
        for (const auto& s : segments) {
            const double z0 = std::min(s[0], s[2]), z1 = std::max(s[0], s[2]);
            if (z < z0 || z > z1) continue;
            const double t = s[2] == s[0] ? 0.0 : (z - s[0]) / (s[2] - s[0]);
            return s[1] + t * (s[3] - s[1]);
        }
        return std::nan("");
    };
    double worst = 0.0;
    int compared = 0;
    const double z0 = double(left.box.min[2]) * plan.voxelSize, z1 = z0 + double(left.box.size[2]) * plan.voxelSize;
    for (double z = z0 + 0.05; z < z1; z += 0.1) {
        const double a = heightAt(fineCut, z), b = heightAt(coarseCut, z);
        if (std::isnan(a) || std::isnan(b)) continue;
        worst = std::max(worst, std::abs(a - b));
        ++compared;
    }
    EXPECT_GT(compared, 100);
    EXPECT_GT(worst, 0.0) << "the levels differ on the face";
    EXPECT_LT(worst, plan.skirtDepth) << "a gap deeper than the skirts";
}

/// Hills over two slabs cut at y = 0: the cut runs through nearly flat
/// ground (hill tops and hollows) in places and through slopes in others.
const char* FLAT_CUT_SCENE = R"(
seed = 3
[terrain]
root = "land"
[terrain.nodes.land]
type = "heightfield"
amplitude = 8.0
wavelength = 30.0
[region]
min = [-16.0, -8.0, -16.0]
max = [16.0, 8.0, 16.0]
[sampling]
voxel_size = 0.5
)";

TEST(Bake, WithEveryLevel0TilePresentNoSkirtIsVisibleOrOutsideTheWorld)
{
    // Level 0 everywhere: tiles meet exactly, so a skirt is needed nowhere
    // and must hide in the rock (below this hill scene's single surface):
    // a skirt in a horizontal slab cut through nearly flat ground used to
    // stick out as a flap, made by both slabs; skirts on the world's sides
    // used to hang outside the region.
    const Scene scene = parseScene(FLAT_CUT_SCENE, "flat-cut.toml");
    BakeOptions options;
    options.tileSize = 8.0;
    options.lods = 2;
    const BakePlan plan = planBake(scene, options);
    ASSERT_EQ(plan.counts[1], 2) << "two slabs, cut at y = 0";
    const glm::dvec3 lo = glm::dvec3(plan.minVoxel[0], plan.minVoxel[1], plan.minVoxel[2]) * plan.voxelSize;
    const glm::dvec3 hi = glm::dvec3(plan.maxVoxel[0], plan.maxVoxel[1], plan.maxVoxel[2]) * plan.voxelSize;
    std::size_t skirts = 0, inCut = 0, flat = 0, outside = 0, visible = 0;
    for (int i = 0; i < plan.tileCount(); ++i) {
        world::TileMeshOptions mesh;
        mesh.voxelSize = plan.voxelSize;
        mesh.skirtDepth = plan.skirtDepth;
        const world::TileMeshData tile = world::meshTile(*scene.field, plan.tile(i).box, mesh);
        const meshing::TriangleMesh& s = tile.skirt;
        for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
            ++skirts;
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = s.origin + glm::dvec3(s.positions[s.indices[t + k]]);
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a) outside += p[k][a] < lo[a] || p[k][a] > hi[a];
            if (p[0].y == 0.0 && p[1].y == 0.0 && p[2].y == 0.0) {
                ++inCut;
                // The surface it hangs from (the vertex normals) lies within 30° of the cut.
                const glm::vec3 n = s.normals[s.indices[t]];
                flat += std::abs(n.y) > std::cos(glm::radians(30.0)) * 1.0001;
            }
            // Seen from above: any point of the skirt above the ground. The
            // level-0 surface follows the field to a few hundredths of a metre.
            for (const glm::dvec3& w : {glm::dvec3(1.0 / 3.0), glm::dvec3(0.1, 0.1, 0.8), glm::dvec3(0.45, 0.1, 0.45)}) {
                const glm::dvec3 q = w.x * p[0] + w.y * p[1] + w.z * p[2];
                visible += scene.field->density(q) > 0.03;
            }
        }
    }
    EXPECT_GT(skirts, 100u) << "skirts are still made on inner faces";
    EXPECT_GT(inCut, 0u) << "and in the slab cut where the ground crosses it steeply";
    EXPECT_EQ(flat, 0u) << "skirts in the cut plane where the ground lies nearly in it";
    EXPECT_EQ(outside, 0u) << "skirt vertices outside the world's box";
    EXPECT_EQ(visible, 0u) << "skirt points above the ground, of " << skirts << " skirt triangles";
}

TEST(Bake, SkirtsAreOneSidedWithTheSurfacesNormalsAndFaceOutOfTheirTile)
{
    // glTF clients flip a double-sided material's normals on back faces
    // (black skirts seen from behind): skirts are one-sided, wound to face
    // out of their tile (toward the air side of a seam), and carry the
    // normal of the surface vertex they hang from, so they are lit like it.
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(HILL_SCENE, "hills.toml");
    BakeOptions options = smallBake();
    options.tileSize = 8.0; // 4 × 2 × 4 tiles
    options.grids = false;
    options.tiles = "5"; // (1, 0, 1): neighbours on all four sides and above
    const BakePlan plan = planBake(scene, options);
    ASSERT_EQ(plan.tile(5).box.neighbourFaces, 1u | 2u | 8u | 16u | 32u);
    const BakeSummary summary = bakeInto(scene, dir, options);
    ASSERT_EQ(summary.baked, 1);
    const nlohmann::json manifest = readJson(dir / "manifest.json");
    const nlohmann::json& record = manifest["tiles"][0];
    const glm::dvec3 boxMin(record["box"]["min"][0], record["box"]["min"][1], record["box"]["min"][2]);
    const glm::dvec3 boxMax(record["box"]["max"][0], record["box"]["max"][1], record["box"]["max"][2]);
    for (int level = 0; level < 3; ++level) {
        const std::string bytes = readBytes(dir / "tiles" / std::to_string(level) / "1_0_1.glb");
        ASSERT_GT(bytes.size(), 20u);
        const std::uint32_t jsonLength = std::uint32_t(std::uint8_t(bytes[12])) | std::uint32_t(std::uint8_t(bytes[13])) << 8 |
                                         std::uint32_t(std::uint8_t(bytes[14])) << 16 | std::uint32_t(std::uint8_t(bytes[15])) << 24;
        const nlohmann::json gltf = nlohmann::json::parse(bytes.substr(20, jsonLength));
        ASSERT_EQ(gltf["materials"].size(), 2u);
        for (const auto& material : gltf["materials"])
            EXPECT_FALSE(material.value("doubleSided", false)) << material["name"] << " is double-sided";

        world::TileMeshOptions mesh;
        mesh.voxelSize = plan.voxelSize;
        mesh.level = level;
        mesh.skirtDepth = plan.skirtDepth;
        const world::TileMeshData tile = world::meshTile(*scene.field, plan.tile(5).box, mesh);
        std::map<std::array<float, 3>, glm::vec3> surfaceNormal;
        for (std::size_t v = 0; v < tile.surface.positions.size(); ++v) {
            const glm::vec3& p = tile.surface.positions[v];
            surfaceNormal[{p.x, p.y, p.z}] = tile.surface.normals[v];
        }
        const meshing::TriangleMesh& s = tile.skirt;
        ASSERT_GT(s.triangleCount(), 0u);
        std::size_t outward = 0;
        for (std::size_t t = 0; t + 2 < s.indices.size(); t += 3) {
            glm::dvec3 p[3];
            for (int k = 0; k < 3; ++k) p[k] = s.origin + glm::dvec3(s.positions[s.indices[t + k]]);
            // The face it lies on and that face's outward normal.
            glm::dvec3 face(0.0);
            for (int a = 0; a < 3; ++a) {
                if (p[0][a] == boxMin[a] && p[1][a] == boxMin[a] && p[2][a] == boxMin[a]) face[a] = -1.0;
                if (p[0][a] == boxMax[a] && p[1][a] == boxMax[a] && p[2][a] == boxMax[a]) face[a] = 1.0;
            }
            ASSERT_NE(face, glm::dvec3(0.0)) << "a skirt triangle off the tile's faces";
            outward += glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), face) > 0.0;
            // The top edge repeats the surface's border vertices with their normals,
            // and the whole skirt carries the surface normal it hangs from.
            const glm::vec3 n = s.normals[s.indices[t]];
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t v = s.indices[t + k];
                const glm::vec3& q = s.positions[v];
                const auto found = surfaceNormal.find({q.x, q.y, q.z});
                if (found != surfaceNormal.end()) {
                    EXPECT_EQ(s.normals[v], found->second) << "a skirt top vertex with another normal than the surface's";
                } else {
                    // A bottom vertex: the normal of its top (vertices come in top, bottom pairs).
                    ASSERT_EQ(v % 2, 1u);
                    EXPECT_EQ(s.normals[v], s.normals[v - 1]);
                }
            }
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
        }
        EXPECT_EQ(outward, s.triangleCount()) << "level " << level << ": skirt triangles facing into their tile";
    }
}

TEST(Bake, TheTilesetIsValid3DTilesAndNamesEveryTileOnce)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    bakeInto(scene, dir, smallBake());
    const nlohmann::json tileset = readJson(dir / "tileset.json");
    EXPECT_EQ(tileset["asset"]["version"], "1.1");
    ASSERT_TRUE(tileset.contains("geometricError"));
    ASSERT_TRUE(tileset.contains("root"));
    EXPECT_EQ(tileset["root"]["refine"], "REPLACE");

    std::multiset<std::string> uris;
    std::map<std::string, double> nodeError; // content uri → the node's geometric error
    // Walks the tree: every node has a box (12 finite numbers, half axes
    // >= 0), a geometric error no larger than its parent's, and a box inside
    // its parent's (axis-aligned boxes: centre ± half extents).
    std::function<void(const nlohmann::json&, double, const std::array<double, 6>*)> walk =
        [&](const nlohmann::json& node, double parentError, const std::array<double, 6>* parent) {
            ASSERT_TRUE(node.contains("boundingVolume"));
            const nlohmann::json& box = node["boundingVolume"]["box"];
            ASSERT_EQ(box.size(), 12u);
            std::array<double, 6> extent{};
            for (int a = 0; a < 3; ++a) {
                const double half = box[3 + 4 * a].get<double>(); // diagonal entries
                ASSERT_GE(half, 0.0);
                extent[a] = box[a].get<double>() - half;
                extent[3 + a] = box[a].get<double>() + half;
            }
            const double error = node["geometricError"].get<double>();
            EXPECT_GE(error, 0.0);
            EXPECT_LE(error, parentError) << "geometric error grows with depth";
            if (parent)
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(extent[a], (*parent)[a] - 1e-9);
                    EXPECT_LE(extent[3 + a], (*parent)[3 + a] + 1e-9);
                }
            if (node.contains("content")) {
                uris.insert(node["content"]["uri"].get<std::string>());
                nodeError[node["content"]["uri"].get<std::string>()] = error;
            }
            if (node.contains("contents"))
                for (const auto& c : node["contents"]) uris.insert(c["uri"].get<std::string>());
            if (node.contains("children"))
                for (const auto& child : node["children"]) walk(child, error, &extent);
            else
                EXPECT_EQ(error, 0.0) << "a leaf is level 0";
        };
    walk(tileset["root"], tileset["geometricError"].get<double>(), nullptr);

    // Exactly the .glb files of the bake, each once.
    std::multiset<std::string> files;
    for (const auto& entry : fs::recursive_directory_iterator(dir / "tiles"))
        if (entry.is_regular_file()) files.insert(fs::relative(entry.path(), dir).string());
    EXPECT_EQ(uris, files);
    // The manifest's per-level errors grow with the level.
    const nlohmann::json manifest = readJson(dir / "manifest.json");
    const auto errors = manifest["geometric_error"].get<std::vector<double>>();
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_EQ(errors[0], 0.0);
    EXPECT_GT(errors[1], 0.0);
    EXPECT_GE(errors[2], errors[1]);

    // Each chain node carries its own tile's measured error (made
    // non-decreasing up the chain), not the worst of its level: clients
    // refine a smooth tile later than a rough one.
    std::size_t belowWorst = 0, level1 = 0;
    for (const auto& tile : manifest["tiles"]) {
        double expected = 0.0;
        for (const auto& level : tile["levels"]) {
            const int l = level["level"].get<int>();
            if (l > 0) expected = std::max(expected, level["error"].get<double>());
            if (level["file"].is_null()) continue;
            const std::string uri = level["file"]["path"].get<std::string>();
            ASSERT_TRUE(nodeError.count(uri)) << uri;
            EXPECT_EQ(nodeError[uri], l == 0 ? 0.0 : expected) << uri;
            if (l == 1) {
                ++level1;
                belowWorst += nodeError[uri] < errors[1];
            }
        }
    }
    EXPECT_GT(level1, 5u);
    EXPECT_GT(belowWorst, level1 / 2) << "most level-1 tiles err less than the worst one";
}

TEST(Bake, ResumeRedoesExactlyTheMissingAndDamagedTiles)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    BakeOptions options = smallBake();
    const BakeSummary first = bakeInto(scene, dir, options);
    const auto before = filesUnder(dir);

    const BakeSummary again = bakeInto(scene, dir, options);
    EXPECT_EQ(again.baked, 0);
    EXPECT_EQ(again.kept, 18);

    fs::remove(dir / "tiles/1/0_0_0.glb");              // missing
    std::string damaged = readBytes(dir / "tiles/0/2_0_2.glb");
    damaged[damaged.size() / 2] ^= 0x40;                  // same size, one bit flipped
    std::ofstream(dir / "tiles/0/2_0_2.glb", std::ios::binary) << damaged;
    const BakeSummary resumed = bakeInto(scene, dir, options);
    EXPECT_EQ(resumed.baked, 2);
    EXPECT_EQ(resumed.kept, 16);
    EXPECT_EQ(filesUnder(dir), before) << "the resumed bake is the same bytes";
    EXPECT_EQ(first.trianglesPerLevel, resumed.trianglesPerLevel);
}

TEST(Bake, BadInputIsRefusedBeforeAnythingIsWritten)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    const auto refused = [&](BakeOptions options, const std::string& flag, const std::string& words) {
        options.outputDir = dir / "out";
        try {
            bake(scene, options, planBake(scene, options));
            ADD_FAILURE() << "accepted " << flag;
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput) << e.what();
            EXPECT_EQ(e.place().key, flag) << e.what();
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
        }
        EXPECT_FALSE(fs::exists(dir / "out")) << flag << ": something was written";
    };
    BakeOptions o = smallBake();
    o.tileSize = 16.3;
    refused(o, "--tile-size", "not a multiple of the voxel size");
    o.tileSize = 17.0; // 34 voxels: not a multiple of the coarsest cell (4 voxels)
    refused(o, "--tile-size", "coarsest cell");
    o.tileSize = 64.0;
    refused(o, "--tile-size", "smaller than one tile");
    o = smallBake();
    o.tiles = "18";
    refused(o, "--tiles", "the world has 18 tiles");
    o.tiles = "3-1";
    refused(o, "--tiles", "ends before it starts");
    o.tiles = "x";
    refused(o, "--tiles", "expected all");
    o = smallBake();
    o.maxMemoryBytes = 1000;
    refused(o, "--tile-size", "over the budget");
}

// A folder that cannot be made is reported, naming it, before any tile is
// baked, even when folders made after it succeed (one shared error code
// once kept only the last call's result).
TEST(Bake, AFolderThatCannotBeMadeIsReportedNamingIt)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    fs::create_directories(dir / "tiles");
    std::ofstream(dir / "tiles" / "0") << "a file where the level 0 folder goes\n";
    BakeOptions options = smallBake();
    try {
        bakeInto(scene, dir, options);
        ADD_FAILURE() << "baked with a file in the way of tiles/0";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Io) << e.what();
        EXPECT_NE(std::string(e.what()).find("cannot create folder '" + (dir / "tiles" / "0").string() + "'"),
                  std::string::npos)
            << e.what();
        EXPECT_EQ(e.place().file, (dir / "tiles" / "0").string());
    }
    for (const char* level : {"1", "2"}) {
        if (fs::exists(dir / "tiles" / level)) {
            EXPECT_TRUE(fs::is_empty(dir / "tiles" / level)) << "a tile was baked";
        }
    }
}

TEST(Bake, AnotherScenesBakeIsRefusedNamingBothHashesUnlessForced)
{
    const fs::path dir = test::freshTestDir();
    const Scene caves = parseScene(CAVE_SCENE, "caves.toml");
    std::string otherText = CAVE_SCENE;
    otherText.replace(otherText.find("seed = 11"), 9, "seed = 12");
    const Scene other = parseScene(otherText, "other.toml");
    bakeInto(caves, dir, smallBake());
    const auto before = filesUnder(dir);
    BakeOptions options = smallBake();
    options.outputDir = dir;
    const BakePlan plan = planBake(other, options);
    try {
        bake(other, options, plan);
        ADD_FAILURE() << "baked over another scene's bake";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::BadInput);
        const std::string message = e.what();
        EXPECT_NE(message.find(planBake(caves, options).sceneHash.substr(0, 16)), std::string::npos) << message;
        EXPECT_NE(message.find(plan.sceneHash.substr(0, 16)), std::string::npos) << message;
        EXPECT_NE(message.find("--force"), std::string::npos) << message;
    }
    EXPECT_EQ(filesUnder(dir), before) << "the refused bake changed the folder";
    options.force = true;
    const BakeSummary forced = bake(other, options, plan);
    EXPECT_EQ(forced.baked, 18);
    EXPECT_EQ(readJson(dir / "manifest.json")["seed"], 12);
}

TEST(Bake, TheWorldRendersFromItsTilesCoarserWhenFar)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
    bakeInto(scene, dir, smallBake());
    const Scene baked = loadBakedScene(dir);
    EXPECT_EQ(baked.text, scene.text);
    WorldSnapshotOptions options;
    options.width = 160;
    options.height = 90;
    options.request.backend = "cpu";
    render::Image near, far;
    const WorldSnapshotStats close =
        renderBakedWorld(baked, dir, options, nullptr, [&](const render::Image& image) { near = image; });
    EXPECT_GT(close.tilesPerLevel[0], 0);
    EXPECT_EQ(near.width, 160);
    options.request.cameraPosition = glm::dvec3(2000.0, 1500.0, 2000.0);
    options.request.cameraTarget = glm::dvec3(0.0);
    options.request.fov = 10.0;
    const WorldSnapshotStats distant =
        renderBakedWorld(baked, dir, options, nullptr, [&](const render::Image& image) { far = image; });
    EXPECT_EQ(distant.tilesPerLevel[0], 0) << "far away no tile needs level 0";
    EXPECT_GT(distant.tilesPerLevel[2], 0);
    EXPECT_LT(distant.triangles, close.triangles);
}

TEST(Bake, TheCliBakesResumesAndRendersTheWorld)
{
    STRATA_REQUIRE_PROGRAM();
    const fs::path dir = test::freshTestDir();
    {
        std::ofstream(dir / "caves.toml") << CAVE_SCENE;
    }
    const test::CommandResult help = test::runStrata("bake --help", dir);
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.output.find("--tile-size"), std::string::npos);

    const test::CommandResult bad = test::runStrata("bake " + (dir / "caves.toml").string() + " -o " +
                                                        (dir / "out").string() + " --tile-size 16.3",
                                                    dir);
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("strata: error: --tile-size 16.3"), std::string::npos) << bad.output;
    EXPECT_FALSE(fs::exists(dir / "out"));

    const std::string bakeArgs = "bake " + (dir / "caves.toml").string() + " -o " + (dir / "out").string() +
                                 " --tile-size 16 --lods 2 --no-grids";
    const test::CommandResult baked = test::runStrata(bakeArgs, dir);
    ASSERT_EQ(baked.exitCode, 0) << baked.output;
    EXPECT_NE(baked.output.find("18 baked"), std::string::npos) << baked.output;
    EXPECT_FALSE(fs::exists(dir / "out/grids"));
    const test::CommandResult resumed = test::runStrata(bakeArgs, dir);
    EXPECT_NE(resumed.output.find("0 baked, 18 kept"), std::string::npos) << resumed.output;

    const test::CommandResult outOfRange = test::runStrata(bakeArgs + " --tiles 40", dir);
    EXPECT_EQ(outOfRange.exitCode, 2);
    EXPECT_NE(outOfRange.output.find("tile 40 is out of range: the world has 18 tiles"), std::string::npos)
        << outOfRange.output;

    const test::CommandResult render = test::runStrata(
        "render " + (dir / "out").string() + " -o " + (dir / "world.png").string() + " --backend cpu --size 160x90", dir);
    ASSERT_EQ(render.exitCode, 0) << render.output;
    EXPECT_TRUE(fs::exists(dir / "world.png"));
    const test::CommandResult mixed = test::runStrata(
        "render " + (dir / "out").string() + " -o " + (dir / "x.png").string() + " --seed 3", dir);
    EXPECT_EQ(mixed.exitCode, 2);
    EXPECT_NE(mixed.output.find("--seed cannot be used"), std::string::npos) << mixed.output;
}

// The same scene and heightmap read through another path (a cluster node
// that mounts the shared folder elsewhere, another working directory) is
// the same bake: the scene hash names input files as the scene does
// (issue 43; it hashed the path as given, so a worker refused the folder as
// "another scene").
TEST(Bake, TheSameSceneThroughAnotherPathIsTheSameBake)
{
    const fs::path dir = test::freshTestDir();
    fs::create_directories(dir / "share");
    std::vector<float> pixels(16 * 16, 0.25f);
    std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create((dir / "share" / "height.tif").string());
    ASSERT_TRUE(out);
    ASSERT_TRUE(out->open((dir / "share" / "height.tif").string(), OIIO::ImageSpec(16, 16, 1, OIIO::TypeDesc::FLOAT)));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
    out->close();
    std::ofstream(dir / "share" / "scene.toml") << "[terrain]\nroot = \"land\"\n[terrain.nodes.land]\n"
                                                   "type = \"image_heightfield\"\nfile = \"height.tif\"\n"
                                                   "[region]\nmin = [-16.0, -4.0, -16.0]\nmax = [16.0, 12.0, 16.0]\n";
    fs::create_directory_symlink(dir / "share", dir / "mounted-elsewhere");
    BakeOptions options = smallBake();
    const std::string direct = planBake(loadScene(dir / "share" / "scene.toml"), options).sceneHash;
    const std::string other = planBake(loadScene(dir / "mounted-elsewhere" / "scene.toml"), options).sceneHash;
    const fs::path before = fs::current_path();
    fs::current_path(dir / "share");
    const std::string relative = planBake(loadScene("scene.toml"), options).sceneHash;
    fs::current_path(before);
    EXPECT_EQ(other, direct);
    EXPECT_EQ(relative, direct);
}

TEST(Bake, AChangedHeightmapIsAnotherBake)
{
    // The scene hash covers the heightmap's contents, not only the scene
    // text: after the image changes, resuming into the old folder is refused.
    const fs::path dir = test::freshTestDir();
    const auto writeImage = [&](float slope) {
        std::vector<float> pixels(32 * 32);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) pixels[std::size_t(y * 32 + x)] = slope * float(x + y) / 62.0f;
        std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create((dir / "height.tif").string());
        ASSERT_TRUE(out);
        ASSERT_TRUE(out->open((dir / "height.tif").string(), OIIO::ImageSpec(32, 32, 1, OIIO::TypeDesc::FLOAT)));
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()));
        out->close();
    };
    writeImage(1.0f);
    std::ofstream(dir / "scene.toml") << R"(
[terrain]
root = "land"
[terrain.nodes.land]
type = "image_heightfield"
file = "height.tif"
min = [-16.0, -16.0]
max = [16.0, 16.0]
height_scale = 8.0
[region]
min = [-16.0, -4.0, -16.0]
max = [16.0, 12.0, 16.0]
[sampling]
voxel_size = 0.5
)";
    BakeOptions options = smallBake();
    options.grids = false;
    const Scene first = loadScene(dir / "scene.toml");
    ASSERT_EQ(first.inputFiles.size(), 1u);
    bakeInto(first, dir / "out", options);
    EXPECT_EQ(loadBakedScene(dir / "out").inputFiles.size(), 1u);
    const std::string before = planBake(first, options).sceneHash;

    writeImage(0.5f); // same scene text, other heights
    const Scene second = loadScene(dir / "scene.toml");
    EXPECT_EQ(second.text, first.text);
    EXPECT_NE(planBake(second, options).sceneHash, before);
    try {
        bakeInto(second, dir / "out", options);
        ADD_FAILURE() << "resumed a bake of other heights";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("another scene"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loadBakedScene(dir / "out"), Error) << "the folder's scene no longer matches its heightmap";
}

// Workers record which machine baked each tile (provenance/I.json: host,
// architecture, scheduler task); finalize reports it, and the tiles,
// records and manifest are the bytes of a single process, which writes no
// provenance. A bake forced over the folder removes the old provenance.
TEST(Bake, WorkersRecordWhichHostBakedEachTileAndFinalizeReportsIt)
{
    const Scene scene = parseScene(HILL_SCENE, "<hills>");
    const fs::path dir = test::freshTestDir();
    BakeOptions options = smallBake(1);
    options.lods = 1;
    const BakeSummary single = bakeInto(scene, dir / "single", options);
    EXPECT_FALSE(fs::exists(dir / "single" / "provenance"));
    EXPECT_TRUE(single.bakedBy.empty());

    options.worker = true;
    ::setenv("SLURM_ARRAY_JOB_ID", "77", 1);
    ::setenv("SLURM_ARRAY_TASK_ID", "1", 1);
    options.tiles = "0-1";
    bakeInto(scene, dir / "workers", options);
    options.tiles = "2-3";
    bakeInto(scene, dir / "workers", options);
    ::unsetenv("SLURM_ARRAY_JOB_ID");
    ::unsetenv("SLURM_ARRAY_TASK_ID");
    const BakeSummary summary = finalizeBake(dir / "workers");

    char host[256] = {};
    ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
    ASSERT_EQ(summary.bakedBy.size(), 1u);
    EXPECT_EQ(summary.bakedBy[0].host, host);
#if defined(__x86_64__)
    EXPECT_EQ(summary.bakedBy[0].arch, "x86_64");
#elif defined(__aarch64__)
    EXPECT_EQ(summary.bakedBy[0].arch, "aarch64");
#endif
    EXPECT_EQ(summary.bakedBy[0].tiles, (std::vector<int>{0, 1, 2, 3}));
    const nlohmann::json record = readJson(dir / "workers" / "provenance" / "2.json");
    EXPECT_EQ(record.at("tile"), 2);
    EXPECT_EQ(record.at("job"), "77_1");
    EXPECT_GE(record.at("seconds").get<double>(), 0.0);
    EXPECT_EQ(indexRanges(summary.bakedBy[0].tiles, ", "), "0-3");

    // Everything but the provenance is the single process's bytes.
    std::map<std::string, std::string> workers = filesUnder(dir / "workers");
    std::erase_if(workers, [](const auto& file) { return file.first.starts_with("provenance/"); });
    EXPECT_EQ(workers, filesUnder(dir / "single"));

    // A damaged provenance file is not read, nor is one far larger than a
    // worker writes: their tiles are reported as baked by "unknown".
    std::ofstream(dir / "workers" / "provenance" / "3.json") << "{not json";
    fs::resize_file(dir / "workers" / "provenance" / "2.json", std::uintmax_t(1) << 32); // sparse: 4 GiB claimed
    const BakeSummary damaged = finalizeBake(dir / "workers");
    EXPECT_EQ(damaged.bakedBy.at(0).tiles, (std::vector<int>{0, 1}));
    ASSERT_EQ(damaged.bakedBy.size(), 2u);
    EXPECT_EQ(damaged.bakedBy[1].host, "unknown");
    EXPECT_EQ(damaged.bakedBy[1].tiles, (std::vector<int>{2, 3}));

    // A bake of another scene forced over the folder removes the old log.
    options.worker = false;
    options.tiles = "all";
    options.force = true;
    bakeInto(parseScene(std::string(HILL_SCENE) + "\n# another\n", "<other>"), dir / "workers", options);
    EXPECT_FALSE(fs::exists(dir / "workers" / "provenance"));
}
