// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/MeshBench.h>

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceNets.h>

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <utility>

namespace strata::bench {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Processor time of this process (seconds): on a busy machine, the fair
// measure of single-core work (the throughput runs use one thread).
double processSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct MesherConfig
{
    std::string name;      // "volume a=0.5", "surface-nets", "dual-contouring"
    std::string mesher;    // volume | surface-nets | dual-contouring
    double adaptivity = 0; // volume only
};

const std::vector<MesherConfig> MESHERS = {{"volume a=0", "volume", 0.0},
                                           {"volume a=0.5", "volume", 0.5},
                                           {"volume a=1", "volume", 1.0},
                                           {"surface-nets", "surface-nets", 0.0},
                                           {"dual-contouring", "dual-contouring", 0.0}};

const std::vector<std::pair<std::string, meshing::NormalMethod>> NORMAL_METHODS = {
    {"grid", meshing::NormalMethod::Grid}, {"exact", meshing::NormalMethod::Gradient}, {"face", meshing::NormalMethod::Face}};

// Meshes with the given normal method; the caller times it.
meshing::TriangleMesh runMesher(const MesherConfig& config, const openvdb::FloatGrid& grid,
                                meshing::NormalMethod normals, const meshing::GradientFunction& gradient)
{
    if (config.mesher == "volume") {
        meshing::GridToMeshOptions options;
        options.adaptivity = config.adaptivity;
        options.normals = normals;
        options.gradient = gradient;
        return meshing::gridToMesh(grid, options);
    }
    meshing::DualContouringOptions options;
    options.normals = normals;
    options.gradient = gradient;
    options.chunkSize = 32;
    return config.mesher == "surface-nets" ? meshing::surfaceNets(grid, options)
                                           : meshing::dualContouring(grid, options);
}

std::vector<meshing::AnalyticShape> benchShapes()
{
    return {meshing::analyticSphere({0.13, -0.21, 0.07}, 7.3),
            meshing::analyticTorus({0.11, 0.07, -0.13}, 5.0, 2.2),
            meshing::analyticBox({-6.13, -4.41, -5.77}, {5.94, 4.58, 6.06}),
            meshing::analyticGyroid(6.0, 1.2, 7.0)};
}

/// One shape at one voxel size, every mesher with every normal method.
void measureShape(const meshing::AnalyticShape& shape, int across, double voxel, std::vector<MeshBenchRow>& rows)
{
    const openvdb::FloatGrid::Ptr grid = meshing::levelSetFromShape(shape, voxel);
    meshing::SurfaceErrorOptions measure;
    measure.voxelSize = voxel;
    measure.gradient = shape.gradient;
    measure.surfacePoints =
        meshing::sampleSurface(shape.distance, shape.gradient, shape.min - voxel, shape.max + voxel, voxel);
    for (const MesherConfig& mesher : MESHERS) {
        meshing::SurfaceError distances;
        meshing::MeshTopology topology;
        for (std::size_t n = 0; n < NORMAL_METHODS.size(); ++n) {
            const auto start = Clock::now();
            const meshing::TriangleMesh mesh = runMesher(mesher, *grid, NORMAL_METHODS[n].second, shape.gradient);
            MeshBenchRow row;
            row.seconds = secondsSince(start);
            if (n == 0) { // positions do not depend on the normal method
                distances = meshing::measureSurfaceError(mesh, shape.distance, measure);
                topology = meshing::analyzeTopology(mesh);
            } else {
                meshing::SurfaceErrorOptions normalsOnly;
                normalsOnly.voxelSize = voxel;
                normalsOnly.gradient = shape.gradient;
                const meshing::SurfaceError e = meshing::measureSurfaceError(mesh, shape.distance, normalsOnly);
                distances.normalMeanDegrees = e.normalMeanDegrees;
                distances.normalOver5Percent = e.normalOver5Percent;
            }
            row.shape = shape.name + (shape.exact ? "" : "*");
            row.mesher = mesher.name;
            row.normals = NORMAL_METHODS[n].first;
            row.across = across;
            row.voxel = voxel;
            row.triangles = mesh.triangleCount();
            row.error = distances;
            row.watertight = topology.watertight();
            row.boundaryEdges = topology.boundaryEdges;
            row.nonManifoldEdges = topology.nonManifoldEdges;
            rows.push_back(row);
        }
    }
}

// Times meshing every 32^3 chunk of `grid` one after another on one thread.
MeshThroughput chunkThroughput(const std::string& what, const openvdb::FloatGrid& grid, bool dual,
                               meshing::NormalMethod normals, int repeats)
{
    MeshThroughput t;
    t.what = what;
    const std::vector<openvdb::Coord> chunks = meshing::listChunks(grid, 32);
    meshing::DualContouringOptions options;
    options.chunkSize = 32;
    options.normals = normals;
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
        std::size_t triangles = 0;
        const double start = processSeconds();
        for (const openvdb::Coord& c : chunks) {
            const meshing::ChunkMesh m =
                dual ? meshing::dualContouringChunk(grid, c, options) : meshing::surfaceNetsChunk(grid, c, options);
            triangles += m.mesh.triangleCount();
        }
        best = std::min(best, processSeconds() - start);
        t.triangles = triangles;
    }
    t.chunks = chunks.size();
    t.seconds = best;
    t.cells = double(chunks.size()) * 32.0 * 32.0 * 32.0;
    return t;
}

