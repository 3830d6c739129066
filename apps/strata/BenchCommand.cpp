// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench -o DIR [--quick]`: speed against accuracy, measured by
// bench::runQualityBench (bench/QualityBench.h), which writes DIR/report.md,
// DIR/report.csv and DIR/pareto.png; this file parses flags and prints.
// `bench mesh`, `bench noise` and `bench landforms` are registered under it.

#include "Commands.h"

#include <strata/bench/QualityReport.h>
#include <strata/bench/ReportText.h>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>

namespace strata::app {

namespace {

struct BenchArguments
{
    std::string outputDir;
    bool quick = false;
    bool tiny = false; // hidden: the ctest setting
    int threads = 0;
};

int runBench(const BenchArguments& args)
{
    using bench::fixedOrBlank;
    const auto total = std::chrono::steady_clock::now();
    const std::filesystem::path dir(args.outputDir);
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir)) {
        throw Error(ErrorKind::Io, "cannot create output directory '" + dir.string() + "': " + ec.message(), {dir.string()});
    }
    std::optional<tbb::global_control> threadLimit;
    if (args.threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(args.threads));
    bench::QualityBenchObserver observer;
    observer.started = [](const bench::QualityBenchResult& r) {
        std::cout << "strata bench (" << r.size.name << "): " << r.configs.size() << " configurations on " << r.machine
                  << ", " << r.threads << " threads, renderer: " << (r.gl ? r.renderer : "CPU") << std::endl;
    };
    observer.sceneMeasured = [](const bench::QualityConfig& config, const bench::QualityRow& row) {
        std::cout << "  " << config.name << ": scene " << fixedOrBlank(row.meshSeconds, 2) << " s mesh, "
                  << fixedOrBlank(row.renderSeconds, 3) << " s render (" << row.backend << "), PSNR "
                  << fixedOrBlank(row.psnr, 1) << " dB" << std::endl;
    };
    const int threads = args.threads > 0 ? args.threads : tbb::this_task_arena::max_concurrency();
    const bench::QualityBenchResult result =
        bench::runQualityBench(bench::qualityBenchSize(args.tiny, args.quick), threads, std::cerr, observer);
    bench::writeQualityReport(result, dir);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - total).count();
    std::cout << "wrote " << (dir / "report.md").string() << ", " << (dir / "report.csv").string() << " and "
              << (dir / "pareto.png").string() << " in " << fixedOrBlank(seconds, 1) << " s" << std::endl;
    return 0;
}

} // namespace

Command registerBenchCommand(CLI::App& app)
{
    auto args = std::make_shared<BenchArguments>();
    CLI::App* bench = app.add_subcommand(
        "bench", "Speed against accuracy: the default scene and analytic shapes under each quality preset and each "
                 "knob on its own; writes DIR/report.md, DIR/report.csv, DIR/pareto.png. `bench mesh`: the meshers; `bench noise`: the noise bases; `bench landforms`: the top surface against real land");
    bench->add_option("-o,--output", args->outputDir, "Output directory (created if missing)");
    bench->add_flag("--quick", args->quick, "A smaller scene region, images and fewer shapes (under a minute on 2 cores)");
    bench->add_flag("--tiny", args->tiny, "The test setting (seconds)")->group("");
    bench->add_option("--threads", args->threads, "Worker threads (0 = all cores)")->check(CLI::Range(0, 1024));
    const Command mesh = registerBenchMeshCommand(*bench);
    const Command noise = registerBenchNoiseCommand(*bench);
    const Command landforms = registerBenchLandformsCommand(*bench);
    return {bench, [args, mesh, noise, landforms]() {
                if (mesh.subcommand->parsed()) return mesh.run();
                if (noise.subcommand->parsed()) return noise.run();
                if (landforms.subcommand->parsed()) return landforms.run();
                if (args->outputDir.empty()) throw Error(ErrorKind::BadInput, "bench: -o DIR is required");
                return runBench(*args);
            }};
}

} // namespace strata::app
