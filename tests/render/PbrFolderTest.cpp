// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// PBR texture folders: classification of the common CC0 naming schemes,
// MOHS packing, normal conventions, downsampling and the errors.

#include <strata/Error.h>
#include <strata/render/Image.h>
#include <strata/render/PbrFolder.h>
#include <strata/render/Texture.h>

#include "TestDir.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

using namespace strata::render;
namespace fs = std::filesystem;

/// Writes a w×h image with `channels` 8-bit channels, value(x, y, c) per
/// channel, through OpenImageIO (so 1- and 3-channel files can be made).
template <typename F> void writeChannels(const fs::path& path, int w, int h, int channels, F&& value)
{
    std::vector<std::uint8_t> data(std::size_t(w) * std::size_t(h) * std::size_t(channels));
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            for (int c = 0; c < channels; ++c) {
                data[(std::size_t(y) * std::size_t(w) + std::size_t(x)) * std::size_t(channels) + std::size_t(c)] =
                    std::uint8_t(value(x, y, c));
            }
        }
    }
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out) << path;
    const OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
    ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, data.data())) << out->geterror();
    ASSERT_TRUE(out->close());
}

/// A constant 1-channel image.
void writeGrey(const fs::path& path, int w, int h, int value)
{
    writeChannels(path, w, h, 1, [&](int, int, int) { return value; });
}

/// A constant RGB image.
void writeRgb(const fs::path& path, int w, int h, int r, int g, int b)
{
    const int rgb[3] = {r, g, b};
    writeChannels(path, w, h, 3, [&](int, int, int c) { return rgb[c]; });
}

/// Texel (0, 0) of level 0.
glm::ivec4 texel(const TexturePtr& t)
{
    const std::uint8_t* p = t->levels.at(0).texels.data();
    return {p[0], p[1], p[2], p[3]};
}

/// The message of the strata::Error `f` throws ("" and a test failure if none).
template <typename F> std::string errorOf(F&& f)
{
    try {
        f();
    } catch (const strata::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no strata::Error";
    return "";
}

void touch(const fs::path& path)
{
    std::ofstream(path) << "not an image\n";
}

bool contains(const std::string& text, const std::string& part)
{
    return text.find(part) != std::string::npos;
}

TEST(PbrFolder, ClassifiesAmbientCgNaming)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock023_2K_Color.png", 4, 4, 120, 100, 80);
    writeRgb(dir / "Rock023_2K_NormalGL.png", 4, 4, 128, 128, 255);
    writeRgb(dir / "Rock023_2K_NormalDX.png", 4, 4, 128, 128, 255);
    writeGrey(dir / "Rock023_2K_Roughness.png", 4, 4, 200);
    writeGrey(dir / "Rock023_2K_AmbientOcclusion.png", 4, 4, 180);
    writeGrey(dir / "Rock023_2K_Displacement.png", 4, 4, 90);
    writeGrey(dir / "Rock023_2K_Metalness.png", 4, 4, 10);
    writeGrey(dir / "Rock023_2K_Opacity.png", 4, 4, 255);
    writeRgb(dir / "Rock023.png", 4, 4, 1, 2, 3);         // the library's preview
    writeRgb(dir / "Rock023_PREVIEW.jpg", 4, 4, 1, 2, 3); // another preview
    touch(dir / "Rock023_2K-JPG.mtlx");
    touch(dir / "Rock023_2K-JPG.usdc");

    const PbrFiles gl = findPbrFiles(dir);
    EXPECT_EQ(gl.albedo.filename(), "Rock023_2K_Color.png");
    EXPECT_EQ(gl.normal.filename(), "Rock023_2K_NormalGL.png");
    EXPECT_FALSE(gl.normalDirectX);
    EXPECT_EQ(gl.roughness.filename(), "Rock023_2K_Roughness.png");
    EXPECT_TRUE(gl.smoothness.empty());
    EXPECT_EQ(gl.occlusion.filename(), "Rock023_2K_AmbientOcclusion.png");
    EXPECT_EQ(gl.height.filename(), "Rock023_2K_Displacement.png");
    EXPECT_EQ(gl.metallic.filename(), "Rock023_2K_Metalness.png");
    EXPECT_TRUE(gl.arm.empty());
    // With both conventions present, the default one wins.
    const PbrFiles dx = findPbrFiles(dir, true);
    EXPECT_EQ(dx.normal.filename(), "Rock023_2K_NormalDX.png");
    EXPECT_TRUE(dx.normalDirectX);

    const PbrMaps maps = loadPbrFolder(dir);
    ASSERT_TRUE(maps.albedo && maps.mask && maps.normal);
    EXPECT_EQ(maps.albedo->kind, MapKind::Albedo);
    EXPECT_EQ(maps.mask->kind, MapKind::Mask);
    EXPECT_EQ(maps.normal->kind, MapKind::Normal);
    EXPECT_EQ(texel(maps.albedo), glm::ivec4(120, 100, 80, 255));
    // MOHS: metallic 10, occlusion 180, height 90, smoothness 255 − 200.
    EXPECT_EQ(texel(maps.mask), glm::ivec4(10, 180, 90, 55));
}

