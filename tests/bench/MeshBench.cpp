// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Chunk mesher throughput on one core, next to volumeToMesh on the same grid
// (Google Benchmark; prints numbers, asserts nothing). Counters:
// triangles per second and nanoseconds per voxel (per cell of the 32^3
// chunks). Run: build/tests/bench/mesh_bench [--benchmark_filter=...]

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/SurfaceNets.h>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

using namespace strata::meshing;

namespace {

// A gyroid sheet clipped by a sphere, 1 m voxels: dense surface in every chunk.
const openvdb::FloatGrid& gyroidGrid()
{
    static const openvdb::FloatGrid::Ptr grid = levelSetFromShape(analyticGyroid(24.0, 4.0, 96.0), 1.0);
    return *grid;
}

void setCounters(benchmark::State& state, std::size_t triangles, std::size_t chunks)
{
    state.counters["triangles/s"] =
        benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["ns/voxel"] = benchmark::Counter(double(chunks) * 32 * 32 * 32,
                                                    benchmark::Counter::kIsIterationInvariantRate |
                                                        benchmark::Counter::kInvert);
    state.counters["triangles"] = double(triangles);
    state.counters["chunks"] = double(chunks);
}

template <bool DUAL>
void chunkMesher(benchmark::State& state)
{
    tbb::global_control oneCore(tbb::global_control::max_allowed_parallelism, 1);
    const openvdb::FloatGrid& grid = gyroidGrid();
    const std::vector<openvdb::Coord> chunks = listChunks(grid, 32);
    DualContouringOptions options;
    options.chunkSize = 32;
    options.normals = state.range(0) ? NormalMethod::Grid : NormalMethod::None;
    std::size_t triangles = 0;
    for (auto _ : state) {
        triangles = 0;
        for (const openvdb::Coord& c : chunks) {
            const ChunkMesh mesh = DUAL ? dualContouringChunk(grid, c, options) : surfaceNetsChunk(grid, c, options);
            triangles += mesh.mesh.triangleCount();
            benchmark::DoNotOptimize(mesh.mesh.indices.data());
        }
    }
    setCounters(state, triangles, chunks.size());
}

void volumeToMeshOneCore(benchmark::State& state)
{
    tbb::global_control oneCore(tbb::global_control::max_allowed_parallelism, 1);
    const openvdb::FloatGrid& grid = gyroidGrid();
    GridToMeshOptions options;
    options.computeNormals = state.range(0) != 0;
    std::size_t triangles = 0;
    for (auto _ : state) {
        const TriangleMesh mesh = gridToMesh(grid, options);
        triangles = mesh.triangleCount();
        benchmark::DoNotOptimize(mesh.indices.data());
    }
    setCounters(state, triangles, listChunks(grid, 32).size());
}

} // namespace

BENCHMARK(chunkMesher<false>)->Name("SurfaceNetsChunks/normals")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(chunkMesher<true>)->Name("DualContouringChunks/normals")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(volumeToMeshOneCore)->Name("VolumeToMesh/normals")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
