// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Terrain figures: noise throughput per type, the default scene's field and
// its sampling at 1 and 2 threads, evaluated/active, bytes per active voxel,
// and | |∇φ| − 1 | before and after renormalisation. Numbers only; nothing
// here asserts on time.

#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/LevelSetQuality.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/TerrainField.h>
#include <strata/terrain/Transforms.h>

#ifdef STRATA_BENCH_DEFAULT_SCENE
#include <strata/scene/Scene.h>
#include "../terrain/DefaultSceneTree.h"
#endif

#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <functional>
#include <numeric>
#include <memory>
#include <vector>

using namespace strata::terrain;

namespace {

/// Points spread over a few hundred noise cells, generated without std:: distributions.
const std::vector<glm::dvec3>& points()
{
    static const std::vector<glm::dvec3> pts = [] {
        std::vector<glm::dvec3> out;
        std::uint64_t s = 1;
        const auto next = [&s] {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            return double(s >> 11) * 0x1.0p-53;
        };
        for (int i = 0; i < 4096; ++i) out.emplace_back(200 * next() - 100, 80 * next() - 40, 200 * next() - 100);
        return out;
    }();
    return pts;
}

void runNoise(benchmark::State& state, const std::function<double(const glm::dvec3&)>& f)
{
    const auto& pts = points();
    double sink = 0.0;
    for (auto _ : state) {
        for (const glm::dvec3& p : pts) sink += f(p);
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(pts.size()));
}

void BM_Gradient3(benchmark::State& s) { runNoise(s, [](const glm::dvec3& p) { return gradientNoise(1, p * 0.1); }); }
void BM_Gradient2(benchmark::State& s)
{
    runNoise(s, [](const glm::dvec3& p) { return gradientNoise(1, glm::dvec2(p.x, p.z) * 0.1); });
}
void BM_Simplex3(benchmark::State& s) { runNoise(s, [](const glm::dvec3& p) { return simplexNoise(1, p * 0.1); }); }
void BM_Simplex2(benchmark::State& s)
{
    runNoise(s, [](const glm::dvec3& p) { return simplexNoise(1, glm::dvec2(p.x, p.z) * 0.1); });
}
void BM_Value3(benchmark::State& s) { runNoise(s, [](const glm::dvec3& p) { return valueNoise(1, p * 0.1); }); }
void BM_Value2(benchmark::State& s)
{
    runNoise(s, [](const glm::dvec3& p) { return valueNoise(1, glm::dvec2(p.x, p.z) * 0.1); });
}
void BM_CellularF1F2_3(benchmark::State& s)
{
    runNoise(s, [](const glm::dvec3& p) {
        const CellularDistances c = cellularNoise(1, p * 0.1);
        return c.f1 + c.f2;
    });
}
void BM_CellularF1F2_2(benchmark::State& s)
{
    runNoise(s, [](const glm::dvec3& p) {
        const CellularDistances c = cellularNoise(1, glm::dvec2(p.x, p.z) * 0.1);
        return c.f1 + c.f2;
    });
}

/// A 5-octave fractal sum of `noise` combined by `fractal` (per sample: 5 noise calls).
void BM_Fractal(benchmark::State& s, NoiseType noise, FractalType fractal)
{
    const FractalNoise f(1, FractalOptions{noise, fractal, 5, 2.0, 0.5});
    runNoise(s, [&f](const glm::dvec3& p) { return f(p * 0.05); });
}

void BM_DomainWarp(benchmark::State& s)
{
    const DomainWarp warp(1, FractalOptions{NoiseType::GRADIENT, FractalType::FBM, 2, 2.0, 0.5}, 0.3);
    runNoise(s, [&warp](const glm::dvec3& p) { return warp(p * 0.05).x; });
}

/// The default scene's root field (the embedded scene when the app library
/// is there, else the same tree built by hand).
std::shared_ptr<const DensityField> defaultField()
{
#ifdef STRATA_BENCH_DEFAULT_SCENE
    return strata::scene::parseScene(std::string(strata::scene::defaultSceneText()), "<default scene>").field;
#else
    DensityFieldPtr hills = std::make_shared<NoiseHeightfield>(deriveSeed(1, 1), NoiseHeightfieldOptions{});
    WarpOptions warp;
    warp.amplitude = 7.0;
    warp.wavelength = 32.0;
    warp.vertical = 0.0;
    DensityFieldPtr land = std::make_shared<WarpField>(hills, 2, warp);
    WormOptions worms;
    worms.wormsPerCell = 3.0;
    return std::make_shared<CsgField>(CsgOperation::SUBTRACT,
                                      std::vector<DensityFieldPtr>{land, std::make_shared<WormCaves>(3, worms)}, 1.0);
#endif
}

/// density() of the default field over points near its surface, on
/// state.range(0) threads; items/s over all threads (divide by the thread
/// count for per core).
void BM_DefaultFieldDensity(benchmark::State& state)
{
    const int threads = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const auto field = defaultField();
    std::vector<glm::dvec3> pts;
    for (const glm::dvec3& p : points()) pts.emplace_back(p.x, 0.25 * p.y, p.z); // y in ±10 m: around the ground
    for (auto _ : state) {
        std::vector<double> out(pts.size());
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), 64), [&](const auto& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) out[i] = field->density(pts[i]);
        });
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(pts.size()));
    state.counters["per_core_per_s"] =
        benchmark::Counter(double(state.iterations()) * double(pts.size()) / threads, benchmark::Counter::kIsRate);
}