TEST(PbrFolder, ClassifiesPolyHavenNamingWithArm)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "metal_plate_diff_2k.png", 4, 4, 50, 60, 70);
    writeRgb(dir / "metal_plate_nor_gl_2k.png", 4, 4, 128, 100, 240);
    writeRgb(dir / "metal_plate_arm_2k.png", 4, 4, 200, 60, 30); // AO, roughness, metallic
    writeGrey(dir / "metal_plate_disp_2k.png", 4, 4, 90);
    writeRgb(dir / "metal_plate_nor_dx_2k.png", 4, 4, 128, 100, 240);

    const PbrFiles files = findPbrFiles(dir);
    EXPECT_EQ(files.albedo.filename(), "metal_plate_diff_2k.png");
    EXPECT_EQ(files.normal.filename(), "metal_plate_nor_gl_2k.png");
    EXPECT_EQ(files.arm.filename(), "metal_plate_arm_2k.png");
    EXPECT_EQ(files.height.filename(), "metal_plate_disp_2k.png");
    EXPECT_TRUE(files.metallic.empty()); // "metal" in the material's name is not the map's token
    EXPECT_TRUE(files.roughness.empty());

    const PbrMaps maps = loadPbrFolder(dir);
    ASSERT_TRUE(maps.mask);
    EXPECT_EQ(texel(maps.mask), glm::ivec4(30, 200, 90, 255 - 60));
    EXPECT_EQ(texel(maps.normal), glm::ivec4(128, 100, 240, 255));

    // A separate map takes precedence over its channel of the ARM map.
    writeGrey(dir / "metal_plate_rough_2k.png", 4, 4, 10);
    writeGrey(dir / "metal_plate_metal_2k.png", 4, 4, 255);
    EXPECT_EQ(findPbrFiles(dir).metallic.filename(), "metal_plate_metal_2k.png");
    EXPECT_EQ(texel(loadPbrFolder(dir).mask), glm::ivec4(255, 200, 90, 245));
}

TEST(PbrFolder, ClassifiesOtherCommonNames)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "PaintedPlaster_BaseColor.png", 2, 2, 1, 2, 3);
    writeGrey(dir / "PaintedPlaster_Height.png", 2, 2, 1);
    writeGrey(dir / "PaintedPlaster_Gloss.png", 2, 2, 1);
    writeGrey(dir / "PaintedPlaster_Specular.png", 2, 2, 1);
    writeGrey(dir / "PaintedPlaster_Metallic.png", 2, 2, 1);
    writeRgb(dir / "PaintedPlaster_Normal.png", 2, 2, 128, 128, 255);
    writeGrey(dir / "PaintedPlaster_sphere.png", 2, 2, 1);
    writeRgb(dir / "preview.jpg", 2, 2, 1, 2, 3);
    writeRgb(dir / "PaintedPlaster_Color_preview.jpg", 2, 2, 1, 2, 3);
    const PbrFiles files = findPbrFiles(dir);
    EXPECT_EQ(files.albedo.filename(), "PaintedPlaster_BaseColor.png");
    EXPECT_EQ(files.height.filename(), "PaintedPlaster_Height.png");
    EXPECT_EQ(files.smoothness.filename(), "PaintedPlaster_Gloss.png");
    EXPECT_EQ(files.metallic.filename(), "PaintedPlaster_Metallic.png");
    EXPECT_EQ(files.normal.filename(), "PaintedPlaster_Normal.png");
    EXPECT_FALSE(files.normalDirectX);
    EXPECT_TRUE(findPbrFiles(dir, true).normalDirectX); // unsaid: the caller's convention

    const fs::path lower = dir / "lower";
    fs::create_directories(lower);
    writeRgb(lower / "ground_albedo.jpg", 2, 2, 1, 2, 3);
    writeRgb(lower / "ground_normalgl.png", 2, 2, 128, 128, 255);
    writeGrey(lower / "ground_bump.png", 2, 2, 1);
    writeGrey(lower / "ground_ao.png", 2, 2, 1);
    const PbrFiles l = findPbrFiles(lower);
    EXPECT_EQ(l.albedo.filename(), "ground_albedo.jpg");
    EXPECT_EQ(l.normal.filename(), "ground_normalgl.png");
    EXPECT_EQ(l.height.filename(), "ground_bump.png");
    EXPECT_EQ(l.occlusion.filename(), "ground_ao.png");
    // A height map is preferred to a bump map.
    writeGrey(lower / "ground_height.png", 2, 2, 1);
    EXPECT_EQ(findPbrFiles(lower).height.filename(), "ground_height.png");
}

