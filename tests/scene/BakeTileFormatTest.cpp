// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bake --tile-format`: compact tiles (KHR_mesh_quantization +
// EXT_meshopt_compression, the default) hold the plain tiles' triangles
// within the position bound, several times smaller; decoded, a level's
// tiles still weld with boundary only on the region's border (the grid is
// shared, so seam vertices decode identically); the world renders from
// them like from plain tiles; the format is part of the bake's identity.

#include <strata/scene/Bake.h>
#include <strata/scene/Scene.h>
#include "RunStrata.h"
#include "../SmallScene.h"
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

using namespace strata;
using namespace strata::scene;
namespace fs = std::filesystem;

namespace {

/// Hills minus worm tunnels over 40 × 20 × 40 m at 0.5 m (BakeTest's cave
/// scene): with 16 m tiles, 3 × 3 columns of two slabs.
const char* const CAVE_SCENE = strata::test::BAKE_CAVE_SCENE;

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

BakeOptions smallBake(TileFormat format)
{
    BakeOptions options;
    options.tileSize = 16.0;
    options.lods = 3;
    options.grids = false;
    options.tileFormat = format;
    return options;
}

/// One baked world, both formats, shared by the tests (baked once).
struct TwoBakes
{
    fs::path dir;
    BakePlan plan;
    nlohmann::json plain, compact; ///< manifests
};

const TwoBakes& twoBakes()
{
    static const TwoBakes bakes = [] {
        TwoBakes b;
        b.dir = test::freshTestDir();
        const Scene scene = parseScene(CAVE_SCENE, "caves.toml");
        for (const TileFormat format : {TileFormat::Plain, TileFormat::Meshopt}) {
            BakeOptions options = smallBake(format);
            options.outputDir = b.dir / tileFormatName(format);
            b.plan = planBake(scene, options);
            bake(scene, options, b.plan);
        }
        b.plain = nlohmann::json::parse(readBytes(b.dir / "plain/manifest.json"));
        b.compact = nlohmann::json::parse(readBytes(b.dir / "meshopt/manifest.json"));
        return b;
    }();
    return bakes;
}

/// The largest distance (max norm) from a vertex that a triangle of `from`
/// uses to the nearest vertex of `to`, in world coordinates (unused
/// vertices do not count: the compact writer drops them).
double worstNearest(const meshing::TriangleMesh& from, const meshing::TriangleMesh& to)
{
    std::map<std::array<long long, 3>, std::vector<glm::dvec3>> buckets;
    for (const glm::vec3& p : to.positions) {
        const glm::dvec3 w = to.origin + glm::dvec3(p);
        buckets[{(long long)std::floor(w.x), (long long)std::floor(w.y), (long long)std::floor(w.z)}].push_back(w);
    }
    double worst = 0.0;
    std::vector<bool> used(from.positions.size(), false);
    for (const std::uint32_t i : from.indices) used[i] = true;
    for (std::size_t i = 0; i < from.positions.size(); ++i) {
        if (!used[i]) continue;
        const glm::dvec3 w = from.origin + glm::dvec3(from.positions[i]);
        double best = 1e300;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto found = buckets.find({(long long)std::floor(w.x) + dx, (long long)std::floor(w.y) + dy,
                                                     (long long)std::floor(w.z) + dz});
                    if (found == buckets.end()) continue;
                    for (const glm::dvec3& q : found->second) {
                        const glm::dvec3 d = glm::abs(q - w);
                        best = std::min(best, std::max({d.x, d.y, d.z}));
                    }
                }
        worst = std::max(worst, best);
    }
    return worst;
}

} // namespace