MeshThroughput volumeThroughput(const std::string& what, const openvdb::FloatGrid& grid, bool normals, int repeats,
                                std::size_t chunkCount)
{
    MeshThroughput t;
    t.what = what;
    meshing::GridToMeshOptions options;
    options.computeNormals = normals;
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
        const double start = processSeconds();
        t.triangles = meshing::gridToMesh(grid, options).triangleCount();
        best = std::min(best, processSeconds() - start);
    }
    t.seconds = best;
    t.chunks = chunkCount;
    t.cells = double(chunkCount) * 32.0 * 32.0 * 32.0; // same region as the chunk mesher
    return t;
}

// Single-core chunk throughput next to volumeToMesh on the same grids.
std::vector<MeshThroughput> measureThroughput(int repeats)
{
    std::vector<MeshThroughput> throughput;
    tbb::global_control oneCore(tbb::global_control::max_allowed_parallelism, 1);
    const std::pair<std::string, meshing::AnalyticShape> grids[] = {
        {"sphere r=60 voxels", meshing::analyticSphere({0.3, 0.2, 0.1}, 60.0)},
        {"gyroid 192^3 voxels", meshing::analyticGyroid(24.0, 4.0, 96.0)}};
    for (const auto& [label, shape] : grids) {
        const openvdb::FloatGrid::Ptr grid = meshing::levelSetFromShape(shape, 1.0);
        const std::size_t chunks = meshing::listChunks(*grid, 32).size();
        throughput.push_back(chunkThroughput("surface-nets, no normals: " + label, *grid, false,
                                             meshing::NormalMethod::None, repeats));
        throughput.push_back(chunkThroughput("surface-nets, grid normals: " + label, *grid, false,
                                             meshing::NormalMethod::Grid, repeats));
        throughput.push_back(chunkThroughput("dual-contouring, grid normals: " + label, *grid, true,
                                             meshing::NormalMethod::Grid, repeats));
        throughput.push_back(volumeThroughput("volumeToMesh, no normals: " + label, *grid, false, repeats, chunks));
        throughput.push_back(volumeThroughput("volumeToMesh, grid normals: " + label, *grid, true, repeats, chunks));
    }
    return throughput;
}

} // namespace

MeshBenchResult runMeshBench(const MeshBenchOptions& options,
                             const std::function<void(const std::string& shape, int across)>& shapeDone)
{
    const std::vector<int> acrossList = options.quick ? std::vector<int>{16, 32} : std::vector<int>{16, 32, 64, 128};
    const double extent = 16.0; // metres: every shape fits in [-8, 8]^3
    std::vector<meshing::AnalyticShape> shapes = benchShapes();
    if (options.quick) shapes.resize(2);

    MeshBenchResult result;
    for (const meshing::AnalyticShape& shape : shapes) {
        for (int across : acrossList) {
            measureShape(shape, across, extent / across, result.rows);
            if (shapeDone) shapeDone(shape.name, across);
        }
    }
    result.throughput = measureThroughput(options.quick ? 1 : 3);
    return result;
}

} // namespace strata::bench
