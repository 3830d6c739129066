// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench noise`: points per second per core of each noise basis and
// its 5-octave fBm, scalar path against block path (the measurement is
// terrain::measureNoiseThroughput; this file parses flags and prints).

#include "Commands.h"

#include <strata/terrain/NoiseThroughput.h>
#include <strata/terrain/SimdTarget.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace strata::app {

namespace {

std::string millions(double rate)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f", rate / 1e6);
    return text;
}

int runNoiseBench(const terrain::NoiseThroughputOptions& options, const std::string& simd)
{
    if (!simd.empty()) terrain::useSimdTarget(simd); // one of availableSimdTargets(): checked by the flag
    // Measured first, so a bad --fastnoise-lite fails before anything is printed.
    const std::vector<terrain::NoiseThroughput> rows = terrain::measureNoiseThroughput(options);
    std::string targets;
    for (const std::string& name : terrain::availableSimdTargets()) targets += (targets.empty() ? "" : ", ") + name;
    std::cout << "Noise throughput, one core, processor time (best of 3), M points/s.\n"
              << "Points: 64 blocks of 8^3 voxels " << options.spacing
              << " noise units apart (lattice order); 'scattered': the same count spread over 64 cells.\n"
              << "Block path: FractalNoise::evaluate, lattice hashes reused within a cell, the arithmetic in "
                 "SIMD lanes; the same bits as the scalar path on every target.\n"
              << "SIMD target in use: " << terrain::simdTarget() << " (this machine: " << targets << ").\n";
    const bool reference = !options.fastNoiseLite.empty();
    if (reference) {
        std::cout << "FastNoiseLite: " << options.fastNoiseLite
                  << ", compiled here with -O3 -march=native; GetNoise per point on the same points (as float), "
                     "frequency 1; gradient = Perlin, simplex = OpenSimplex2, value = Value, cellular = Cellular "
                     "(Euclidean; Distance, Distance2).\n";
    }
    std::cout << "\n| noise | dims | scalar, scattered | scalar, voxels | block, no SIMD | block, " << terrain::simdTarget()
              << " | block / scalar |" << (reference ? " FastNoiseLite | block / FastNoiseLite |" : "") << "\n"
              << "|---|---:|---:|---:|---:|---:|---:|" << (reference ? "---:|---:|" : "") << "\n";
    const auto ratio = [](double a, double b) {
        char text[32];
        std::snprintf(text, sizeof(text), "%.2fx", a / b);
        return std::string(text);
    };
    for (const terrain::NoiseThroughput& row : rows) {
        std::cout << "| " << row.name << " | " << row.dimensions << "D | " << millions(row.scatteredRate) << " | "
                  << millions(row.scalarRate) << " | " << millions(row.blockScalarTargetRate) << " | "
                  << millions(row.blockRate) << " | " << ratio(row.blockRate, row.scalarRate) << " |";
        if (reference) {
            std::cout << " " << millions(row.fastNoiseLiteRate) << " | " << ratio(row.blockRate, row.fastNoiseLiteRate)
                      << " |";
        }
        std::cout << std::endl;
    }
    return 0;
}

} // namespace

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
    return {noise, [options, simd]() { return runNoiseBench(*options, *simd); }};
}

} // namespace strata::app