TEST(BakeTileFormat, CompactTilesHoldThePlainTrianglesInAFractionOfTheBytes)
{
    const TwoBakes& b = twoBakes();
    EXPECT_EQ(b.plain["tile_format"], "plain");
    EXPECT_EQ(b.compact["tile_format"], "meshopt");
    ASSERT_EQ(b.plain["tiles"].size(), b.compact["tiles"].size());
    // The grid: 1/1024 voxel here (16 m tiles, 4 m skirts and a 2 m coarsest
    // cell of slack each side are 28 m, 56 voxels, in 16 bits): every decoded
    // vertex lies within half a step of a plain one.
    const double bound = 0.5 * b.plan.voxelSize / 1024.0;
    std::map<int, std::uint64_t> plainBytes, compactBytes;
    std::size_t files = 0;
    for (std::size_t t = 0; t < b.plain["tiles"].size(); ++t) {
        const auto& plainTile = b.plain["tiles"][t];
        const auto& compactTile = b.compact["tiles"][t];
        for (std::size_t l = 0; l < plainTile["levels"].size(); ++l) {
            const auto& p = plainTile["levels"][l];
            const auto& c = compactTile["levels"][l];
            EXPECT_EQ(p["triangles"], c["triangles"]);
            EXPECT_EQ(p["skirt_triangles"], c["skirt_triangles"]);
            if (p["file"].is_null()) {
                EXPECT_TRUE(c["file"].is_null());
                continue;
            }
            const std::string path = p["file"]["path"];
            const meshing::TriangleMesh plain = meshing::readGltf(b.dir / "plain" / path);
            const meshing::TriangleMesh compact = meshing::readGltf(b.dir / "meshopt" / path);
            ASSERT_EQ(compact.triangleCount(), plain.triangleCount()) << path;
            ASSERT_EQ(compact.normals.size(), compact.vertexCount()) << path;
            EXPECT_LE(worstNearest(compact, plain), bound + 1e-9) << path;
            EXPECT_LE(worstNearest(plain, compact), bound + 1e-9) << path;
            plainBytes[int(l)] += p["file"]["bytes"].get<std::uint64_t>();
            compactBytes[int(l)] += c["file"]["bytes"].get<std::uint64_t>();
            ++files;
        }
    }
    EXPECT_GE(files, 30u);
    for (const auto& [level, bytes] : plainBytes) {
        const double ratio = double(bytes) / double(compactBytes[level]);
        std::cout << "[ tiles ] level " << level << ": plain " << bytes << " bytes, meshopt " << compactBytes[level]
                  << " (" << ratio << "x smaller)\n";
        // Tiles of 32 voxels carry more JSON per triangle than real ones
        // (3.8x here); the default scene's 256-voxel tiles are about 6x
        // smaller (docs/bake.md).
        if (level == 0) {
            EXPECT_GT(ratio, 3.0);
        }
    }
}

