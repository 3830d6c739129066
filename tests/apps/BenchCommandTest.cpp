// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench -o DIR` end to end on the hidden --tiny setting: the three
// files, the CSV's columns, a row for each preset and each swept knob, and a
// plot that is an image with something drawn on it.

#include <strata/scene/Quality.h>
#include "RunStrata.h"
#include "TestDir.h"

#include <strata/render/Image.h>
#include <strata/terrain/SimdTarget.h>

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

namespace {

using strata::test::CommandResult;
using strata::test::runStrata;

// Splits one CSV line (fields quoted when they hold commas).
std::vector<std::string> splitCsv(const std::string& line)
{
    std::vector<std::string> fields(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (c == '"') {
            if (quoted && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
            else quoted = !quoted;
        } else if (c == ',' && !quoted) {
            fields.emplace_back();
        } else {
            fields.back() += c;
        }
    }
    return fields;
}

} // namespace

TEST(BenchCommand, TinyRunWritesReportCsvAndPlot)
{
    const auto dir = strata::test::freshTestDir();
    const std::filesystem::path out = dir / "bench";
    const CommandResult run = runStrata("bench -o " + out.string() + " --tiny", dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    ASSERT_TRUE(std::filesystem::exists(out / "report.md"));
    ASSERT_TRUE(std::filesystem::exists(out / "report.csv"));
    ASSERT_TRUE(std::filesystem::exists(out / "pareto.png"));
    for (const auto& entry : std::filesystem::directory_iterator(out)) { // atomic writes leave no temporaries
        const std::string name = entry.path().filename().string();
        EXPECT_TRUE(name == "report.md" || name == "report.csv" || name == "pareto.png") << name;
    }

    std::ifstream csv(out / "report.csv");
    std::string line;
    ASSERT_TRUE(std::getline(csv, line));
    const std::vector<std::string> header = splitCsv(line);
    const std::vector<std::string> expected = {
        "machine", "threads", "backend", "subject", "config", "kind", "preset", "knob", "value", "voxel_size_m",
        "active_voxels", "triangles", "mesh_s", "error_mean_voxels", "error_rms_voxels", "error_hausdorff_voxels",
        "normal_error_deg", "render_s", "psnr_db", "psnr_vs_balanced_db", "texture_fetches", "naive_fetches",
        "shader_variants"};
    ASSERT_EQ(header, expected);
    auto column = [&](const std::string& name) {
        return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };

    std::set<std::string> sceneConfigs, shapeConfigs, knobs;
    std::size_t rows = 0;
    while (std::getline(csv, line)) {
        const std::vector<std::string> f = splitCsv(line);
        ASSERT_EQ(f.size(), header.size()) << line;
        ++rows;
        EXPECT_FALSE(f[column("machine")].empty()) << line;
        EXPECT_GE(std::stoi(f[column("threads")]), 1) << line;
        const std::string backend = f[column("backend")];
        EXPECT_TRUE(backend == "gl" || backend == "cpu" || backend == "none") << line;
        EXPECT_GT(std::stoull(f[column("triangles")]), 0u) << line;
        EXPECT_GT(std::stod(f[column("mesh_s")]), 0.0) << line;
        if (f[column("kind")] == "knob") knobs.insert(f[column("knob")]);
        if (f[column("subject")] == "scene") {
            sceneConfigs.insert(f[column("config")]);
            EXPECT_NE(backend, "none") << line;
            EXPECT_GT(std::stod(f[column("render_s")]), 0.0) << line;
            const std::string psnr = f[column("psnr_db")];
            if (f[column("config")] == "accurate") EXPECT_EQ(psnr, "inf"); // the reference
            else EXPECT_GT(std::stod(psnr), 10.0) << line;
            if (backend == "cpu") {
                EXPECT_GT(std::stoull(f[column("texture_fetches")]), 0u) << line;
                EXPECT_LT(std::stoull(f[column("texture_fetches")]), std::stoull(f[column("naive_fetches")])) << line;
            }
        } else {
            shapeConfigs.insert(f[column("config")]);
            EXPECT_EQ(backend, "none") << line;
            const double error = std::stod(f[column("error_mean_voxels")]);
            EXPECT_GT(error, 0.0) << line;
            EXPECT_LT(error, 1.0) << line; // every configuration meshes a sphere within a voxel
        }
    }
    for (const std::string& preset : strata::scene::presetNames()) {
        EXPECT_TRUE(sceneConfigs.count(preset)) << preset;
        EXPECT_TRUE(shapeConfigs.count(preset)) << preset;
    }
    for (const std::string& key : strata::scene::qualityKeys()) {
        if (key == "voxel_size") continue; // swept as voxel_scale (the same knob, relative)
        EXPECT_TRUE(knobs.count(key)) << key;
    }
    EXPECT_TRUE(sceneConfigs.count("mesher=surface-nets"));
    EXPECT_TRUE(shapeConfigs.count("mesher=dual-contouring"));
    EXPECT_FALSE(shapeConfigs.count("filtering=bilinear")); // render-only knobs do not re-mesh the shapes
    EXPECT_GE(rows, 20u);

    std::ifstream mdFile(out / "report.md");
    const std::string md((std::istreambuf_iterator<char>(mdFile)), std::istreambuf_iterator<char>());
    EXPECT_NE(md.find("## Presets"), std::string::npos);
    EXPECT_NE(md.find("This run took"), std::string::npos);
    EXPECT_NE(md.find("| fast |"), std::string::npos);

    const strata::render::Image plot = strata::render::readImage(out / "pareto.png");
    EXPECT_EQ(plot.width, 1520);
    EXPECT_EQ(plot.height, 620);
    std::size_t dark = 0, coloured = 0;
    for (std::size_t i = 0; i < plot.pixels.size(); i += 4) {
        const int r = plot.pixels[i], g = plot.pixels[i + 1], b = plot.pixels[i + 2];
        if (r + g + b < 150) ++dark;                            // axes, ticks, text
        if (std::max({r, g, b}) - std::min({r, g, b}) > 100) ++coloured; // markers, the front
    }
    EXPECT_GT(dark, 5000u);
    EXPECT_GT(coloured, 200u);
}

TEST(BenchCommand, NeedsAnOutputDirectory)
{
    const auto dir = strata::test::freshTestDir();
    const CommandResult run = runStrata("bench --tiny", dir);
    EXPECT_EQ(run.exitCode, 2);
    EXPECT_NE(run.output.find("-o DIR"), std::string::npos) << run.output;
}

TEST(BenchNoiseCommand, PrintsEveryBasisOnTheChosenSimdTargetAndRefusesAnUnknownOne)
{
    const auto dir = strata::test::freshTestDir();
    const std::string portable = strata::terrain::availableSimdTargets().back(); // SCALAR (EMU128 with clang)
    const CommandResult run = runStrata("bench noise --seconds 0.01 --simd " + portable, dir);
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("SIMD target in use: " + portable), std::string::npos) << run.output;
    for (const char* row : {"| gradient | 3D |", "| cellular F2 fBm 5 | 3D |", "| simplex | 2D |", "| value fBm 5 | 2D |"})
        EXPECT_NE(run.output.find(row), std::string::npos) << row << "\n" << run.output;

    const CommandResult bad = runStrata("bench noise --seconds 0.01 --simd NEON9000", dir);
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_EQ(bad.output.rfind("strata: error: --simd: NEON9000", 0), 0u) << bad.output;

    // A missing FastNoiseLite copy fails before anything is measured or printed.
    const std::string missing = (dir / "FastNoiseLite.h").string();
    const CommandResult noCopy = runStrata("bench noise --seconds 0.01 --fastnoise-lite " + missing, dir);
    EXPECT_EQ(noCopy.exitCode, 2);
    EXPECT_EQ(noCopy.output.rfind("strata: error: --fastnoise-lite: " + missing + ": no such file", 0), 0u) << noCopy.output;
}
