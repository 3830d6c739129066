// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bake`: the command-line front of strata/scene/Bake.h.

#include "Commands.h"
#include "MemoryFlag.h"
#include "Progress.h"

#include <strata/Format.h>
#include <strata/scene/Bake.h>

#include <tbb/global_control.h>

#include <sys/resource.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
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
    std::string tileFormat = "meshopt";
    std::string georeference;
    bool quiet = false;
    bool worker = false;
    int tilesPerWorker = 1;
    std::optional<long long> workerIndex; ///< --tile I
    bool finalize = false;
    bool plan = false;
};

std::string mebibytes(std::uint64_t bytes)
{
    std::ostringstream out;
    out << std::fixed << std::setprecision(1) << double(bytes) / double(1 << 20) << " MiB";
    return out.str();
}

/// The worker's index: --tile, else the scheduler's variable.
long long workerIndex(const BakeArguments& args, std::string& from)
{
    if (args.workerIndex) {
        from = "--tile";
        return *args.workerIndex;
    }
    for (const char* name : {"SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"}) {
        const char* value = std::getenv(name);
        if (!value) continue;
        from = name;
        long long index = -1;
        const std::string_view text(value);
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), index);
        if (ec != std::errc() || end != text.data() + text.size() || index < 0)
            throw Error(ErrorKind::BadInput, std::string(name) + "='" + value + "' is not a worker index",
                        {"", 0, name, value});
        return index;
    }
    throw Error(ErrorKind::BadInput,
                "--worker needs its index: --tile I, or SLURM_ARRAY_TASK_ID (Slurm job array) or JOB_COMPLETION_INDEX "
                "(Kubernetes Indexed Job) in the environment",
                {"", 0, "--worker", ""});
}

/// The process's peak resident memory so far, bytes.
std::uint64_t peakResidentBytes()
{
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return std::uint64_t(usage.ru_maxrss) * 1024;
}

/// The erode nodes' global passes: each worker runs them once, when it
/// loads the scene (recomputing beats reading a stored grid: see docs/landforms.md).
void printLandformPasses(const Scene& scene)
{
    for (const LandformPass& pass : scene.landformPasses) {
        std::cout << "  landform  " << pass.node << ": " << withThousands(pass.cells) << " cells, " << pass.steps
                  << " steps, " << std::fixed << std::setprecision(1) << pass.seconds << " s"
                  << (pass.cached ? " (cached)" : "") << ", about " << mebibytes(pass.peakBytes)
                  << " at its peak; once per worker" << std::defaultfloat << std::endl;
    }
}

/// "  globe     36.5896° N, 84.2458° W, 600 m (the scene's DEM)", when the
/// tileset is placed on the Earth.
void printGeoreference(const Scene& scene, const BakePlan& plan)
{
    if (!plan.georeference) return;
    const Georeference& g = *plan.georeference;
    char text[160];
    std::snprintf(text, sizeof(text), "  globe     %.6f° %c, %.6f° %c, %s m (%s)\n", std::abs(g.latitude),
                  g.latitude < 0.0 ? 'S' : 'N', std::abs(g.longitude), g.longitude < 0.0 ? 'W' : 'E',
                  formatNumber(g.height).c_str(),
                  scene.georeference && *scene.georeference == g ? "the scene's DEM" : "--georeference");
    std::cout << text;
}

