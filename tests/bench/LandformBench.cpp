// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Landform figures: the erode node's global pass over the showcase's 4 km
// domain (examples/worlds/mountains4k.toml) at 8 m (513²) and 4 m (1025²)
// cells, and its parts (flow routing, drainage area, the statistics).
// Numbers only; nothing here asserts on time.

#include <strata/terrain/FlowRouting.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/HeightGraph.h>
#include <strata/terrain/LandformStatistics.h>
#include <strata/terrain/StreamPowerErosion.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

using namespace strata::terrain;

namespace {

/// The showcase's initial surface and uplift map, sampled at the corners of
/// a 4096 m domain: what the erode node evolves.
struct Showcase
{
    int size = 0;
    double cell = 0.0;
    std::vector<double> heights, uplift;
};

const Showcase& showcase(double cell)
{
    static Showcase cached[2];
    Showcase& s = cached[cell < 6.0 ? 1 : 0];
    if (s.size > 0) return s;
    NoiseHeightfieldOptions hills;
    hills.amplitude = 30.0;
    hills.wavelength = 1500.0;
    const NoiseHeightfield initial(1, hills);
    NoiseHeightfieldOptions ridges;
    ridges.amplitude = 1.0;
    ridges.wavelength = 3000.0;
    ridges.noise.fractal = FractalType::RIDGED;
    ridges.noise.octaves = 3;
    const NoiseHeightfield range(2, ridges);
    s.cell = cell;
    s.size = int(4096.0 / cell) + 1;
    for (int z = 0; z < s.size; ++z) {
        for (int x = 0; x < s.size; ++x) {
            const double px = -2048.0 + x * cell, pz = -2048.0 + z * cell;
            s.heights.push_back(initial.height(px, pz));
            s.uplift.push_back(0.5 + 0.5 * std::clamp(range.height(px, pz), 0.0, 1.0));
        }
    }
    return s;
}

StreamPowerOptions evolution(double cell)
{
    StreamPowerOptions o;
    o.cellSize = cell;
    o.years = 2e6;
    o.timeStep = 2e4;
    o.uplift = 3e-4;
    o.erodibility = 1.5e-5;
    o.diffusivity = 0.005;
    return o;
}

void BM_GlobalPass(benchmark::State& state)
{
    const double cell = double(state.range(0));
    const Showcase& s = showcase(cell);
    StreamPowerResult r;
    for (auto _ : state) r = evolveLandscape(s.heights, s.size, s.size, s.uplift, evolution(cell));
    state.counters["cells"] = double(s.size) * s.size;
    state.counters["steps"] = r.steps;
    state.counters["ns_per_cell_step"] =
        benchmark::Counter(double(s.size) * s.size * r.steps, benchmark::Counter::kIsIterationInvariantRate |
                                                                   benchmark::Counter::kInvert);
}

void BM_RouteFlow(benchmark::State& state)
{
    const double cell = double(state.range(0));
    const Showcase& s = showcase(cell);
    for (auto _ : state) benchmark::DoNotOptimize(drainageArea(routeFlow(s.heights, s.size, s.size, cell), cell));
    state.counters["cells"] = double(s.size) * s.size;
}

void BM_LandformStatistics(benchmark::State& state)
{
    const double cell = double(state.range(0));
    const Showcase& s = showcase(cell);
    for (auto _ : state) benchmark::DoNotOptimize(measureLandforms(s.heights, s.size, s.size, cell));
}

} // namespace

BENCHMARK(BM_GlobalPass)->Arg(8)->Arg(4)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();
BENCHMARK(BM_RouteFlow)->Arg(8)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_LandformStatistics)->Arg(8)->Arg(4)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
