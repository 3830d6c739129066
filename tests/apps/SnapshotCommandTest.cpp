// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Snapshot flags of `strata generate` and `strata render`, end to end:
// backends auto/gl/cpu, camera presets and flags, turntables, EXR, bad
// values, and the default scene on GL versus the CPU renderer.

#include "ErodedScene.h"
#include "Parity.h"
#include "RunStrata.h"
#include "TestDir.h"

#include <strata/render/Image.h>

#include <OpenImageIO/imageio.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <regex>
#include <string>
#include <vector>

namespace {

using Result = strata::test::CommandResult;
using strata::render::Image;
Result run(const std::string& arguments, const std::filesystem::path& dir, const std::string& environment = "")
{
    return strata::test::runStrataWithEnvironment(environment, arguments, dir);
}

/// Makes EGL find no driver (glvnd reads this list of vendor files): the
/// machine then looks like one without OpenGL.
const std::string NO_EGL = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl-vendor.json";

/// A small scene and a tetrahedron mesh (OBJ, counter-clockwise seen from
/// outside) in `dir`: quick to render.
void writeTetrahedron(const std::filesystem::path& dir)
{
    std::ofstream(dir / "tet.obj") << "v 0 0 0\nv 4 0 0\nv 0 4 0\nv 0 0 4\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::ofstream(dir / "scene.toml") << "seed = 3\n[region]\nmin = [-16.0, -8.0, -16.0]\nmax = [16.0, 8.0, 16.0]\n"
                                         "[material]\ntexture_size = 64\n[snapshot]\nwidth = 96\nheight = 64\n";
}

std::string tetrahedron(const std::filesystem::path& dir)
{
    return (dir / "scene.toml").string() + " --mesh " + (dir / "tet.obj").string();
}

double standardDeviation(const Image& image)
{
    double sum = 0.0, sum2 = 0.0;
    const double n = double(image.width) * double(image.height) * 3.0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        sum += image.pixels[i];
        sum2 += double(image.pixels[i]) * double(image.pixels[i]);
    }
    return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

} // namespace

TEST(SnapshotCommand, BackendAutoUsesGlAndFallsBackToTheCpuWithANotice)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    // With EGL (llvmpipe in CI): OpenGL, no notice.
    const Result gl = run("render " + tetrahedron(dir) + " -o " + (dir / "auto.png").string(), dir);
    ASSERT_EQ(gl.exitCode, 0) << gl.output;
    EXPECT_TRUE(contains(gl.output, ", gl")) << gl.output;
    EXPECT_FALSE(contains(gl.output, "rendering on the CPU")) << gl.output;
    // Without: the CPU renderer, after one line on stderr.
    const Result fallback = run("render " + tetrahedron(dir) + " -o " + (dir / "fallback.png").string(), dir, NO_EGL);
    ASSERT_EQ(fallback.exitCode, 0) << fallback.output;
    EXPECT_TRUE(contains(fallback.output, "strata: no OpenGL context (")) << fallback.output;
    EXPECT_TRUE(contains(fallback.output, "); rendering on the CPU\n")) << fallback.output;
    EXPECT_TRUE(contains(fallback.output, ", cpu")) << fallback.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "fallback.png"));
    // --backend gl fails clearly instead, and writes nothing: exit 1, since
    // the machine, not the input, lacks a GL context.
    const Result forced =
        run("render " + tetrahedron(dir) + " -o " + (dir / "forced.png").string() + " --backend gl", dir, NO_EGL);
    EXPECT_EQ(forced.exitCode, 1) << forced.output;
    EXPECT_TRUE(contains(forced.output, "--backend gl: no OpenGL context")) << forced.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "forced.png"));
    // --backend cpu never asks for EGL.
    const Result cpu =
        run("render " + tetrahedron(dir) + " -o " + (dir / "cpu.png").string() + " --backend cpu", dir, NO_EGL);
    ASSERT_EQ(cpu.exitCode, 0) << cpu.output;
    EXPECT_FALSE(contains(cpu.output, "no OpenGL context")) << cpu.output;
    // generate: the same fallback, recorded in the report.
    const Result generate =
        run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string(), dir, NO_EGL);
    ASSERT_EQ(generate.exitCode, 0) << generate.output;
    EXPECT_TRUE(contains(generate.output, "rendering on the CPU")) << generate.output;
    std::ifstream report(dir / "out" / "report.json");
    const std::string text((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
    EXPECT_TRUE(contains(text, "CPU reference renderer")) << text;
}

TEST(SnapshotCommand, TurntableWritesNumberedFramesAroundTheTarget)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    const Result r =
        run("render " + tetrahedron(dir) + " -o " + (dir / "spin.png").string() + " --turntable 5 --backend cpu", dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "5 frames")) << r.output;
    std::vector<Image> frames;
    for (int i = 0; i < 5; ++i) {
        const auto path = dir / ("spin_00" + std::to_string(i) + ".png");
        ASSERT_TRUE(std::filesystem::exists(path)) << path;
        frames.push_back(strata::render::readImage(path));
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "spin_005.png"));
    EXPECT_FALSE(std::filesystem::exists(dir / "spin.png"));
    for (int i = 1; i < 5; ++i) {
        EXPECT_LT(strata::render::fractionWithin(frames[0], frames[std::size_t(i)], 2), 0.98) << "frame " << i;
    }
    // The first frame is the camera itself.
    const Result single =
        run("render " + tetrahedron(dir) + " -o " + (dir / "one.png").string() + " --backend cpu", dir);
    ASSERT_EQ(single.exitCode, 0) << single.output;
    EXPECT_EQ(strata::render::readImage(dir / "one.png").pixels, frames[0].pixels);
    // generate: DIR/snapshot_000.png ...
    const Result generate = run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string() +
                                    " --turntable 3 --backend cpu --no-snapshot",
                                dir);
    ASSERT_EQ(generate.exitCode, 0) << generate.output;
    const Result frames3 = run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string() +
                                   " --turntable 3 --backend cpu",
                               dir);
    ASSERT_EQ(frames3.exitCode, 0) << frames3.output;
    for (const char* name : {"snapshot_000.png", "snapshot_001.png", "snapshot_002.png"}) {
        EXPECT_TRUE(std::filesystem::exists(dir / "out" / name)) << name;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "snapshot_003.png"));
}

