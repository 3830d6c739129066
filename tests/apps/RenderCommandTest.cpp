// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata render` and `strata generate --backend cpu`, end to end.

#include "RunStrata.h"
#include "TestDir.h"

#include <strata/render/Image.h>

#include <gtest/gtest.h>

#include <fstream>

namespace {

using Result = strata::test::CommandResult;
const auto run = strata::test::runStrata;

/// A small scene: a cube-ish bump of terrain, quick to generate.
void writeSmallScene(const std::filesystem::path& path, const std::string& material)
{
    std::ofstream out(path);
    out << "seed = 3\n[region]\nmin = [-16.0, -8.0, -16.0]\nmax = [16.0, 8.0, 16.0]\n"
           "[sampling]\nvoxel_size = 0.5\n[snapshot]\nwidth = 160\nheight = 90\n"
        << material;
}

bool looksRendered(const strata::render::Image& image)
{
    std::size_t differing = 0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            differing += image.at(x, y)[0] != image.at(0, 0)[0] || image.at(x, y)[1] != image.at(0, 0)[1];
        }
    }
    return differing > std::size_t(image.width * image.height / 10);
}

} // namespace

TEST(RenderCommand, RendersAMeshFileOnTheCpu)
{
    const auto dir = strata::test::freshTestDir();
    // A tetrahedron in OBJ, counter-clockwise seen from outside, no normals.
    std::ofstream(dir / "tet.obj") << "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 0 0 4\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    writeSmallScene(dir / "scene.toml", "[material]\nside = \"circuitry\"\ntop = \"grass\"\ntexture_size = 64\n");
    const Result r = run("render " + (dir / "scene.toml").string() + " --mesh " + (dir / "tet.obj").string() + " -o " +
                             (dir / "tet.png").string() + " --backend cpu --size 120x90",
                         dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const strata::render::Image image = strata::render::readImage(dir / "tet.png");
    EXPECT_EQ(image.width, 120);
    EXPECT_EQ(image.height, 90);
    EXPECT_TRUE(looksRendered(image));
    EXPECT_NE(r.output.find("mask+height+normal+top"), std::string::npos) << r.output;
}

TEST(RenderCommand, RendersASceneToExrAndIsDeterministicAcrossThreads)
{
    const auto dir = strata::test::freshTestDir();
    writeSmallScene(dir / "scene.toml", "[material]\ntexture_size = 64\n");
    const std::string base = (dir / "scene.toml").string() + " --backend cpu";
    ASSERT_EQ(run("render " + base + " -o " + (dir / "one.png").string() + " --threads 1", dir).exitCode, 0);
    ASSERT_EQ(run("render " + base + " -o " + (dir / "two.png").string() + " --threads 2", dir).exitCode, 0);
    const auto one = strata::render::readImage(dir / "one.png");
    const auto two = strata::render::readImage(dir / "two.png");
    EXPECT_EQ(one.pixels, two.pixels);
    EXPECT_TRUE(looksRendered(one));
    const Result exr = run("render " + base + " -o " + (dir / "shot.exr").string(), dir);
    ASSERT_EQ(exr.exitCode, 0) << exr.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "shot.exr"));
    // No scratch folder is left behind.
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
        EXPECT_EQ(entry.path().filename().string().rfind(".strata-render", 0), std::string::npos) << entry.path();
    }
}

TEST(RenderCommand, GenerateWithTheCpuBackend)
{
    const auto dir = strata::test::freshTestDir();
    writeSmallScene(dir / "scene.toml", "");
    const Result r =
        run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string() + " --backend cpu", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    const strata::render::Image image = strata::render::readImage(dir / "out" / "snapshot.png");
    EXPECT_EQ(image.width, 160);
    EXPECT_TRUE(looksRendered(image));
    EXPECT_NE(r.output.find("cpu"), std::string::npos) << r.output;
}

TEST(RenderCommand, BadInputIsExitCodeTwo)
{
    const auto dir = strata::test::freshTestDir();
    EXPECT_EQ(run("render -o " + (dir / "x.png").string() + " --backend vulkan", dir).exitCode, 2);
    EXPECT_EQ(run("generate -o " + (dir / "x").string() + " --backend vulkan", dir).exitCode, 2);
    writeSmallScene(dir / "scene.toml", "[material.maps.albedo]\nfile = \"missing.png\"\n");
    const Result r = run("render " + (dir / "scene.toml").string() + " -o " + (dir / "x.png").string(), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.output.find("missing.png"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("material.maps.albedo"), std::string::npos) << r.output;
}