TEST(PbrFolder, IgnoresPreviewsOpacityAndSpecular)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock_Color.png", 2, 2, 9, 9, 9);
    writeRgb(dir / "preview.jpg", 2, 2, 1, 2, 3);
    writeGrey(dir / "Rock_Opacity.png", 2, 2, 1);
    writeGrey(dir / "Rock_Opacity.jpg", 2, 2, 1);
    writeGrey(dir / "Rock_Specular.png", 2, 2, 1);
    writeRgb(dir / "Rock_sphere.png", 2, 2, 1, 2, 3);
    writeRgb(dir / ".Rock_Normal.png", 2, 2, 1, 2, 3);  // hidden
    fs::create_directories(dir / "Rock_Roughness.png"); // a folder
    const PbrFiles files = findPbrFiles(dir);
    EXPECT_EQ(files.albedo.filename(), "Rock_Color.png");
    EXPECT_TRUE(files.normal.empty() && files.roughness.empty() && files.smoothness.empty() &&
                files.occlusion.empty() && files.height.empty() && files.metallic.empty() && files.arm.empty());
    const PbrMaps maps = loadPbrFolder(dir);
    EXPECT_TRUE(maps.albedo);
    EXPECT_FALSE(maps.mask);
    EXPECT_FALSE(maps.normal);
}

TEST(PbrFolder, FlipsDirectXNormalsToOpenGl)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "ground_Color.png", 2, 2, 9, 9, 9);
    writeRgb(dir / "ground_Normal_DX.png", 2, 2, 100, 70, 230);
    EXPECT_TRUE(findPbrFiles(dir).normalDirectX);
    EXPECT_EQ(texel(loadPbrFolder(dir).normal), glm::ivec4(100, 255 - 70, 230, 255));

    // A name that says neither: the caller's convention.
    fs::rename(dir / "ground_Normal_DX.png", dir / "ground_Normal.png");
    EXPECT_EQ(texel(loadPbrFolder(dir).normal), glm::ivec4(100, 70, 230, 255));
    EXPECT_EQ(texel(loadPbrFolder(dir, {}, 0, true).normal), glm::ivec4(100, 255 - 70, 230, 255));
    // A GL map stays as is when the default is DirectX.
    fs::rename(dir / "ground_Normal.png", dir / "ground_Normal_GL.png");
    EXPECT_EQ(texel(loadPbrFolder(dir, {}, 0, true).normal), glm::ivec4(100, 70, 230, 255));
}

TEST(PbrFolder, InvertsRoughnessIntoSmoothness)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "sand_Color.png", 2, 2, 9, 9, 9);
    writeGrey(dir / "sand_Roughness.png", 2, 2, 64);
    // Defaults: metallic 0, occlusion 1, height 0.5; smoothness 1 − 64/255.
    EXPECT_EQ(texel(loadPbrFolder(dir).mask), glm::ivec4(0, 255, 128, 191));
    // A gloss map is smoothness as is, and a roughness map wins over it.
    writeGrey(dir / "sand_Gloss.png", 2, 2, 30);
    EXPECT_EQ(texel(loadPbrFolder(dir).mask).a, 191);
    fs::remove(dir / "sand_Roughness.png");
    EXPECT_EQ(texel(loadPbrFolder(dir).mask).a, 30);
    // An RGB roughness map uses its first channel.
    fs::remove(dir / "sand_Gloss.png");
    writeRgb(dir / "sand_Roughness.jpg", 2, 2, 64, 64, 64);
    EXPECT_NEAR(texel(loadPbrFolder(dir).mask).a, 191, 2);
}

TEST(PbrFolder, MissingAlbedoNamesTheFolder)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock_NormalGL.png", 2, 2, 128, 128, 255);
    writeGrey(dir / "Rock_Roughness.png", 2, 2, 1);
    const std::string what = errorOf([&] { findPbrFiles(dir); });
    EXPECT_TRUE(contains(what, dir.string())) << what;
    EXPECT_TRUE(contains(what, "albedo")) << what;
    EXPECT_TRUE(contains(errorOf([&] { loadPbrFolder(dir); }), dir.string()));
}

