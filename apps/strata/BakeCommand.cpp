// `strata bake`: the command-line front of strata/scene/Bake.h.

#include "Commands.h"
#include "MemoryFlag.h"
#include "Progress.h"

#include <strata/Format.h>
#include <strata/scene/Bake.h>

#include <tbb/global_control.h>

#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

namespace strata::app {

namespace {

struct BakeArguments
{
    std::string scenePath;
    std::string outputDir;
    double tileSize = 0.0;
    int lods = 3;
    std::string tiles = "all";
    bool noGrids = false;
    bool force = false;
    std::optional<std::uint64_t> seed;
    int threads = 0;
    std::string maxMemory = "8GiB";
    double skirtDepth = 0.0;
    bool quiet = false;
};

std::string mebibytes(std::uint64_t bytes)
{
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << double(bytes) / double(1 << 20) << " MiB";
    return out.str();
}

void printSummary(const BakePlan& plan, const BakeSummary& summary)
{
    std::cout << "  tiles     " << summary.baked << " baked, " << summary.kept << " kept (files match the manifest), "
              << summary.missing << " of " << summary.tiles << " not baked yet\n";
    for (std::size_t l = 0; l < summary.trianglesPerLevel.size(); ++l) {
        std::cout << "  level " << l << "   " << std::setw(6) << summary.filesPerLevel[l] << " files  " << std::setw(10)
                  << mebibytes(summary.bytesPerLevel[l]) << "  " << std::setw(14)
                  << withThousands(summary.trianglesPerLevel[l]) << " triangles  error "
                  << formatNumber(summary.errorPerLevel[l]) << " m\n";
    }
    const double perMinute = summary.seconds > 0.0 ? 60.0 * summary.baked / summary.seconds : 0.0;
    std::cout << "  total     " << std::fixed << std::setprecision(3) << std::setw(8) << summary.seconds << " s   "
              << std::setprecision(1) << perMinute << " tiles/min" << std::defaultfloat << std::endl;
}

} // namespace

Command registerBakeCommand(CLI::App& app)
{
    auto args = std::make_shared<BakeArguments>();
    CLI::App* bake = app.add_subcommand(
        "bake", "Bake a world: the scene's region cut into tiles with levels of detail; writes DIR/tiles/L/X_Z.glb, "
                "DIR/grids/X_Z.vdb, DIR/manifest.json, DIR/tileset.json (OGC 3D Tiles 1.1). Re-running resumes.");
    bake->add_option("scene", args->scenePath, "Scene file (TOML); without one, the embedded default scene")
        ->check(CLI::ExistingFile);
    bake->add_option("-o,--output", args->outputDir, "Output directory (created if missing)")->required();
    bake->add_option("--tile-size", args->tileSize,
                     "Tile edge in metres: a multiple of the coarsest cell (voxel size × 2^(lods−1)), at most 1024 "
                     "voxels (default: 256 voxels)");
    bake->add_option("--lods", args->lods, "Levels of detail; level L has cells of 2^L voxels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    bake->add_option("--tiles", args->tiles, "Which tiles: all, an index I, or a range A-B (inclusive)")
        ->capture_default_str();
    bake->add_flag("--no-grids", args->noGrids, "Skip the level-0 grids (DIR/grids/X_Z.vdb)");
    bake->add_flag("--force", args->force, "Bake over a folder that holds another scene's bake (its files are removed)");
    bake->add_option("--seed", args->seed, "Override the scene's seed")->check(seedValidator());
    bake->add_option("--threads", args->threads,
                     "Tiles baked at once (0 = all cores); every tile is the same bytes for any count")
        ->check(CLI::Range(0, 1024));
    bake->add_option("--max-memory", args->maxMemory, "Memory budget per tile, e.g. 8GiB (default), 512MiB")
        ->capture_default_str();
    bake->add_option("--skirt-depth", args->skirtDepth,
                     "Depth of the skirts that close seams between levels, metres (default: two coarsest cells)")
        ->check(CLI::NonNegativeNumber);
    bake->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");

    return {bake, [args]() {
                BakeOptions options;
                options.outputDir = args->outputDir;
                options.tileSize = args->tileSize;
                options.lods = args->lods;
                options.tiles = args->tiles;
                options.grids = !args->noGrids;
                options.force = args->force;
                options.seed = args->seed;
                options.threads = args->threads;
                options.maxMemoryBytes = parseMemory(args->maxMemory);
                options.skirtDepth = args->skirtDepth;
                const Scene scene = args->scenePath.empty() ? defaultScene() : loadScene(args->scenePath);
                const BakePlan plan = planBake(scene, options); // bad flags: exit 2, nothing written
                std::unique_ptr<tbb::global_control> threadLimit;
                if (args->threads > 0) {
                    threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                                        std::size_t(args->threads));
                }
                if (!args->quiet) {
                    std::cout << "strata bake: " << scene.source << " → " << args->outputDir << "/\n  plan      "
                              << plan.counts[0] << " × " << plan.counts[2]
                              << (plan.counts[1] > 1 ? " × " + std::to_string(plan.counts[1]) + " slabs" : std::string())
                              << " tiles of " << formatNumber(plan.tileSize) << " m, " << plan.lods << " levels, "
                              << plan.selected.size() << " selected, about "
                              << mebibytes(plan.tileMemoryBytes) << " per tile" << std::endl;
                }
                TerminalProgress progress(std::cout, stdoutIsTerminal(), args->quiet);
                const BakeSummary summary = scene::bake(scene, options, plan, &progress);
                if (!args->quiet) printSummary(plan, summary);
                return 0;
            }};
}

} // namespace strata::app