/// The default scene's field through the block path over 1 M points in
/// its region (x, y, z rows, as a NumPy (N, 3) array holds them), in blocks
/// of 512, one thread: the C++ side of `python/bench/evaluate_bench.py`,
/// which times strata's Field.evaluate on the same points (the same
/// generator) to measure what the binding costs (issue 28: at most 1.2×).
void BM_DefaultFieldBlocks(benchmark::State& state)
{
    const auto field = defaultField();
    constexpr std::size_t COUNT = 1'000'000, BLOCK = 512;
    std::vector<double> rows(3 * COUNT);
    std::uint64_t s = 1;
    for (std::size_t i = 0; i < COUNT; ++i) {
        const double extent[3] = {192.0, 88.0, 192.0};
        for (int axis = 0; axis < 3; ++axis) {
            s = s * 6364136223846793005ULL + 1442695040888963407ULL;
            rows[3 * i + axis] = extent[axis] * (double(s >> 11) * 0x1.0p-53) - 0.5 * extent[axis];
        }
    }
    std::vector<double> out(COUNT);
    for (auto _ : state) {
        double x[BLOCK], y[BLOCK], z[BLOCK];
        for (std::size_t first = 0; first < COUNT; first += BLOCK) {
            const std::size_t n = std::min(BLOCK, COUNT - first);
            for (std::size_t i = 0; i < n; ++i) {
                x[i] = rows[3 * (first + i)];
                y[i] = rows[3 * (first + i) + 1];
                z[i] = rows[3 * (first + i) + 2];
            }
            strata::terrain::PointBlock block{x, y, z, n, {}};
            block.box = strata::terrain::spannedBox(block);
            field->densities(block, out.data() + first);
        }
        benchmark::DoNotOptimize(out.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(COUNT));
    state.counters["checksum"] = std::accumulate(out.begin(), out.end(), 0.0);
}

/// bounds() of the default field over boxes of 2³ voxels (0.5 m voxels:
/// 0.5 m between the first and last voxel centre) at the same points as
/// BM_DefaultFieldDensity, one thread: the cost the sampler counts as one
/// evaluated point per call.
void BM_DefaultFieldBounds(benchmark::State& state)
{
    const auto field = defaultField();
    const double size = 0.5 * double(state.range(0) - 1);
    std::vector<glm::dvec3> pts;
    for (const glm::dvec3& p : points()) pts.emplace_back(p.x, 0.25 * p.y, p.z);
    double sink = 0.0;
    for (auto _ : state) {
        for (const glm::dvec3& p : pts) {
            const Interval b = field->bounds({p, p + size});
            sink += b.hi - b.lo;
        }
    }
    benchmark::DoNotOptimize(sink);
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(pts.size()));
    state.counters["mean_width"] = sink / double(state.iterations()) / double(pts.size());
}

/// The default scene's tree without its terrace node (warped hills minus
/// worms), built by hand with the scene's values, for comparison.
std::shared_ptr<const DensityField> warpedHillsField() { return strata::test::defaultSceneTree(false); }

SampleOptions defaultSampling()
{
    SampleOptions o;
    o.voxelSize = 0.5;
    o.halfWidth = 3;
    o.region = {{-96.0, -44.0, -96.0}, {96.0, 44.0, 96.0}};
    return o;
}

