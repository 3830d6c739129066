// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The web viewer `strata bake` writes, in a real browser: Debian's headless
// Chromium on software WebGL (SwiftShader), driven by puppeteer-core
// (viewer_browser.mjs; web/package-lock.json) opens DIR/viewer/ served by
// `strata serve DIR --port 0` with the camera of `strata render DIR` given by
// URL parameters, every level-0 tile (sse=0) and shadows off on both sides
// (the scene says so; a second test with them on), and checks: no console errors; every level-0 content drawn and no
// other; the picture is terrain, not the clear colour; and it matches `strata
// render DIR --backend cpu` from the same camera on the terrain's pixels.
// Fails, never skips, where Chromium, node or the npm packages are missing.

#include <strata/render/Image.h>

#include "../SmallScene.h"
#include "../TestDir.h"
#include "RunStrata.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>

namespace fs = std::filesystem;
using namespace strata;

namespace {

/// Browser vs CPU renderer on the terrain pixels (the small scene at
/// 480×270 with its atmosphere, 4× MSAA on both, level 0): measured
/// 43.42 dB on Debian's Chromium with SwiftShader (--use-angle=swiftshader),
/// AMD EPYC, 2 cores (49.47 dB over the whole frame); with shadows 41.10 dB
/// (47.26 dB whole frame). The floor is the
/// issue's goal.
constexpr double MIN_TERRAIN_PSNR_DB = 35.0;

std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

struct Shell
{
    int exitCode;
    std::string output;
};

Shell runShell(const std::string& command, const fs::path& dir)
{
    const fs::path log = dir / "shell.log";
    const int status = std::system((command + " > " + log.string() + " 2>&1").c_str());
    const std::string output = readText(log);
    fs::remove(log);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::string vec3Text(const nlohmann::json& v)
{
    std::ostringstream out;
    out << std::setprecision(17) << v.at(0).get<double>() << "," << v.at(1).get<double>() << "," << v.at(2).get<double>();
    return out.str();
}

/// The last line of `output` that parses as a JSON object.
nlohmann::json lastJsonLine(const std::string& output)
{
    std::istringstream in(output);
    std::string line;
    nlohmann::json found;
    while (std::getline(in, line))
        if (!line.empty() && line.front() == '{') found = nlohmann::json::parse(line, nullptr, false);
    return found;
}

/// Bakes the small scene (shadows as given) with its viewer, renders it on
/// the CPU and in Chromium from the scene's camera at level 0, checks the
/// browser's run and sets `db`, the PSNR on the terrain pixels (NaN when it
/// stopped early).
void browserParity(bool shadows, double& db)
{
    db = std::numeric_limits<double>::quiet_NaN();
    ASSERT_TRUE(fs::exists(STRATA_CHROMIUM)) << "no Chromium at " << STRATA_CHROMIUM
                                             << ": install Debian's chromium (scripts/install-deps.sh)";
    ASSERT_TRUE(fs::exists(STRATA_NODE)) << "no node at '" << STRATA_NODE << "': install nodejs and npm (scripts/install-deps.sh)";
    ASSERT_TRUE(fs::exists(fs::path(STRATA_WEB_MODULES) / "node_modules" / "puppeteer-core"))
        << "puppeteer-core is not installed in " << STRATA_WEB_MODULES << ": build the target strata_web_viewer (npm ci)";

    const fs::path dir = test::freshTestDir();
    {
        std::ofstream scene(dir / "small.toml");
        scene << test::SMALL_SCENE << "[snapshot]\nwidth = 480\nheight = 270\nshadows = " << (shadows ? "true" : "false") << "\n";
    }
    const fs::path bake = dir / "bake";
    const test::CommandResult baked = test::runStrata(
        "bake " + (dir / "small.toml").string() + " -o " + bake.string() + " --tile-size 12 --lods 2 --no-grids -q", dir);
    ASSERT_EQ(baked.exitCode, 0) << baked.output;
    ASSERT_TRUE(fs::exists(bake / "viewer" / "index.html")) << "the bake wrote no viewer/: " << baked.output;
    const nlohmann::json config = nlohmann::json::parse(readText(bake / "viewer" / "strata.json"));
    EXPECT_EQ(config.at("shadows").get<bool>(), shadows);
    const nlohmann::json& camera = config.at("camera");
    const std::string position = vec3Text(camera.at("position"));
    const std::string target = vec3Text(camera.at("target"));
    std::ostringstream fov;
    fov << std::setprecision(17) << camera.at("fov").get<double>();
    const nlohmann::json manifest = nlohmann::json::parse(readText(bake / "manifest.json"));
    int levelZeroFiles = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(bake / "tiles" / "0")) levelZeroFiles += e.is_regular_file();
    ASSERT_GT(levelZeroFiles, 1);

    // The CPU renderer: every tile at level 0, the same camera.
    const test::CommandResult cpu =
        test::runStrata("render " + bake.string() + " -o " + (dir / "cpu.png").string() +
                            " --backend cpu --max-screen-error 1e-6 --camera-position " + position +
                            " --camera-target " + target + " --fov " + fov.str() + " -q",
                        dir);
    ASSERT_EQ(cpu.exitCode, 0) << cpu.output;

    // The browser: the terrain, then the sky alone (which pixels are terrain).
    const std::string query = "pos=" + position + "&target=" + target + "&fov=" + fov.str() + "&sse=0&ui=0&controls=0" + (shadows ? "" : "&shadows=0");
    auto browse = [&](const std::string& extra, const fs::path& out) {
        const std::string command = std::string(STRATA_NODE) + " " + STRATA_WEB_TEST_SCRIPT + " --serve " + STRATA_EXECUTABLE + " --modules " +
                                    STRATA_WEB_MODULES + "/node_modules --chromium " + STRATA_CHROMIUM + " --dir " +
                                    bake.string() + " --size 480x270 --out " + out.string() + " --query '" + query +
                                    extra + "'";
        const Shell run = runShell(command, dir);
        EXPECT_EQ(run.exitCode, 0) << command << "\n" << run.output;
        const nlohmann::json result = lastJsonLine(run.output);
        EXPECT_TRUE(result.is_object()) << run.output;
        return result;
    };
    const nlohmann::json web = browse("", dir / "web.png");
    ASSERT_TRUE(web.is_object());
    EXPECT_TRUE(web.at("ok").get<bool>()) << web.dump();
    EXPECT_TRUE(web.at("consoleErrors").empty()) << web.at("consoleErrors").dump(1);
    const nlohmann::json& stats = web.at("stats");
    std::cout << "[ web      ] " << stats.dump() << std::endl;
    EXPECT_EQ(stats.at("loadErrors").get<int>(), 0);
    const nlohmann::json& byLevel = stats.at("visibleByLevel");
    EXPECT_EQ(byLevel.value("0", 0), levelZeroFiles) << "every level-0 tile drawn: " << byLevel.dump();
    EXPECT_EQ(byLevel.size(), 1u) << "only level 0: " << byLevel.dump();
    const nlohmann::json sky = browse("&tiles=0", dir / "sky.png");
    ASSERT_TRUE(sky.is_object());
    EXPECT_TRUE(sky.at("consoleErrors").empty()) << sky.at("consoleErrors").dump(1);

    const render::Image a = render::readImage(dir / "web.png");
    const render::Image b = render::readImage(dir / "cpu.png");
    const render::Image s = render::readImage(dir / "sky.png");
    ASSERT_EQ(a.width, 480);
    ASSERT_EQ(a.height, 270);
    ASSERT_EQ(b.width, a.width);
    ASSERT_EQ(s.width, a.width);
    double sum = 0.0;
    std::size_t terrain = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool differs = false;
            for (int c = 0; c < 3; ++c) differs = differs || a.at(x, y)[c] != s.at(x, y)[c];
            if (!differs) continue;
            ++terrain;
            for (int c = 0; c < 3; ++c) {
                const double d = double(a.at(x, y)[c]) - double(b.at(x, y)[c]);
                sum += d * d;
            }
        }
    // The terrain covers a good part of the frame (the small scene framed by its camera).
    EXPECT_GT(terrain, std::size_t(a.width * a.height / 8)) << "the browser drew little but the sky";
    db = sum == 0.0 ? std::numeric_limits<double>::infinity()
                                 : 10.0 * std::log10(255.0 * 255.0 / (sum / double(3 * terrain)));
    std::cout << "[ parity   ] browser (Chromium, SwiftShader) vs strata render --backend cpu, shadows "
              << (shadows ? "on" : "off") << ", terrain pixels (" << terrain
              << "): PSNR " << std::fixed << std::setprecision(2) << db << " dB; whole frame " << render::psnr(a, b)
              << " dB" << std::endl;
}

} // namespace

TEST(WebViewer, DrawsTheBakeInChromiumLikeTheCpuRendererWithoutShadows)
{
    double db = 0.0;
    browserParity(false, db); // measured 43.42 dB (see MIN_TERRAIN_PSNR_DB)
    EXPECT_GE(db, MIN_TERRAIN_PSNR_DB);
}

TEST(WebViewer, DrawsTheSunsShadowsLikeTheCpuRenderer)
{
    // The same shadow map algorithm (shaders/Shadow.h) fitted to the baked
    // world's bounds in the browser, to the drawn tiles' in strata render.
    double db = 0.0;
    browserParity(true, db); // measured 41.10 dB
    EXPECT_GE(db, MIN_TERRAIN_PSNR_DB);
}
