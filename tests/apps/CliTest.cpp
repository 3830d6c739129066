// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The strata executable end to end, as a user runs it.

#include "RunStrata.h"
#include "TestDir.h"

#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/render/Image.h>

#include <OpenImageIO/imageio.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

/// The non-empty lines of `text`.
std::vector<std::string> linesOf(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (!line.empty()) lines.push_back(line);
    }
    return lines;
}

/// An 8x8 RGB ramp as PNG bytes (written by OpenImageIO): a heightmap or a
/// normal map.
std::string pngBytes(const std::filesystem::path& dir)
{
    std::vector<unsigned char> pixels(8 * 8 * 3);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<unsigned char>(i);
    const std::filesystem::path path = dir / "good.png";
    auto out = OIIO::ImageOutput::create(path.string());
    EXPECT_TRUE(out && out->open(path.string(), OIIO::ImageSpec(8, 8, 3, OIIO::TypeDesc::UINT8)));
    EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(Cli, HelpListsTheCommands)
{
    const auto dir = strata::test::freshTestDir();
    const CommandResult run = runStrata("--help", dir);
    EXPECT_EQ(run.exitCode, 0);
    EXPECT_NE(run.output.find("generate"), std::string::npos) << run.output;
    const CommandResult generateHelp = runStrata("generate --help", dir);
    EXPECT_EQ(generateHelp.exitCode, 0);
    EXPECT_NE(generateHelp.output.find("--seed"), std::string::npos) << generateHelp.output;
    EXPECT_NE(generateHelp.output.find("--size"), std::string::npos);
}

TEST(Cli, GenerateDefaultSceneEndToEnd)
{
    const auto dir = strata::test::freshTestDir();
    const auto out = dir / "default";
    const CommandResult run = runStrata("generate -o " + out.string() + " --size 320x180", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    for (const char* stage : {"generate", "mesh", "render", "total"}) {
        EXPECT_NE(run.output.find(stage), std::string::npos) << "stage time missing: " << stage << "\n" << run.output;
    }

    std::ifstream reportFile(out / "report.json");
    ASSERT_TRUE(reportFile) << "report.json missing";
    const nlohmann::json report = nlohmann::json::parse(reportFile);
    EXPECT_EQ(report.at("seed").get<int>(), 1);
    EXPECT_DOUBLE_EQ(report.at("voxel_size").get<double>(), 0.5);
    EXPECT_GT(report.at("active_voxels").get<long>(), 100000);
    EXPECT_GT(report.at("vertices").get<long>(), 10000);
    EXPECT_GT(report.at("triangles").get<long>(), 10000);
    for (const char* stage : {"generate", "mesh", "render", "total"}) {
        EXPECT_GT(report.at("timings").at(stage).get<double>(), 0.0) << stage;
    }

    const openvdb::FloatGrid::Ptr grid = strata::meshing::readLevelSet(out / "terrain.vdb");
    EXPECT_EQ(std::uint64_t(grid->activeVoxelCount()), report.at("active_voxels").get<std::uint64_t>());

    const strata::meshing::TriangleMesh mesh = strata::meshing::readGltf(out / "terrain.glb");
    EXPECT_EQ(mesh.triangleCount(), report.at("triangles").get<std::size_t>());
    EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
    EXPECT_EQ(strata::meshing::analyzeTopology(mesh).inconsistentEdges, 0u);

    const strata::render::Image image = strata::render::readImage(out / "snapshot.png");
    EXPECT_EQ(image.width, 320);
    EXPECT_EQ(image.height, 180);
    std::size_t differing = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            differing += std::memcmp(image.at(x, y), image.at(0, 0), 3) != 0;
        }
    }
    EXPECT_GT(differing, std::size_t(image.width * image.height / 4)) << "the snapshot is nearly constant";

    // Nothing else is left in the directory (no temporary files).
    std::size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(out)) ++files;
    EXPECT_EQ(files, 4u);
}

TEST(Cli, SameSeedSameBytesOnAnyThreadCount)
{
    const auto dir = strata::test::freshTestDir();
    // A small scene keeps this quick; the determinism is the same at any size.
    {
        std::ofstream(dir / "small.toml") << "seed = 5\n[region]\nmin = [-24, -20, -24]\nmax = [24, 20, 24]\n";
    }
    const std::string scene = (dir / "small.toml").string();
    ASSERT_EQ(runStrata("generate " + scene + " -o " + (dir / "one").string() + " --threads 1 --no-snapshot", dir).exitCode, 0);
    ASSERT_EQ(runStrata("generate " + scene + " -o " + (dir / "two").string() + " --threads 2 --no-snapshot", dir).exitCode, 0);
    auto bytes = [](const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    };
    EXPECT_EQ(bytes(dir / "one" / "terrain.glb"), bytes(dir / "two" / "terrain.glb"));
    EXPECT_EQ(bytes(dir / "one" / "terrain.vdb"), bytes(dir / "two" / "terrain.vdb"));
}

