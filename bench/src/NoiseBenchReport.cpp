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
        << "Block path: FractalNoise::evaluate, lattice hashes reused within a cell, the arithmetic in "
           "SIMD lanes; the same bits as the scalar path on every target.\n"
        << "SIMD target in use: " << terrain::simdTarget() << " (this machine: " << targets << ").\n";
    const bool reference = !options.fastNoiseLite.empty();
    if (reference) {
        out << "FastNoiseLite: " << options.fastNoiseLite
            << ", compiled here with -O3 -march=native; GetNoise per point on the same points (as float), "
               "frequency 1; gradient = Perlin, simplex = OpenSimplex2, value = Value, cellular = Cellular "
               "(Euclidean; Distance, Distance2).\n";
    }
    out << "\n| noise | dims | scalar, scattered | scalar, voxels | block, no SIMD | block, " << terrain::simdTarget()
        << " | block / scalar |" << (reference ? " FastNoiseLite | block / FastNoiseLite |" : "") << "\n"
        << "|---|---:|---:|---:|---:|---:|---:|" << (reference ? "---:|---:|" : "") << "\n";
    for (const terrain::NoiseThroughput& row : rows) {
        out << "| " << row.name << " | " << row.dimensions << "D | " << millions(row.scatteredRate) << " | "
            << millions(row.scalarRate) << " | " << millions(row.blockScalarTargetRate) << " | "
            << millions(row.blockRate) << " | " << ratio(row.blockRate, row.scalarRate) << " |";
        if (reference) {
            out << " " << millions(row.fastNoiseLiteRate) << " | " << ratio(row.blockRate, row.fastNoiseLiteRate)
                << " |";
        }
        out << "\n";
    }
    return out.str();
}

} // namespace strata::bench
