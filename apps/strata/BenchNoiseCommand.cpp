// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench noise`: points per second per core of each noise basis and
// its 5-octave fBm, scalar path against block path (measured by
// terrain::measureNoiseThroughput, tabled by bench::formatNoiseThroughput);
// this file parses flags and prints.

#include "Commands.h"

#include <strata/bench/NoiseBenchReport.h>
#include <strata/terrain/SimdTarget.h>

#include <iostream>
#include <memory>

namespace strata::app {

Command registerBenchNoiseCommand(CLI::App& bench)
{
    auto options = std::make_shared<terrain::NoiseThroughputOptions>();
    auto simd = std::make_shared<std::string>();
    CLI::App* noise = bench.add_subcommand(
        "noise", "Points per second per core of each noise basis and 5-octave fBm: scalar path against block path");
    noise->add_option("--spacing", options->spacing, "Voxel spacing in noise units")
        ->check(CLI::Range(1e-6, 16.0))
        ->capture_default_str();
    noise->add_option("--seconds", options->seconds, "Processor seconds per measurement")
        ->check(CLI::Range(0.01, 60.0))
        ->capture_default_str();
    noise->add_option("--simd", *simd, "Run the block path on this SIMD target (default: the best this machine has)")
        ->check(CLI::IsMember(terrain::availableSimdTargets()));
    noise->add_option("--fastnoise-lite", options->fastNoiseLite,
                      "A copy of FastNoiseLite.h (C++; never shipped with Strata) to measure beside the block path on "
                      "the same points: compiled here with $CXX -O3 -march=native");
    return {noise, [options, simd]() {
                if (!simd->empty()) terrain::useSimdTarget(*simd); // one of availableSimdTargets(): checked by the flag
                // Measured first, so a bad --fastnoise-lite fails before anything is printed.
                const std::vector<terrain::NoiseThroughput> rows = terrain::measureNoiseThroughput(*options);
                std::cout << strata::bench::formatNoiseThroughput(rows, *options) << std::flush;
                return 0;
            }};
}

} // namespace strata::app