TEST(Cli, BadSceneExitsWithTwoAndWritesNothing)
{
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream(dir / "bad.toml") << "seed = 3\n[sampling]\nvoxel_size = 0\n";
    }
    const CommandResult run = runStrata("generate " + (dir / "bad.toml").string() + " -o " + (dir / "out").string(), dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("bad.toml:3: sampling.voxel_size = 0"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "terrain.vdb"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "report.json"));

    const CommandResult badSize = runStrata("generate -o " + (dir / "out").string() + " --size 12by3", dir);
    EXPECT_EQ(badSize.exitCode, 2);
    EXPECT_NE(badSize.output.find("--size"), std::string::npos) << badSize.output;

    const CommandResult missing = runStrata("generate /nonexistent.toml -o " + (dir / "out").string(), dir);
    EXPECT_EQ(missing.exitCode, 2);
}

// libpng prints "libpng error: ..." on stderr for a corrupt PNG before
// OpenImageIO reports the failure: the user sees one `strata: error:` line
// naming the key and the file, nothing else, and no output folder.
TEST(Cli, CorruptPngHeightmapOrMaterialMapGivesOneErrorLine)
{
    const auto dir = strata::test::freshTestDir();
    const std::string good = pngBytes(dir);
    ASSERT_GT(good.size(), 60u);
    const std::size_t idat = good.find("IDAT");
    ASSERT_NE(idat, std::string::npos);
    std::string badCrc = good;
    const std::size_t length = (std::size_t(std::uint8_t(good[idat - 4])) << 24) | (std::size_t(std::uint8_t(good[idat - 3])) << 16) |
                               (std::size_t(std::uint8_t(good[idat - 2])) << 8) | std::size_t(std::uint8_t(good[idat - 1]));
    badCrc[idat + 4 + length] = char(badCrc[idat + 4 + length] ^ 0x5a); // the IDAT chunk's CRC
    const std::map<std::string, std::string> corrupt = {{"badcrc.png", badCrc}, {"truncated.png", good.substr(0, idat + 12)}};
    for (const auto& [name, bytes] : corrupt) {
        std::ofstream(dir / name, std::ios::binary) << bytes;
    }
    struct Case
    {
        std::string scene, key;
    };
    for (const auto& [name, bytes] : corrupt) {
        for (const Case& c :
             {Case{"[terrain]\nroot = \"a\"\n[terrain.nodes.a]\ntype = \"image_heightfield\"\nfile = \"" + name + "\"\n",
                   "terrain.nodes.a.file = '"},
              Case{"[material.maps.normal]\nfile = \"" + name + "\"\n", "material.maps.normal"}}) {
            {
                std::ofstream(dir / "scene.toml") << c.scene;
            }
            for (const std::string flags : {"", " --no-snapshot"}) {
                const CommandResult run =
                    runStrata("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string() + " -q" + flags, dir);
                EXPECT_EQ(run.exitCode, 2) << name << flags << "\n" << run.output;
                const std::vector<std::string> lines = linesOf(run.output);
                ASSERT_EQ(lines.size(), 1u) << name << flags << "\n" << run.output;
                EXPECT_EQ(lines[0].rfind("strata: error: ", 0), 0u) << lines[0];
                EXPECT_NE(lines[0].find(c.key), std::string::npos) << lines[0];
                EXPECT_NE(lines[0].find(name), std::string::npos) << lines[0];
                EXPECT_EQ(run.output.find("libpng"), std::string::npos) << run.output;
                EXPECT_FALSE(std::filesystem::exists(dir / "out")) << name << flags;
            }
        }
    }
}

/// `strata generate` of the default scene at the accurate preset, sent
/// `signal` (a kill(1) name) once it has said it started and loaded its
/// material (its handler is installed first thing), while the terrain is
/// still being sampled. Waiting for the line, not a fixed delay, keeps a
/// slow start on a loaded machine from racing it. Returns the exit status
/// and the output.
std::pair<int, std::string> generateAndSignal(const std::filesystem::path& dir, const std::string& signal)
{
    const auto out = dir / "out";
    const std::string log = (dir / "log.txt").string();
    const std::string command = "bash -c '" + std::string(STRATA_EXECUTABLE) + " generate -o " + out.string() +
                                " --backend cpu --preset accurate > " + log + " 2>&1 & pid=$!; " +
                                "for i in $(seq 1 600); do grep -q material " + log +
                                " && break; sleep 0.05; done; kill -" + signal + " $pid; wait $pid; exit $?'";
    const int status = std::system(command.c_str());
    std::ifstream in(log);
    return {status, std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>())};
}