int printPlan(const Scene& scene, const BakeOptions& options, const BakePlan& plan, int perWorker)
{
    const int tiles = plan.tileCount();
    const int workers = (tiles + perWorker - 1) / perWorker;
    std::cout << "strata bake --plan: " << scene.source << "\n  world     " << plan.counts[0] << " × " << plan.counts[2]
              << " tiles of " << formatNumber(plan.tileSize) << " m"
              << (plan.counts[1] > 1 ? " × " + std::to_string(plan.counts[1]) + " slabs" : std::string()) << ", "
              << plan.lods << " levels: " << tiles << " tiles\n  workers   " << workers << " (" << perWorker
              << " tiles each, --tiles-per-worker " << perWorker << ")" << std::endl;
    printGeoreference(scene, plan);
    printLandformPasses(scene);
    const BakeSample sample = sampleBakeTile(scene, options, plan);
    const std::uint64_t peak = peakResidentBytes();
    // A task's memory: this process's peak with the sample tile, plus half.
    const std::uint64_t request = (peak + peak / 2 + (1 << 20) - 1) >> 20;
    const double taskSeconds = sample.seconds * perWorker;
    std::cout << "  per tile  " << std::fixed << std::setprecision(1) << sample.seconds << " s on one core, "
              << mebibytes(peak) << " peak memory (sample tile " << sample.index << ": " << withThousands(sample.triangles)
              << " triangles, " << mebibytes(sample.bytes) << " of .glb); estimate " << mebibytes(plan.tileMemoryBytes)
              << "\n  per task  about " << taskSeconds << " s; request " << request << " MiB\n  total     about "
              << sample.seconds * tiles / 60.0 << " CPU-minutes, about " << mebibytes(sample.bytes * std::uint64_t(tiles))
              << " of tiles\n  array     0-" << workers - 1 << std::defaultfloat << "\n"
              << "  slurm     sbatch --array=0-" << workers - 1 << "%8 --mem=" << request
              << "M examples/slurm/bake.sbatch SCENE DIR " << perWorker << std::endl;
    return 0;
}


void printSummary(const BakeSummary& summary, bool worker = false)
{
    std::cout << "  tiles     " << summary.baked << " baked, " << summary.kept << " kept (files match their records)";
    if (worker) {
        std::cout << "; when every worker is done: strata bake DIR --finalize" << std::endl;
        return;
    }
    std::cout << ", " << summary.missing << " of " << summary.tiles << " not in the manifest\n";
    for (std::size_t l = 0; l < summary.trianglesPerLevel.size(); ++l) {
        std::cout << "  level " << l << "   " << std::setw(6) << summary.filesPerLevel[l] << " files  " << std::setw(10)
                  << mebibytes(summary.bytesPerLevel[l]) << "  " << std::setw(14)
                  << withThousands(summary.trianglesPerLevel[l]) << " triangles  error "
                  << formatNumber(summary.errorPerLevel[l]) << " m\n";
    }
    for (const BakeHostTiles& host : summary.bakedBy)
        std::cout << "  baked by  " << host.host << " (" << host.arch << "): " << host.tiles.size() << " tiles: "
                  << indexRanges(host.tiles, ", ") << "\n";
    const double perMinute = summary.seconds > 0.0 ? 60.0 * summary.baked / summary.seconds : 0.0;
    std::cout << "  total     " << std::fixed << std::setprecision(3) << std::setw(8) << summary.seconds << " s";
    if (summary.baked > 0) std::cout << "   " << std::setprecision(1) << perMinute << " tiles/min";
    std::cout << std::defaultfloat << std::endl;
}

} // namespace