TEST(SnapshotCommand, ExrIsLinearFloatAndFinite)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    const Result r = run("render " + tetrahedron(dir) + " -o " + (dir / "shot.exr").string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    auto input = OIIO::ImageInput::open((dir / "shot.exr").string());
    ASSERT_TRUE(input) << OIIO::geterror();
    const OIIO::ImageSpec& spec = input->spec();
    EXPECT_EQ(spec.width, 96);
    EXPECT_EQ(spec.height, 64);
    ASSERT_GE(spec.nchannels, 3);
    EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
    std::vector<float> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
    ASSERT_TRUE(input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data()));
    float lo = 1e30f, hi = -1e30f;
    for (float v : pixels) {
        ASSERT_TRUE(std::isfinite(v));
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 0.0f);
    EXPECT_GT(hi, lo);
    // The PNG of the same view, decoded to linear, holds the same values.
    ASSERT_EQ(run("render " + tetrahedron(dir) + " -o " + (dir / "shot.png").string(), dir).exitCode, 0);
    const Image png = strata::render::readImage(dir / "shot.png");
    const Image exrAsBytes = strata::render::readImage(dir / "shot.exr");
    EXPECT_GE(strata::render::fractionWithin(png, exrAsBytes, 1), 0.999);
    // generate --snapshot-format exr writes DIR/snapshot.exr.
    const Result generate = run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "out").string() +
                                    " --snapshot-format exr --backend cpu",
                                dir);
    ASSERT_EQ(generate.exitCode, 0) << generate.output;
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / "snapshot.exr"));
    EXPECT_FALSE(std::filesystem::exists(dir / "out" / "snapshot.png"));
}

TEST(SnapshotCommand, BadValuesNameTheFlagExitTwoAndWriteNothing)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    struct Case
    {
        std::string flags;
        std::string expected; // in the message
    };
    const std::vector<Case> cases = {
        {"--backend vulkan", "--backend 'vulkan'"},
        {"--view side", "--view 'side'"},
        {"--camera-position 1,2", "--camera-position '1,2'"},
        {"--camera-position 1,2,3,4", "--camera-position '1,2,3,4'"},
        {"--camera-target a,b,c", "--camera-target 'a,b,c'"},
        {"--camera-position 1,2,3 --camera-target 1,2,3", "--camera-position equals --camera-target"},
        {"--fov 0", "--fov '0"},
        {"--fov 180", "--fov '180"},
        {"--turntable 0", "--turntable '0'"},
        {"--turntable -2", "--turntable '-2'"},
        {"--snapshot-format jpg", "--snapshot-format 'jpg'"},
        {"--debug-view shiny", "--debug-view 'shiny' is not a debug view (use weights, normals"},
    };
    for (const Case& c : cases) {
        const Result render =
            run("render " + tetrahedron(dir) + " -o " + (dir / "bad.png").string() + " " + c.flags, dir);
        EXPECT_EQ(render.exitCode, 2) << c.flags << "\n" << render.output;
        EXPECT_TRUE(contains(render.output, c.expected)) << c.flags << "\n" << render.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad.png")) << c.flags;
        const Result generate =
            run("generate " + (dir / "scene.toml").string() + " -o " + (dir / "bad").string() + " " + c.flags, dir);
        EXPECT_EQ(generate.exitCode, 2) << c.flags << "\n" << generate.output;
        EXPECT_TRUE(contains(generate.output, c.expected)) << c.flags << "\n" << generate.output;
        EXPECT_FALSE(std::filesystem::exists(dir / "bad")) << c.flags;
    }
    // A format that disagrees with the output name; the cave view without a grid.
    const Result mismatch =
        run("render " + tetrahedron(dir) + " -o " + (dir / "bad.png").string() + " --snapshot-format exr", dir);
    EXPECT_EQ(mismatch.exitCode, 2);
    EXPECT_TRUE(contains(mismatch.output, "--snapshot-format 'exr' does not match")) << mismatch.output;
    const Result cave = run("render " + tetrahedron(dir) + " -o " + (dir / "bad.png").string() + " --view cave", dir);
    EXPECT_EQ(cave.exitCode, 2);
    EXPECT_TRUE(contains(cave.output, "--view cave needs the scene's terrain grid")) << cave.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "bad.png"));
}

