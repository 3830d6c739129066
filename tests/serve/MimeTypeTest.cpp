// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/serve/MimeType.h>

#include <gtest/gtest.h>

using strata::serve::compressibilityFor;
using strata::serve::compressibilityOf;
using strata::serve::mimeTypeFor;

TEST(MimeType, TheTypesABakeAndItsViewerUse)
{
    EXPECT_EQ(mimeTypeFor("tileset.json"), "application/json");
    EXPECT_EQ(mimeTypeFor("tiles/0/1_2_3.glb"), "model/gltf-binary");
    EXPECT_EQ(mimeTypeFor("a.gltf"), "model/gltf+json");
    EXPECT_EQ(mimeTypeFor("viewer/index.html"), "text/html; charset=utf-8");
    EXPECT_EQ(mimeTypeFor("viewer/main.js"), "text/javascript; charset=utf-8");
    EXPECT_EQ(mimeTypeFor("viewer/style.css"), "text/css; charset=utf-8");
    EXPECT_EQ(mimeTypeFor("albedo.png"), "image/png");
    EXPECT_EQ(mimeTypeFor("albedo.jpg"), "image/jpeg");
    EXPECT_EQ(mimeTypeFor("albedo.ktx2"), "image/ktx2");
    EXPECT_EQ(mimeTypeFor("draco.wasm"), "application/wasm");
    EXPECT_EQ(mimeTypeFor("buffer.bin"), "application/octet-stream");
}

TEST(MimeType, ExtensionsAreCaseInsensitiveAndUnknownOnesAreOctetStream)
{
    EXPECT_EQ(mimeTypeFor("TILE.GLB"), "model/gltf-binary");
    EXPECT_EQ(mimeTypeFor("Index.Html"), "text/html; charset=utf-8");
    EXPECT_EQ(mimeTypeFor("README"), "application/octet-stream");
    EXPECT_EQ(mimeTypeFor("archive.xyz"), "application/octet-stream");
    EXPECT_EQ(mimeTypeFor(".glb/x"), "application/octet-stream");
}

TEST(MimeType, CompressedFormatsAreNotCompressedAgain)
{
    using strata::serve::Compressibility;
    EXPECT_EQ(compressibilityOf("application/json"), Compressibility::Text);
    EXPECT_EQ(compressibilityOf("model/gltf+json"), Compressibility::Text);
    EXPECT_EQ(compressibilityOf("text/javascript; charset=utf-8"), Compressibility::Text);
    EXPECT_EQ(compressibilityOf("model/gltf-binary"), Compressibility::Binary);
    EXPECT_EQ(compressibilityOf("application/wasm"), Compressibility::Binary);
    EXPECT_EQ(compressibilityOf("application/octet-stream"), Compressibility::Binary);
    EXPECT_EQ(compressibilityOf("image/png"), Compressibility::None);
    EXPECT_EQ(compressibilityOf("image/jpeg"), Compressibility::None);
    EXPECT_EQ(compressibilityOf("image/ktx2"), Compressibility::None);
    EXPECT_EQ(compressibilityOf("image/webp"), Compressibility::None);
}

TEST(MimeType, OnlyKnownExtensionsAreCompressible)
{
    using strata::serve::Compressibility;
    EXPECT_EQ(compressibilityFor("tileset.json"), Compressibility::Text);
    EXPECT_EQ(compressibilityFor("viewer/Main.JS"), Compressibility::Text);
    EXPECT_EQ(compressibilityFor("tiles/0/1_2_3.glb"), Compressibility::Binary);
    EXPECT_EQ(compressibilityFor("buffer.bin"), Compressibility::Binary);
    EXPECT_EQ(compressibilityFor("draco.wasm"), Compressibility::Binary);
    EXPECT_EQ(compressibilityFor("albedo.png"), Compressibility::None);
    // application/octet-stream as .bin is, but of unknown content: maybe a
    // zip, a video or a VDB, compressed already.
    EXPECT_EQ(mimeTypeFor("world.vdb"), "application/octet-stream");
    EXPECT_EQ(compressibilityFor("world.vdb"), Compressibility::None);
    EXPECT_EQ(compressibilityFor("archive.zip"), Compressibility::None);
    EXPECT_EQ(compressibilityFor("README"), Compressibility::None);
}