Command registerBakeCommand(CLI::App& app)
{
    auto args = std::make_shared<BakeArguments>();
    CLI::App* bake = app.add_subcommand(
        "bake", "Bake a world: the scene's region cut into tiles with levels of detail; writes DIR/tiles/L/X_Z.glb, "
                "DIR/grids/X_Z.vdb, DIR/manifest.json, DIR/tileset.json (OGC 3D Tiles 1.1). Re-running resumes.");
    bake->add_option("scene", args->scenePath,
                     "Scene file (TOML); without one, the embedded default scene. With --finalize: the bake folder")
        ->check(CLI::ExistingPath);
    bake->add_option("-o,--output", args->outputDir, "Output directory (created if missing)");
    bake->add_option("--tile-size", args->tileSize,
                     "Tile edge in metres: a multiple of the coarsest cell (voxel size × 2^(lods−1)), at most 1024 "
                     "voxels (default: 256 voxels)");
    bake->add_option("--lods", args->lods, "Levels of detail; level L has cells of 2^L voxels")
        ->capture_default_str()
        ->check(CLI::Range(1, 8));
    bake->add_option("--tiles", args->tiles, "Which tiles: all, or indices and ranges A-B (inclusive) with commas: 7, 0-63, 3,7-9")
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
    bake->add_option("--tile-format", args->tileFormat,
                     "How tiles are stored: meshopt (default: quantized, EXT_meshopt_compression, several times "
                     "smaller) or plain (float glTF any client reads)")
        ->check(CLI::IsMember({"plain", "meshopt"}));
    bake->add_option("--georeference", args->georeference,
                     "LAT,LON,HEIGHT: put the world on the Earth for globe clients (CesiumJS): the tileset's root "
                     "transform is east-north-up at that WGS84 point (degrees, degrees, metres above the ellipsoid), "
                     "the scene's origin there, +x east, -z north, +y up. Default: where the scene's georeferenced DEM "
                     "(dem_heightfield) puts it; none: nowhere");
    bake->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");
    bake->add_flag("--worker", args->worker,
                   "One worker of a scheduler's array: bakes tiles I·K to I·K+K−1 (K = --tiles-per-worker) into the "
                   "shared -o folder, I from --tile, SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX; then run --finalize");
    bake->add_option("--tiles-per-worker", args->tilesPerWorker, "Tiles per worker (with --worker and --plan)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 24));
    bake->add_option("--tile", args->workerIndex, "The worker's index (with --worker; default from the scheduler)");
    bake->add_flag("--finalize", args->finalize,
                   "strata bake DIR --finalize: check every tile of the bake in DIR and write manifest.json and "
                   "tileset.json (after the workers)");
    bake->add_flag("--plan", args->plan,
                   "Print the tiles, workers, time and memory per tile (from one sample tile, baked in memory) and "
                   "the array to submit; writes nothing");

    return {bake, [args]() {
                if (args->finalize) {
                    if (args->scenePath.empty() || !std::filesystem::is_directory(args->scenePath))
                        throw Error(ErrorKind::BadInput, "--finalize takes the bake folder: strata bake DIR --finalize");
                    TerminalProgress progress(std::cout, stdoutIsTerminal(), args->quiet);
                    const BakeSummary summary = finalizeBake(args->scenePath, &progress);
                    if (!args->quiet) {
                        std::cout << "strata bake --finalize: " << args->scenePath << "\n";
                        printSummary(summary);
                    }
                    return 0;
                }
                if (!args->plan && args->outputDir.empty()) throw Error(ErrorKind::BadInput, "--output is required (strata bake SCENE -o DIR)");
                // From here on the first Ctrl-C is a clean stop (exit 130).
                TerminalProgress progress(std::cout, stdoutIsTerminal(), args->quiet);
                if (!args->scenePath.empty() && std::filesystem::is_directory(args->scenePath))
                    throw Error(ErrorKind::BadInput, "'" + args->scenePath + "' is a folder: give a scene file (or --finalize a bake folder)");
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
                options.tileFormat = args->tileFormat == "plain" ? TileFormat::Plain : TileFormat::Meshopt;
                options.georeference = args->georeference;
                options.worker = args->worker;
                // Erode nodes run their global pass while the scene loads: once
                // per worker, refused first when over --max-memory (exit 2).
                const SceneLoadOptions load = sceneLoadOptions(options.maxMemoryBytes, progress);
                const Scene scene = args->scenePath.empty() ? defaultScene() : loadScene(args->scenePath, load);
                if (args->worker) {
                    // Check the world's size first, then the worker's slice of it.
                    const int tiles = planBake(scene, options).tileCount();
                    std::string from;
                    const long long index = workerIndex(*args, from);
                    const long long first = index * args->tilesPerWorker;
                    const int workers = (tiles + args->tilesPerWorker - 1) / args->tilesPerWorker;
                    if (first >= tiles)
                        throw Error(ErrorKind::BadInput,
                                    "worker index " + std::to_string(index) + " (" + from + ") is out of range: " +
                                        std::to_string(tiles) + " tiles, " + std::to_string(args->tilesPerWorker) +
                                        " per worker, so workers 0 to " + std::to_string(workers - 1),
                                    {"", 0, from, std::to_string(index)});
                    options.tiles = std::to_string(first) + "-" +
                                    std::to_string(std::min<long long>(first + args->tilesPerWorker, tiles) - 1);
                }
                const BakePlan plan = planBake(scene, options); // bad flags: exit 2, nothing written
                if (args->plan) return printPlan(scene, options, plan, args->tilesPerWorker);
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
                    printGeoreference(scene, plan);
                    printLandformPasses(scene);
                }
                const BakeSummary summary = scene::bake(scene, options, plan, &progress);
                if (!args->quiet) printSummary(summary, args->worker);
                return 0;
            }};
}

} // namespace strata::app