TEST(SnapshotCommand, CameraFlagsOverrideTheSceneCamera)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    const std::string base = "render " + tetrahedron(dir) + " --backend cpu -o ";
    ASSERT_EQ(run(base + (dir / "scene.png").string(), dir).exitCode, 0);
    ASSERT_EQ(run(base + (dir / "flags.png").string() + " --camera-position 8,6,10 --camera-target 1,1,1 --fov 30", dir)
                  .exitCode,
              0);
    ASSERT_EQ(run(base + (dir / "fov.png").string() + " --camera-position 8,6,10 --camera-target 1,1,1 --fov 60", dir)
                  .exitCode,
              0);
    const Image scene = strata::render::readImage(dir / "scene.png");
    const Image flags = strata::render::readImage(dir / "flags.png");
    const Image fov = strata::render::readImage(dir / "fov.png");
    EXPECT_LT(strata::render::fractionWithin(scene, flags, 2), 0.9);
    EXPECT_LT(strata::render::fractionWithin(flags, fov, 2), 0.9);
    EXPECT_GT(standardDeviation(flags), 5.0);
}

TEST(SnapshotCommand, DebugViewsShowTheMaterialInsteadOfTheLitImage)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    const std::string base = "render " + tetrahedron(dir) + " --backend cpu -o ";
    ASSERT_EQ(run(base + (dir / "lit.png").string(), dir).exitCode, 0);
    const Result normals = run(base + (dir / "normals.png").string() + " --debug-view normals", dir);
    ASSERT_EQ(normals.exitCode, 0) << normals.output;
    const Result layers = run(base + (dir / "layers.png").string() + " --debug-view layers", dir);
    ASSERT_EQ(layers.exitCode, 0) << layers.output;
    const Image lit = strata::render::readImage(dir / "lit.png");
    const Image normalView = strata::render::readImage(dir / "normals.png");
    const Image layerView = strata::render::readImage(dir / "layers.png");
    EXPECT_LT(strata::render::fractionWithin(lit, normalView, 2), 0.9);
    // Without [[layer]] tables the whole surface is the base: its colour,
    // 0.2 as a display value, byte 124 after the sRGB encoding.
    int baseColoured = 0;
    for (std::size_t i = 0; i < layerView.pixels.size(); i += 4) {
        const std::uint8_t* p = layerView.pixels.data() + i;
        baseColoured += std::abs(p[0] - 124) <= 1 && std::abs(p[1] - 124) <= 1 && std::abs(p[2] - 124) <= 1;
    }
    EXPECT_GT(baseColoured, int(layerView.pixels.size() / 4 / 50)) << "the surface shows the base layer's colour";
}

TEST(SnapshotCommand, LandformDebugViewsNeedAndShowAnErodeNode)
{
    const auto dir = strata::test::freshTestDir();
    writeTetrahedron(dir);
    // A terrain without an `erode` node has no landform masks to show.
    const Result none = run("render " + (dir / "scene.toml").string() + " --backend cpu --debug-view flow -o " +
                                (dir / "none.png").string(),
                            dir);
    EXPECT_NE(none.exitCode, 0);
    EXPECT_NE(none.output.find("debug view 'flow' needs the landform masks"), std::string::npos) << none.output;
    EXPECT_NE(none.output.find("`erode` node"), std::string::npos) << none.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "none.png"));

    std::ofstream(dir / "eroded.toml") << strata::test::erodedSceneToml()
                                       << "[material]\ntexture_size = 64\n[snapshot]\nwidth = 96\nheight = 64\n";
    std::vector<Image> views;
    for (const char* view : {"flow", "wear", "deposition", "water"}) {
        const std::filesystem::path png = dir / (std::string(view) + ".png");
        const Result r = run("render " + (dir / "eroded.toml").string() + " --backend cpu --debug-view " + view +
                                 " -o " + png.string(),
                             dir);
        ASSERT_EQ(r.exitCode, 0) << r.output;
        views.push_back(strata::render::readImage(png));
    }
    EXPECT_GT(standardDeviation(views[0]), 5.0) << "the flow varies over the terrain";
    for (std::size_t i = 0; i < views.size(); ++i) {
        for (std::size_t j = i + 1; j < views.size(); ++j) {
            EXPECT_LT(strata::render::fractionWithin(views[i], views[j], 2), 0.9) << i << " vs " << j;
        }
    }
}