TEST(PbrFolder, MissingFolderOrFileNamesThePath)
{
    const fs::path dir = strata::test::freshTestDir();
    const std::string missing = errorOf([&] { findPbrFiles(dir / "nowhere"); });
    EXPECT_TRUE(contains(missing, (dir / "nowhere").string())) << missing;
    EXPECT_TRUE(contains(missing, "no such folder")) << missing;
    writeRgb(dir / "Rock_Color.png", 2, 2, 9, 9, 9);
    const std::string file = errorOf([&] { loadPbrFolder(dir / "Rock_Color.png"); });
    EXPECT_TRUE(contains(file, "Rock_Color.png")) << file;
    EXPECT_TRUE(contains(file, "not a folder")) << file;
}

TEST(PbrFolder, MaskMapsOfDifferentSizesNameBothFiles)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock_Color.png", 8, 8, 9, 9, 9);
    writeGrey(dir / "Rock_Roughness.png", 4, 4, 100);
    writeGrey(dir / "Rock_AO.png", 8, 8, 100);
    const std::string what = errorOf([&] { loadPbrFolder(dir); });
    EXPECT_TRUE(contains(what, dir.string())) << what;
    EXPECT_TRUE(contains(what, "Rock_Roughness.png")) << what;
    EXPECT_TRUE(contains(what, "Rock_AO.png")) << what;
    EXPECT_TRUE(contains(what, "4x4")) << what;
    EXPECT_TRUE(contains(what, "8x8")) << what;
    // Brought to the same size by maxSize, they pack.
    const PbrMaps maps = loadPbrFolder(dir, {}, 4);
    ASSERT_TRUE(maps.mask);
    EXPECT_EQ(maps.mask->width(), 4);
    EXPECT_EQ(maps.albedo->width(), 4);
}

TEST(PbrFolder, OneChannelNormalMapIsAnError)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock_Color.png", 2, 2, 9, 9, 9);
    writeGrey(dir / "Rock_NormalGL.png", 2, 2, 128);
    const std::string what = errorOf([&] { loadPbrFolder(dir); });
    EXPECT_TRUE(contains(what, "Rock_NormalGL.png")) << what;
    EXPECT_TRUE(contains(what, "channel")) << what;
    // An ARM map needs three channels as well.
    fs::remove(dir / "Rock_NormalGL.png");
    writeGrey(dir / "rock_arm_1k.png", 2, 2, 128);
    EXPECT_TRUE(contains(errorOf([&] { loadPbrFolder(dir); }), "rock_arm_1k.png"));
}

TEST(PbrFolder, AmbiguousCandidatesNameBothFiles)
{
    const fs::path dir = strata::test::freshTestDir();
    writeRgb(dir / "Rock_Color.png", 2, 2, 9, 9, 9);
    writeRgb(dir / "Rock_Color.jpg", 2, 2, 9, 9, 9);
    std::string what = errorOf([&] { findPbrFiles(dir); });
    EXPECT_TRUE(contains(what, dir.string())) << what;
    EXPECT_TRUE(contains(what, "Rock_Color.png")) << what;
    EXPECT_TRUE(contains(what, "Rock_Color.jpg")) << what;
    EXPECT_TRUE(contains(what, "albedo")) << what;

    const fs::path ph = dir / "ph";
    fs::create_directories(ph);
    writeRgb(ph / "rock_diff_2k.png", 2, 2, 9, 9, 9);
    writeGrey(ph / "rock_rough_2k.png", 2, 2, 9);
    writeGrey(ph / "rock_rough_4k.png", 2, 2, 9);
    what = errorOf([&] { findPbrFiles(ph); });
    EXPECT_TRUE(contains(what, "rock_rough_2k.png") && contains(what, "rock_rough_4k.png")) << what;
    EXPECT_TRUE(contains(what, "roughness")) << what;

    // Two normal maps of one convention.
    fs::remove(ph / "rock_rough_4k.png");
    writeRgb(ph / "rock_nor_gl_2k.png", 2, 2, 128, 128, 255);
    writeRgb(ph / "rock_nor_gl_4k.png", 2, 2, 128, 128, 255);
    what = errorOf([&] { findPbrFiles(ph); });
    EXPECT_TRUE(contains(what, "rock_nor_gl_2k.png") && contains(what, "rock_nor_gl_4k.png")) << what;
}

