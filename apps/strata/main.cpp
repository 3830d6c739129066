// strata — the terrain generator command line.

#include "Generate.h"
#include "Scene.h"

#include <strata/Error.h>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <regex>

namespace {

constexpr int EXIT_BAD_INPUT = 2;

// "1280x720" → {1280, 720}; throws strata::Error otherwise.
std::pair<int, int> parseSize(const std::string& text)
{
    static const std::regex pattern(R"((\d{1,5})[xX](\d{1,5}))");
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) {
        throw strata::Error("--size '" + text + "' must look like WIDTHxHEIGHT, e.g. 1280x720");
    }
    const int width = std::stoi(match[1]), height = std::stoi(match[2]);
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        throw strata::Error("--size '" + text + "': width and height must be in [1, 16384]");
    }
    return {width, height};
}

} // namespace

int main(int argc, char** argv)
{
    CLI::App app{"Strata: procedural terrain and caves, sampled into OpenVDB level sets, meshed,\n"
                 "and rendered with height-blended triplanar texturing."};
    app.set_version_flag("--version", "strata 0.1.0");
    app.require_subcommand(1);

    CLI::App* generate = app.add_subcommand(
        "generate", "Generate a terrain: writes DIR/terrain.vdb, DIR/terrain.glb, DIR/snapshot.png, DIR/report.json");
    std::string scenePath;
    std::string outputDir;
    std::optional<std::uint64_t> seed;
    int threads = 0;
    std::string size;
    bool noSnapshot = false, writePly = false, quiet = false;
    generate->add_option("scene", scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    generate->add_option("-o,--output", outputDir, "Output directory (created if missing)")->required();
    generate->add_option("--seed", seed, "Override the scene's seed");
    generate->add_option("--threads", threads, "Worker threads (0 = all cores); output is identical for any count")
        ->check(CLI::Range(0, 1024));
    generate->add_option("--size", size, "Snapshot size WIDTHxHEIGHT (default from the scene, 1280x720)");
    generate->add_flag("--no-snapshot", noSnapshot, "Skip the snapshot (no OpenGL/EGL needed)");
    generate->add_flag("--ply", writePly, "Also write DIR/terrain.ply (binary PLY)");
    generate->add_flag("-q,--quiet", quiet, "Print nothing but errors");

    CLI::App* scene = app.add_subcommand("scene", "Print the embedded default scene (a starting point for your own)");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : EXIT_BAD_INPUT;
    }

    try {
        if (scene->parsed()) {
            std::cout << strata::app::defaultSceneText();
            return 0;
        }

        strata::app::GenerateOptions options;
        options.outputDir = outputDir;
        options.seed = seed;
        options.snapshot = !noSnapshot;
        options.writePly = writePly;
        options.quiet = quiet;
        options.threads = threads;
        if (!size.empty()) {
            const auto [width, height] = parseSize(size);
            options.width = width;
            options.height = height;
        }
        const strata::app::Scene sceneData = scenePath.empty()
            ? strata::app::parseScene(strata::app::defaultSceneText(), "<default scene>")
            : strata::app::loadScene(scenePath);

        std::unique_ptr<tbb::global_control> threadLimit;
        if (threads > 0) {
            threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                std::size_t(threads));
        }
        if (!quiet) {
            std::cout << "strata generate: " << sceneData.source << " → " << outputDir << "/" << std::endl;
        }
        strata::app::generate(sceneData, options, std::cout);
        return 0;
    } catch (const strata::Error& e) {
        std::cerr << "strata: error: " << e.what() << std::endl;
        return EXIT_BAD_INPUT;
    } catch (const std::exception& e) {
        std::cerr << "strata: internal error: " << e.what() << std::endl;
        return 1;
    }
}