TEST(Cli, CtrlCStopsTheRunWritesNothingAndExits130)
{
    // The run stops at its next check, before any file or folder is made.
    const auto dir = strata::test::freshTestDir();
    const auto [status, text] = generateAndSignal(dir, "INT");
    ASSERT_TRUE(WIFEXITED(status)) << text;
    EXPECT_EQ(WEXITSTATUS(status), 130) << text;
    EXPECT_NE(text.find("interrupted"), std::string::npos) << text;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "an interrupted run left " << (dir / "out");
}

TEST(Cli, SigtermStopsTheRunAsCtrlCDoesAndExits143)
{
    // What Slurm sends on scancel and at a job's time limit: the same clean
    // stop (no half-written output), exit 128 + SIGTERM. bash reports 143
    // for a death by the signal too; the message tells them apart (before
    // this the process died of the signal, saying nothing).
    const auto dir = strata::test::freshTestDir();
    const auto [status, text] = generateAndSignal(dir, "TERM");
    ASSERT_TRUE(WIFEXITED(status)) << text;
    EXPECT_EQ(WEXITSTATUS(status), 143) << text;
    EXPECT_NE(text.find("interrupted"), std::string::npos) << text;
    EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "an interrupted run left " << (dir / "out");
}

// Exit code 1 is for failures of the system, not of the input: an output
// that cannot be written (a file stands where a parent folder should be;
// the tests run as root, so a read-only folder would not stop them) and a
// GL context that cannot be had. Bad input is 2 (above), Ctrl-C 130 (above),
// success 0 (GenerateDefaultSceneEndToEnd).
TEST(Cli, UnwritableOutputExitsWithOne)
{
    const auto dir = strata::test::freshTestDir();
    std::ofstream(dir / "blocker") << "a file, not a folder\n";
    const auto out = dir / "blocker" / "out";
    const CommandResult generate = runStrata("generate -o " + out.string() + " --no-snapshot -q", dir);
    EXPECT_EQ(generate.exitCode, 1) << generate.output;
    EXPECT_NE(generate.output.find("strata: error: cannot create output directory '" + out.string() + "'"),
              std::string::npos)
        << generate.output;

    const auto benchOut = dir / "blocker" / "bench";
    const CommandResult bench = runStrata("bench -o " + benchOut.string() + " --tiny", dir);
    EXPECT_EQ(bench.exitCode, 1) << bench.output; // was 2: bench's write errors defaulted to bad input
    EXPECT_NE(bench.output.find(benchOut.string()), std::string::npos) << bench.output;

    const CommandResult bake = runStrata("bake -o " + (dir / "blocker" / "bake").string() + " --tile-size 64", dir);
    EXPECT_EQ(bake.exitCode, 1) << bake.output;
    EXPECT_NE(bake.output.find((dir / "blocker" / "bake").string()), std::string::npos) << bake.output;
}

TEST(Cli, NoGlContextForBackendGlExitsWithOne)
{
    // GLVND finds no EGL vendor library: no EGL display at all. That is the
    // machine's failure, not the user's input (it was rewrapped as bad input).
    const auto dir = strata::test::freshTestDir();
    const auto out = dir / "out";
    const CommandResult run = strata::test::runStrataWithEnvironment(
        "__EGL_VENDOR_LIBRARY_FILENAMES=" + (dir / "no-such-vendor.json").string(),
        "generate -o " + out.string() + " --backend gl -q", dir);
    EXPECT_EQ(run.exitCode, 1) << run.output;
    EXPECT_NE(run.output.find("--backend gl: no OpenGL context"), std::string::npos) << run.output;
    EXPECT_FALSE(std::filesystem::exists(out)) << "a run that cannot render wrote files";
}

TEST(Cli, FinalizeNamesTilesWithoutProvenance)
{
    // A worker's provenance is a best-effort log (a full disk may refuse it
    // after the tile is written): finalize names such tiles, not drops them.
    const auto dir = strata::test::freshTestDir();
    const auto bake = dir / "bake";
    const CommandResult worker =
        runStrata("bake -o " + bake.string() + " --tile-size 64 --lods 1 --worker --tile 0 --tiles-per-worker 64 -q", dir);
    ASSERT_EQ(worker.exitCode, 0) << worker.output;
    ASSERT_TRUE(std::filesystem::remove(bake / "provenance" / "1.json"));
    const CommandResult finalize = runStrata("bake " + bake.string() + " --finalize", dir);
    ASSERT_EQ(finalize.exitCode, 0) << finalize.output;
    EXPECT_NE(finalize.output.find("tiles: 0, 2-17\n"), std::string::npos) << finalize.output;
    EXPECT_NE(finalize.output.find("baked by  unknown (no provenance file): 1 tiles: 1\n"), std::string::npos)
        << finalize.output;
}
