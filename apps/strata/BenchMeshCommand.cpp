// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench mesh -o DIR`: the meshers measured on analytic shapes and the
// chunk mesher's single-core throughput (bench::runMeshBench,
// bench/MeshBench.h); writes DIR/mesh-bench.md and DIR/mesh-bench.csv.

#include "Commands.h"

#include <strata/bench/MeshBenchReport.h>
#include <strata/bench/ReportText.h>

#include <chrono>
#include <iostream>
#include <memory>

namespace strata::app {

namespace {

struct BenchArguments
{
    std::string outputDir;
    bench::MeshBenchOptions options;
};

int runBench(const BenchArguments& args)
{
    const std::filesystem::path dir(args.outputDir);
    std::filesystem::create_directories(dir);
    const auto total = std::chrono::steady_clock::now();
    const auto seconds = [total] {
        return bench::fixedDigits(std::chrono::duration<double>(std::chrono::steady_clock::now() - total).count(), 1);
    };
    const bench::MeshBenchResult result = bench::runMeshBench(args.options, [&](const std::string& shape, int across) {
        std::cout << "bench mesh: " << shape << " at " << across << " voxels across done (" << seconds() << " s)"
                  << std::endl;
    });
    const std::string md = bench::formatMeshBenchMarkdown(result);
    bench::writeTextFile(dir / "mesh-bench.md", md);
    bench::writeTextFile(dir / "mesh-bench.csv", bench::formatMeshBenchCsv(result));
    std::cout << md << "\nwrote " << (dir / "mesh-bench.md").string() << " and " << (dir / "mesh-bench.csv").string()
              << " in " << seconds() << " s" << std::endl;
    return 0;
}

} // namespace

Command registerBenchMeshCommand(CLI::App& bench)
{
    auto args = std::make_shared<BenchArguments>();
    CLI::App* mesh = bench.add_subcommand(
        "mesh", "Measure the meshers on analytic shapes; writes DIR/mesh-bench.md and DIR/mesh-bench.csv");
    mesh->add_option("-o,--output", args->outputDir, "Output directory (created if missing)")->required();
    mesh->add_flag("--quick", args->options.quick, "Two shapes at two resolutions (a smoke test, seconds)");
    return {mesh, [args]() { return runBench(*args); }};
}

} // namespace strata::app
