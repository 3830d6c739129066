// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/NoiseBenchReport.h>

#include <strata/terrain/SimdTarget.h>

#include <cstdio>
#include <sstream>

namespace strata::bench {

namespace {

std::string millions(double rate)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.2f", rate / 1e6);
    return text;
}

std::string ratio(double a, double b)
{
    char text[32];
    std::snprintf(text, sizeof(text), "%.2fx", a / b);
    return text;
}

} // namespace

std::string formatNoiseThroughput(const std::vector<terrain::NoiseThroughput>& rows,
                                  const terrain::NoiseThroughputOptions& options)
{
    std::string targets;
    for (const std::string& name : terrain::availableSimdTargets()) targets += (targets.empty() ? "" : ", ") + name;
    std::ostringstream out;
    out << "Noise throughput, one core, processor time (best of 3), M points/s.\n"
        << "Points: 64 blocks of 8^3 voxels " << options.spacing
        << " noise units apart (lattice order); 'scattered': the same count spread over 64 cells.\n"
        << "Block path: FractalNoise::evaluate. Version 1: lattice hashes (64-bit) reused within a cell, the "
           "arithmetic in double lanes. Version 2 (noise_version = 2): every point in its own float lane, its cell "
           "hashed in 32-bit lanes. Each gives the same bits as its scalar path on every target.\n"
        << "SIMD target in use: " << terrain::simdTarget() << " (this machine: " << targets << ").\n";
    const bool reference = !options.fastNoiseLite.empty();
    if (reference) {
        out << "FastNoiseLite: " << options.fastNoiseLite
            << ", compiled here with -O3 -march=native; GetNoise per point on the same points (as float), "
               "frequency 1; gradient = Perlin, simplex = OpenSimplex2, value = Value, cellular = Cellular "
               "(Euclidean; Distance, Distance2).\n";
    }
    const std::string target = terrain::simdTarget();
    out << "\n| noise | dims | v1 scalar, scattered | v1 scalar, voxels | v1 block, no SIMD | v1 block, " << target
        << " | v2 block, scattered | v2 block, " << target << " | v2 / v1 block |"
        << (reference ? " FastNoiseLite | v1 / FastNoiseLite | v2 / FastNoiseLite |" : "") << "\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|" << (reference ? "---:|---:|---:|" : "") << "\n";
    for (const terrain::NoiseThroughput& row : rows) {
        out << "| " << row.name << " | " << row.dimensions << "D | " << millions(row.scatteredRate) << " | "
            << millions(row.scalarRate) << " | " << millions(row.blockScalarTargetRate) << " | "
            << millions(row.blockRate) << " | " << millions(row.version2ScatteredRate) << " | "
            << millions(row.version2Rate) << " | " << ratio(row.version2Rate, row.blockRate) << " |";
        if (reference) {
            out << " " << millions(row.fastNoiseLiteRate) << " | " << ratio(row.blockRate, row.fastNoiseLiteRate)
                << " | " << ratio(row.version2Rate, row.fastNoiseLiteRate) << " |";
        }
        out << "\n";
    }
    return out.str();
}

} // namespace strata::bench
