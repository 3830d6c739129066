// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The scene and heightmap fuzzers' seed corpora (fuzz/corpus/scene/,
// fuzz/corpus/heightmap/) and any crash reproducer added to them, replayed
// as regression inputs: each file is accepted or refused with
// strata::Error (BadInput), never a crash or another exception.
#include "HeightImageFile.h"
#include "ImageExtension.h" // fuzz/
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/scene/Scene.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace fs = std::filesystem;

namespace {

std::string readBytes(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(FuzzCorpus, EverySceneCorpusFileParsesOrThrowsStrataError)
{
    std::size_t files = 0, parsed = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(STRATA_FUZZ_CORPUS_DIR) / "scene")) {
        if (!entry.is_regular_file()) continue;
        ++files;
        try {
            // Named after the corpus file: relative image names resolve
            // next to it (where none of the ones named exist).
            const strata::scene::Scene scene = strata::scene::parseScene(readBytes(entry.path()), entry.path().string());
            ASSERT_TRUE(scene.field) << entry.path();
            EXPECT_TRUE(std::isfinite(scene.field->density({0.0, 0.0, 0.0}))) << entry.path();
            ++parsed;
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << entry.path() << ": " << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    EXPECT_GT(files, 0u);
    EXPECT_GT(parsed, 0u);
    EXPECT_LT(parsed, files);
}

TEST(FuzzCorpus, EveryHeightmapCorpusFileLoadsOrThrowsStrataError)
{
    const fs::path dir = strata::test::freshTestDir();
    std::size_t files = 0, loaded = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(STRATA_FUZZ_CORPUS_DIR) / "heightmap")) {
        if (!entry.is_regular_file()) continue;
        ++files;
        // Under the extension the fuzzer gave the bytes (the loader opens a
        // file with its extension's reader only; crash files have none).
        const std::string bytes = readBytes(entry.path());
        const fs::path copy =
            dir / (entry.path().stem().string() +
                   strata::fuzz::imageExtensionFor(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()));
        std::ofstream(copy, std::ios::binary) << bytes;
        try {
            const strata::terrain::HeightImage image = strata::scene::readHeightImageFile(copy);
            EXPECT_GE(image.width, 2) << entry.path();
            EXPECT_GE(image.height, 2) << entry.path();
            ASSERT_EQ(image.values.size(), std::size_t(image.width) * std::size_t(image.height)) << entry.path();
            for (float v : image.values) EXPECT_TRUE(std::isfinite(v)) << entry.path();
            ++loaded;
        } catch (const strata::Error& e) {
            EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput) << entry.path() << ": " << e.what();
            EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
        }
    }
    EXPECT_GT(files, 0u);
    EXPECT_GT(loaded, 0u);
    EXPECT_LT(loaded, files);
}

// The fuzzer's image findings, each refused with the reason named, before
// the image library reads the bytes.
TEST(FuzzCorpus, TheHeightmapFindingsAreRefusedWithTheirReason)
{
    const fs::path corpus = fs::path(STRATA_FUZZ_CORPUS_DIR) / "heightmap";
    auto error = [&](const std::string& file) {
        try {
            strata::scene::readHeightImageFile(corpus / file);
        } catch (const strata::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    // OpenEXR reads a channel list by its contents, not its stated 19 bytes,
    // and then took a later "size" for an attribute to allocate (libFuzzer:
    // out-of-memory in OpaqueAttribute::readValueFrom).
    EXPECT_EQ(error("oom-exr-chlist-size.exr"),
              "is a corrupt OpenEXR file: attribute ':28:28channels' (chlist) at byte 128 runs past its 19 bytes");
    EXPECT_NE(error("crash-oom-exr-attribute.exr").find("is a corrupt OpenEXR file"), std::string::npos);
    // A data window 50 million pixels wide in a 957-byte file: OpenEXR
    // allocated its compressor's line buffers for it when the file was
    // opened (libFuzzer: malloc of more than 1 GiB in newCompressor).
    EXPECT_EQ(error("oom-exr-data-window-width.exr"),
              "claims 50331652x1 pixels of 2 bytes in a file of 957 bytes: more than any image compression holds "
              "(a corrupt or hostile header)");
    EXPECT_EQ(error("ramp-half.exr"), "no error");
}