/// The whole default scene sampled (as `strata generate` does) on
/// state.range(0) threads; state.range(1) = 1 renormalises the band.
void BM_SampleDefaultScene(benchmark::State& state)
{
    const int threads = int(state.range(0));
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const auto field = defaultField();
    SampleOptions options = defaultSampling();
    options.renormalize = state.range(1) != 0;
    SampleStats stats;
    openvdb::FloatGrid::Ptr grid;
    for (auto _ : state) {
        grid = sampleLevelSet(*field, options, &stats);
    }
    const SdfQuality q = measureSdfQuality(*grid);
    state.counters["evaluated"] = double(stats.evaluatedPoints);
    state.counters["bounds"] = double(stats.boundEvaluations);
    state.counters["active"] = double(stats.activeVoxels);
    state.counters["eval/active"] = double(stats.evaluatedPoints) / double(stats.activeVoxelsBeforeRenormalize);
    state.counters["bytes/active"] = double(grid->memUsage()) / double(stats.activeVoxels);
    state.counters["estimate/mem"] = double(stats.estimatedBytes) / double(grid->memUsage());
    state.counters["evals_per_core_per_s"] = benchmark::Counter(
        double(stats.evaluatedPoints) * double(state.iterations()) / threads, benchmark::Counter::kIsRate);
    state.counters["sdf_err_mean"] = q.meanError;
    state.counters["sdf_err_max"] = q.maxError;
}

/// The default scene without terraces (warpedHillsField), 2 threads.
void BM_SampleWarpedHills(benchmark::State& state)
{
    const auto field = warpedHillsField();
    const SampleOptions options = defaultSampling();
    SampleStats stats;
    openvdb::FloatGrid::Ptr grid;
    for (auto _ : state) grid = sampleLevelSet(*field, options, &stats);
    state.counters["evaluated"] = double(stats.evaluatedPoints);
    state.counters["bounds"] = double(stats.boundEvaluations);
    state.counters["active"] = double(stats.activeVoxels);
    state.counters["eval/active"] = double(stats.evaluatedPoints) / double(stats.activeVoxels);
    state.counters["bytes/active"] = double(grid->memUsage()) / double(stats.activeVoxels);
}

/// The old shorthand field (heightfield minus 1-Lipschitz spaghetti), for comparison.
void BM_SampleShorthandScene(benchmark::State& state)
{
    const TerrainField field{TerrainOptions{}};
    SampleOptions options = defaultSampling();
    options.renormalize = state.range(0) != 0;
    SampleStats stats;
    openvdb::FloatGrid::Ptr grid;
    for (auto _ : state) grid = sampleLevelSet(field, options, &stats);
    const SdfQuality q = measureSdfQuality(*grid);
    state.counters["evaluated"] = double(stats.evaluatedPoints);
    state.counters["active"] = double(stats.activeVoxels);
    state.counters["eval/active"] = double(stats.evaluatedPoints) / double(stats.activeVoxelsBeforeRenormalize);
    state.counters["bytes/active"] = double(grid->memUsage()) / double(stats.activeVoxels);
    state.counters["sdf_err_mean"] = q.meanError;
    state.counters["sdf_err_max"] = q.maxError;
}

} // namespace

BENCHMARK(BM_Gradient3);
BENCHMARK(BM_Gradient2);
BENCHMARK(BM_Simplex3);
BENCHMARK(BM_Simplex2);
BENCHMARK(BM_Value3);
BENCHMARK(BM_Value2);
BENCHMARK(BM_CellularF1F2_3);
BENCHMARK(BM_CellularF1F2_2);
BENCHMARK_CAPTURE(BM_Fractal, gradient_fbm5, NoiseType::GRADIENT, FractalType::FBM);
BENCHMARK_CAPTURE(BM_Fractal, gradient_ridged5, NoiseType::GRADIENT, FractalType::RIDGED);
BENCHMARK_CAPTURE(BM_Fractal, gradient_billow5, NoiseType::GRADIENT, FractalType::BILLOW);
BENCHMARK_CAPTURE(BM_Fractal, simplex_fbm5, NoiseType::SIMPLEX, FractalType::FBM);
BENCHMARK_CAPTURE(BM_Fractal, value_fbm5, NoiseType::VALUE, FractalType::FBM);
BENCHMARK_CAPTURE(BM_Fractal, cellular_f1_fbm5, NoiseType::CELLULAR_F1, FractalType::FBM);
BENCHMARK(BM_DomainWarp);
BENCHMARK(BM_DefaultFieldDensity)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK(BM_DefaultFieldBlocks)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_DefaultFieldBounds)->Arg(2)->Arg(4)->Arg(8);
BENCHMARK(BM_SampleDefaultScene)->Args({1, 0})->Args({2, 0})->Args({2, 1})->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_SampleWarpedHills)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);
BENCHMARK(BM_SampleShorthandScene)->Arg(0)->Arg(1)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