TEST(PbrFolder, MaxSizeHalvesLargerMaps)
{
    const fs::path dir = strata::test::freshTestDir();
    // 16×8 albedo of alternating black and white columns: each 2×2 box
    // averages to linear 0.5, sRGB 188.
    writeChannels(dir / "Rock_Color.png", 16, 8, 3, [](int x, int, int) { return x % 2 ? 255 : 0; });
    // Normals tilted ±x alternately: the average renormalises to +z.
    writeChannels(dir / "Rock_NormalGL.png", 16, 16, 3, [](int x, int, int c) {
        const int tilted[2][3] = {{218, 128, 218}, {38, 128, 218}};
        return tilted[x % 2][c];
    });
    writeGrey(dir / "Rock_Height.png", 16, 16, 77);

    const PbrMaps maps = loadPbrFolder(dir, {}, 4);
    EXPECT_EQ(maps.albedo->width(), 4);
    EXPECT_EQ(maps.albedo->height(), 2);
    EXPECT_EQ(maps.normal->width(), 4);
    EXPECT_EQ(maps.normal->height(), 4);
    EXPECT_EQ(maps.mask->width(), 4);
    for (std::size_t i = 0; i < maps.albedo->levels[0].texels.size(); i += 4) {
        EXPECT_EQ(int(maps.albedo->levels[0].texels[i]), 188) << i;
    }
    const glm::ivec4 n = texel(maps.normal);
    EXPECT_NEAR(n.r, 128, 1);
    EXPECT_NEAR(n.g, 128, 1);
    EXPECT_EQ(n.b, 255);
    EXPECT_EQ(texel(maps.mask).b, 77);
    // Maps already small enough are kept; 0 keeps every size.
    EXPECT_EQ(loadPbrFolder(dir, {}, 16).albedo->width(), 16);
    EXPECT_EQ(loadPbrFolder(dir).normal->width(), 16);
    // Not a power of two.
    const std::string what = errorOf([&] { loadPbrFolder(dir, {}, 12); });
    EXPECT_TRUE(contains(what, "power of two")) << what;
}

// The sets in docs/textures (from Debian's ufoai-textures) load through the
// loader: albedo, normal and a mask with the height of each.
TEST(PbrFolder, LoadsTheDocumentedTextureSets)
{
    const fs::path root = fs::path(STRATA_TEST_DATA_DIR) / ".." / ".." / ".." / "docs" / "textures";
    ASSERT_TRUE(fs::is_directory(root)) << root;
    int sets = 0;
    for (const fs::directory_entry& entry : fs::directory_iterator(root)) {
        if (!entry.is_directory()) continue;
        ++sets;
        const PbrMaps maps = loadPbrFolder(entry.path(), {}, 256);
        ASSERT_TRUE(maps.albedo && maps.normal && maps.mask) << entry.path();
        EXPECT_LE(maps.albedo->width(), 256) << entry.path();
        EXPECT_EQ(maps.normal->width(), maps.albedo->width()) << entry.path();
        // The normals point out of the surface on average (a flipped or
        // swizzled map would not).
        glm::vec3 sum(0.0f);
        const auto& texels = maps.normal->levels[0].texels;
        for (std::size_t i = 0; i < texels.size(); i += 4) {
            sum += glm::vec3(texels[i], texels[i + 1], texels[i + 2]) / 127.5f - 1.0f;
        }
        sum /= float(texels.size() / 4);
        EXPECT_GT(sum.z, 0.7f) << entry.path();
        // OpenGL convention after loading: x and y of the normal lean
        // against the height's slope (n ∝ (−∂h/∂u, −∂h/∂v, 1), v up, as
        // the texels are stored bottom to top).
        const auto& mask = maps.mask->levels[0].texels;
        const int w = maps.normal->width();
        const int h = maps.normal->height();
        ASSERT_EQ(maps.mask->width(), w);
        ASSERT_EQ(maps.mask->height(), h);
        auto height = [&](int i, int j) { return float(mask[(std::size_t(j) * w + i) * 4 + 2]); };
        double alongU = 0.0, alongV = 0.0;
        for (int j = 1; j + 1 < h; ++j) {
            for (int i = 1; i + 1 < w; ++i) {
                const std::uint8_t* t = texels.data() + (std::size_t(j) * w + i) * 4;
                alongU += (t[0] - 127.5) * -(height(i + 1, j) - height(i - 1, j));
                alongV += (t[1] - 127.5) * -(height(i, j + 1) - height(i, j - 1));
            }
        }
        EXPECT_GT(alongU, 0.0) << entry.path();
        EXPECT_GT(alongV, 0.0) << entry.path();
    }
    EXPECT_EQ(sets, 4);
}

} // namespace