/// The default scene: the presets give different, non-constant images, and
/// the cave view is inside a cave (looking out: the generate log says so).
TEST(SnapshotCommand, PresetsOrbitTopAndCaveDiffer)
{
    const auto dir = strata::test::freshTestDir();
    const Result cave = run("generate -o " + (dir / "out").string() + " --view cave --size 160x90 --backend cpu", dir);
    ASSERT_EQ(cave.exitCode, 0) << cave.output;
    EXPECT_TRUE(std::regex_search(cave.output, std::regex(R"(cave +[0-9.]+ s +camera at \()"))) << cave.output;
    const std::string mesh = " --mesh " + (dir / "out" / "terrain.glb").string() + " --size 160x90 --backend cpu";
    ASSERT_EQ(run("render -o " + (dir / "orbit.png").string() + " --view orbit" + mesh, dir).exitCode, 0);
    ASSERT_EQ(run("render -o " + (dir / "top.png").string() + " --view top" + mesh, dir).exitCode, 0);
    const std::vector<Image> images = {strata::render::readImage(dir / "orbit.png"),
                                       strata::render::readImage(dir / "top.png"),
                                       strata::render::readImage(dir / "out" / "snapshot.png")};
    const char* names[] = {"orbit", "top", "cave"};
    for (std::size_t i = 0; i < images.size(); ++i) {
        EXPECT_GT(standardDeviation(images[i]), 8.0) << names[i];
        for (std::size_t j = i + 1; j < images.size(); ++j) {
            // (orbit and top share much of the sky: 64% alike at 160x90)
            EXPECT_LT(strata::render::fractionWithin(images[i], images[j], 4), 0.8) << names[i] << " vs " << names[j];
        }
    }
}

/// The default scene at 640×360 on GL and on the CPU renderer, each with the
/// scene's 4× MSAA and atmosphere: the PSNR measured on llvmpipe less a
/// margin (tests/Parity.h) and >= 99% of the pixels
/// within 2/255 over the whole frame (terrain pixels alone:
/// SnapshotParity.* in scene_tests). The strata executable runs llvmpipe
/// with its default (fixed-point "AoS") filtering of RGBA8 textures.
TEST(SnapshotCommand, DefaultSceneOnGlMatchesTheCpu)
{
    const auto dir = strata::test::freshTestDir();
    for (const char* backend : {"gl", "cpu"}) {
        const Result r =
            run("generate -o " + (dir / backend).string() + " --size 640x360 --backend " + backend, dir);
        ASSERT_EQ(r.exitCode, 0) << r.output;
    }
    const Image gl = strata::render::readImage(dir / "gl" / "snapshot.png");
    const Image cpu = strata::render::readImage(dir / "cpu" / "snapshot.png");
    const double psnr = strata::render::psnr(gl, cpu);
    const double within = strata::render::fractionWithin(gl, cpu, 2);
    std::cout << "[ parity   ] default scene 640x360, 4x MSAA: " << std::fixed << std::setprecision(3)
              << within * 100.0 << "% of pixels within 2/255" << std::defaultfloat << std::endl;
    // Measured 56.51 dB on llvmpipe/EGL, AMD EPYC (Parity.h)
    STRATA_EXPECT_PARITY(psnr, 56.51, "strata generate --backend gl vs cpu");
    EXPECT_GE(within, 0.99);
}

TEST(SnapshotCommand, HelpDocumentsTheSnapshotFlags)
{
    const auto dir = strata::test::freshTestDir();
    for (const char* command : {"generate", "render"}) {
        const Result help = run(std::string(command) + " --help", dir);
        EXPECT_EQ(help.exitCode, 0);
        for (const char* flag : {"--backend", "auto", "--view", "cave", "--camera-position", "--camera-target", "--fov",
                                 "--turntable", "--snapshot-format", "exr", "--debug-view", "layers"}) {
            EXPECT_TRUE(contains(help.output, flag)) << command << " --help lacks " << flag << "\n" << help.output;
        }
    }
    // A value CLI11 cannot convert is exit code 2 as well.
    const Result fov = run("render -o " + (dir / "x.png").string() + " --fov wide", dir);
    EXPECT_EQ(fov.exitCode, 2);
    EXPECT_TRUE(contains(fov.output, "--fov")) << fov.output;
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}
