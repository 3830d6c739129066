// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `strata bench mesh`: the meshers (volumeToMesh at three adaptivities,
/// surface nets, dual contouring) measured on analytic shapes (accuracy,
/// normals, watertightness, time), and the chunk meshers' single-core
/// throughput next to volumeToMesh. MeshBenchReport.h formats the report.

#include <strata/meshing/SurfaceError.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace strata::bench {

struct MeshBenchOptions
{
    /// Two shapes at two resolutions and one throughput run (seconds);
    /// otherwise four shapes at 16, 32, 64 and 128 voxels across, best of 3.
    bool quick = false;
};

/// One shape at one resolution, meshed by one mesher with one normal method.
struct MeshBenchRow
{
    std::string shape;   ///< "*" marks a shape whose distance is first order only
    std::string mesher;  ///< "volume a=0.5", "surface-nets", ...
    std::string normals; ///< "grid", "exact" or "face"
    int across = 0;      ///< voxels across the 16 m cube
    double voxel = 0;    ///< metres
    std::size_t triangles = 0;
    double seconds = 0;  ///< meshing including normals, all cores
    meshing::SurfaceError error; ///< distances in voxels (positions measured once per mesher)
    bool watertight = false;
    std::size_t boundaryEdges = 0, nonManifoldEdges = 0;
};

/// Meshing every 32^3 chunk of a grid one after another on one thread
/// (volumeToMesh: the whole grid, charged the same cells).
struct MeshThroughput
{
    std::string what;
    std::size_t chunks = 0, triangles = 0;
    double seconds = 0; ///< processor time, best of the runs
    double cells = 0;   ///< voxels (cells) processed
};

struct MeshBenchResult
{
    std::vector<MeshBenchRow> rows;
    std::vector<MeshThroughput> throughput;
};

/// Runs the mesher benchmark; `shapeDone(shape, across)` (may be empty) is
/// called after each shape at each resolution.
MeshBenchResult runMeshBench(const MeshBenchOptions& options,
                             const std::function<void(const std::string& shape, int across)>& shapeDone = {});

} // namespace strata::bench