TEST(BakeTileFormat, DecodedCompactTilesOfALevelWeldWithBoundaryOnlyOnTheRegionBorder)
{
    // As Bake.ALevelsTilesWeldWithBoundaryOnlyOnTheRegionBorder, but from the
    // compact files as a client decodes them: seam vertices must decode to
    // the same world point in both tiles (bit for bit), or the weld leaves
    // boundary edges inside the region. Each file's first `triangles`
    // triangles are its surface (primitive 0), the rest its skirt.
    const TwoBakes& b = twoBakes();
    const glm::dvec3 lo = glm::dvec3(b.plan.minVoxel[0], b.plan.minVoxel[1], b.plan.minVoxel[2]) * b.plan.voxelSize;
    const glm::dvec3 hi = glm::dvec3(b.plan.maxVoxel[0], b.plan.maxVoxel[1], b.plan.maxVoxel[2]) * b.plan.voxelSize;
    for (int level = 0; level < b.plan.lods; ++level) {
        std::map<std::array<double, 3>, std::uint32_t> index;
        std::vector<std::array<double, 3>> positions;
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> uses;
        std::size_t degenerate = 0;
        for (const auto& tile : b.compact["tiles"]) {
            const auto& record = tile["levels"][std::size_t(level)];
            if (record["file"].is_null()) continue;
            const meshing::TriangleMesh mesh = meshing::readGltf(b.dir / "meshopt" / record["file"]["path"].get<std::string>());
            const std::size_t surfaceTriangles = record["triangles"];
            std::vector<std::uint32_t> local;
            for (const glm::vec3& p : mesh.positions) {
                const std::array<double, 3> key{mesh.origin.x + p.x, mesh.origin.y + p.y, mesh.origin.z + p.z};
                local.push_back(index.emplace(key, std::uint32_t(positions.size())).first->second);
                if (local.back() == positions.size()) positions.push_back(key);
            }
            for (std::size_t t = 0; t < surfaceTriangles; ++t) {
                const std::uint32_t a = local[mesh.indices[3 * t]], c = local[mesh.indices[3 * t + 1]],
                                    d = local[mesh.indices[3 * t + 2]];
                // A sliver the grid collapsed: its two remaining edges pair up.
                if (a == c || c == d || d == a) {
                    ++degenerate;
                    continue;
                }
                for (const auto& [u, v] : {std::pair{a, c}, std::pair{c, d}, std::pair{d, a}}) ++uses[std::minmax(u, v)];
            }
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
        EXPECT_EQ(inside, 0u) << "level " << level << ": decoded tiles leave boundary edges inside the region";
        EXPECT_LT(degenerate, uses.size() / 1000 + 10) << "level " << level;
    }
}

TEST(BakeTileFormat, TheWorldRendersFromCompactTilesAsFromPlainOnes)
{
    STRATA_REQUIRE_PROGRAM();
    const TwoBakes& b = twoBakes();
    // Beside the bakes (freshTestDir() would empty the folder they may be in).
    const fs::path dir = b.dir / "renders";
    fs::create_directories(dir);
    for (const char* format : {"plain", "meshopt"}) {
        const test::CommandResult render =
            test::runStrata("render " + (b.dir / format).string() + " -o " + (dir / (std::string(format) + ".png")).string() +
                                " --backend cpu --size 320x180 --max-screen-error 0.5",
                            dir);
        ASSERT_EQ(render.exitCode, 0) << render.output;
    }
    const OIIO::ImageBuf plain((dir / "plain.png").string()), compact((dir / "meshopt.png").string());
    const OIIO::ImageBufAlgo::CompareResults diff = OIIO::ImageBufAlgo::compare(plain, compact, 1.0f, 1.0f);
    EXPECT_FALSE(diff.error);
    std::cout << "[ render ] plain vs meshopt tiles: PSNR " << diff.PSNR << " dB, mean error " << diff.meanerror << "\n";
    EXPECT_GT(diff.PSNR, 35.0);
}

TEST(BakeTileFormat, TheDefaultIsCompactAndTheFormatIsPartOfTheBakesIdentity)
{
    STRATA_REQUIRE_PROGRAM();
    const fs::path dir = test::freshTestDir();
    {
        std::ofstream(dir / "caves.toml") << CAVE_SCENE;
    }
    const std::string bakeArgs = "bake " + (dir / "caves.toml").string() + " -o " + (dir / "out").string() +
                                 " --tile-size 16 --lods 1 --no-grids --tiles 4";
    const test::CommandResult baked = test::runStrata(bakeArgs, dir);
    ASSERT_EQ(baked.exitCode, 0) << baked.output;
    const std::string tile = readBytes(dir / "out/tiles/0/1_0_1.glb");
    EXPECT_NE(tile.find("\"extensionsRequired\":[\"EXT_meshopt_compression\",\"KHR_mesh_quantization\"]"),
              std::string::npos);
    // The same folder with plain tiles is another bake: refused, naming both formats.
    const test::CommandResult other = test::runStrata(bakeArgs + " --tile-format plain", dir);
    EXPECT_EQ(other.exitCode, 2) << other.output;
    EXPECT_NE(other.output.find("meshopt tiles; this bake"), std::string::npos) << other.output;
    EXPECT_NE(other.output.find("plain tiles)"), std::string::npos) << other.output;
    const test::CommandResult forced = test::runStrata(bakeArgs + " --tile-format plain --force", dir);
    ASSERT_EQ(forced.exitCode, 0) << forced.output;
    EXPECT_EQ(readBytes(dir / "out/tiles/0/1_0_1.glb").find("EXT_meshopt_compression"), std::string::npos);
    const test::CommandResult bad = test::runStrata(bakeArgs + " --tile-format draco", dir);
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.output.find("--tile-format"), std::string::npos) << bad.output;
}
