// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/NoiseThroughput.h>
#include <strata/terrain/SimdTarget.h>

#include "FastNoiseLiteReference.h"

#include <ctime>
#include <functional>
#include <memory>
#include <vector>

namespace strata::terrain {

namespace {

double processSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Points per second of `run` (which handles `points` points per call):
/// repeated for options.seconds, the best of three such runs.
double rate(const std::function<void()>& run, std::size_t points, double seconds)
{
    double best = 0.0;
    for (int attempt = 0; attempt < 3; ++attempt) {
        const double start = processSeconds();
        std::size_t done = 0;
        double elapsed = 0.0;
        do {
            run();
            done += points;
            elapsed = processSeconds() - start;
        } while (elapsed < seconds / 3.0);
        best = std::max(best, double(done) / elapsed);
    }
    return best;
}

/// 64 blocks of 8³ voxels `spacing` apart, each block's points in lattice
/// order (x outer, z inner), the blocks spread over the noise.
struct Blocks
{
    static constexpr std::size_t BLOCK = 512;
    std::vector<double> x, y, z;
};

Blocks voxelBlocks(double spacing)
{
    Blocks b;
    for (int block = 0; block < 64; ++block) {
        const double ox = 37.3 * block, oy = -11.1 * (block % 7), oz = 5.7 * (block % 13);
        for (int i = 0; i < 8; ++i)
            for (int j = 0; j < 8; ++j)
                for (int k = 0; k < 8; ++k) {
                    b.x.push_back(ox + i * spacing);
                    b.y.push_back(oy + j * spacing);
                    b.z.push_back(oz + k * spacing);
                }
    }
    return b;
}

Blocks scatteredPoints(std::size_t count)
{
    Blocks b;
    std::uint64_t s = 1;
    const auto next = [&s] {
        s = s * 6364136223846793005ULL + 1442695040888963407ULL;
        return double(s >> 11) * 0x1.0p-53;
    };
    for (std::size_t i = 0; i < count; ++i) {
        b.x.push_back(64.0 * next());
        b.y.push_back(16.0 * next());
        b.z.push_back(64.0 * next());
    }
    return b;
}

} // namespace

std::vector<NoiseThroughput> measureNoiseThroughput(const NoiseThroughputOptions& options)
{
    const Blocks blocks = voxelBlocks(options.spacing);
    const Blocks scattered = scatteredPoints(blocks.x.size());
    const std::size_t n = blocks.x.size();
    std::vector<double> out(n);
    // FastNoiseLite takes float coordinates: the same points, rounded.
    std::unique_ptr<detail::FastNoiseLiteReference> reference;
    std::vector<float> fx, fy, fz, fout(n);
    if (!options.fastNoiseLite.empty()) {
        reference = std::make_unique<detail::FastNoiseLiteReference>(options.fastNoiseLite);
        for (std::size_t i = 0; i < n; ++i) {
            fx.push_back(float(blocks.x[i]));
            fy.push_back(float(blocks.y[i]));
            fz.push_back(float(blocks.z[i]));
        }
    }
    volatile double sink = 0.0;

    const struct
    {
        const char* name;
        NoiseType type;
        detail::ReferenceBasis reference;
    } bases[] = {{"gradient", NoiseType::GRADIENT, detail::ReferenceBasis::GRADIENT},
                 {"simplex", NoiseType::SIMPLEX, detail::ReferenceBasis::SIMPLEX},
                 {"value", NoiseType::VALUE, detail::ReferenceBasis::VALUE},
                 {"cellular F1", NoiseType::CELLULAR_F1, detail::ReferenceBasis::CELLULAR_F1},
                 {"cellular F2", NoiseType::CELLULAR_F2, detail::ReferenceBasis::CELLULAR_F2}};
    // The block path also runs on Highway's portable target (SCALAR, or
    // EMU128 with compilers that support it: no SIMD); then the target that
    // was in use comes back.
    const std::string inUse = simdTarget();
    const std::vector<std::string> targets = availableSimdTargets();
    const bool best = inUse == targets.front();
    const auto restore = [&] { useSimdTarget(best ? std::string() : inUse); };
    std::vector<NoiseThroughput> rows;
    for (const int dimensions : {3, 2})
        for (const int octaves : {1, 5})
            for (const auto& basis : bases) {
                const FractalNoise noise(7, {basis.type, FractalType::FBM, octaves, 2.0, 0.5});
                NoiseThroughput row;
                row.name = std::string(basis.name) + (octaves > 1 ? " fBm 5" : "");
                row.dimensions = dimensions;
                const auto scalarOver = [&](const Blocks& points) {
                    return [&noise, &points, &sink, dimensions] {
                        double sum = 0.0;
                        for (std::size_t i = 0; i < points.x.size(); ++i)
                            sum += dimensions == 3 ? noise({points.x[i], points.y[i], points.z[i]})
                                                   : noise(glm::dvec2(points.x[i], points.z[i]));
                        sink = sink + sum;
                    };
                };
                row.scalarRate = rate(scalarOver(blocks), n, options.seconds);
                row.scatteredRate = rate(scalarOver(scattered), n, options.seconds);
                // The block path of `f` over `points`, a block of 8³ at a time.
                const auto blockOver = [&](const FractalNoise& f, const Blocks& points) {
                    return [&f, &points, &out, &sink, n, dimensions] {
                        for (std::size_t at = 0; at < n; at += Blocks::BLOCK) {
                            if (dimensions == 3)
                                f.evaluate(&points.x[at], &points.y[at], &points.z[at], Blocks::BLOCK, &out[at]);
                            else
                                f.evaluate(&points.x[at], &points.z[at], Blocks::BLOCK, &out[at]);
                        }
                        sink = sink + out[n / 2];
                    };
                };
                const auto blockPath = blockOver(noise, blocks);
                row.blockRate = rate(blockPath, n, options.seconds);
                const FractalNoise version2(7, {basis.type, FractalType::FBM, octaves, 2.0, 0.5, 2});
                row.version2Rate = rate(blockOver(version2, blocks), n, options.seconds);
                row.version2ScatteredRate = rate(blockOver(version2, scattered), n, options.seconds);
                useSimdTarget(targets.back());
                row.blockScalarTargetRate = rate(blockPath, n, options.seconds);
                restore();
                if (reference) {
                    row.fastNoiseLiteRate = rate(
                        [&] {
                            reference->fill(basis.reference, octaves, dimensions, fx.data(), fy.data(), fz.data(), n,
                                            fout.data());
                            sink = sink + fout[n / 2];
                        },
                        n, options.seconds);
                }
                rows.push_back(row);
            }
    return rows;
}

} // namespace strata::terrain
