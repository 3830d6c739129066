// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/bench/MeshBenchReport.h>

#include <strata/bench/ReportText.h>

#include <algorithm>
#include <sstream>
#include <thread>

namespace strata::bench {

namespace {

std::string closed(const MeshBenchRow& r)
{
    if (r.watertight) return "yes";
    return "no (" + std::to_string(r.boundaryEdges) + " boundary, " + std::to_string(r.nonManifoldEdges) +
           " non-manifold edges)";
}

/// M triangles/s, ns per voxel, ms per chunk.
struct Rates
{
    double mtris, ns, perChunk;
};

Rates rates(const MeshThroughput& t)
{
    return {double(t.triangles) / t.seconds / 1e6, t.seconds * 1e9 / t.cells,
            1000.0 * t.seconds / double(std::max<std::size_t>(t.chunks, 1))};
}

} // namespace

std::string formatMeshBenchMarkdown(const MeshBenchResult& result)
{
    std::ostringstream md;
    md << "# Mesher benchmark\n\n"
       << "Shapes fit in a 16 m cube; `across` is 16 m over the voxel size. Distances in voxels: mean and RMS "
          "over mesh samples (vertices and triangle centroids, |exact distance|) and surface samples (points on "
          "the analytic surface one voxel apart, distance to the nearest triangle); Hausdorff is the larger "
          "maximum of the two directions. Normal error: angle between vertex normals and the exact gradient. "
          "Time: meshing including normals, all cores (" << std::thread::hardware_concurrency() << "). "
       << "Chunk meshers use 32^3 chunks. `*` marks the gyroid, whose distance is first order only.\n\n"
       << "| shape | across | mesher | normals | triangles | time (ms) | mean | RMS | Hausdorff | normal mean (deg) "
          "| normals > 5 deg (%) | watertight |\n"
       << "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const MeshBenchRow& r : result.rows) {
        md << "| " << r.shape << " | " << r.across << " | " << r.mesher << " | " << r.normals << " | " << r.triangles
           << " | " << fixedDigits(1000 * r.seconds, 1) << " | " << fixedDigits(r.error.mean, 4) << " | "
           << fixedDigits(r.error.rms, 4) << " | " << fixedDigits(r.error.hausdorff, 3) << " | "
           << fixedDigits(r.error.normalMeanDegrees, 2) << " | " << fixedDigits(r.error.normalOver5Percent, 2)
           << " | " << closed(r) << " |\n";
    }
    md << "\n## Chunk mesher throughput, one core\n\n"
       << "Every 32^3 chunk of the grid meshed one after another on one thread (block fill from the VDB tree, "
          "vertices, triangles, normals), processor time, best of the runs; volumeToMesh meshes the whole grid on one thread and is charged "
          "the same cells. Anchor: about 20 M triangles/s for a surface nets mesher on one core of a 2.5 GHz laptop.\n\n"
       << "| what | chunks | triangles | time (ms) | M triangles/s | ns per voxel | ms per chunk |\n"
       << "|---|---:|---:|---:|---:|---:|---:|\n";
    for (const MeshThroughput& t : result.throughput) {
        const Rates r = rates(t);
        md << "| " << t.what << " | " << t.chunks << " | " << t.triangles << " | " << fixedDigits(1000 * t.seconds, 1)
           << " | " << fixedDigits(r.mtris, 2) << " | " << fixedDigits(r.ns, 2) << " | " << fixedDigits(r.perChunk, 3)
           << " |\n";
    }
    return md.str();
}

std::string formatMeshBenchCsv(const MeshBenchResult& result)
{
    std::ostringstream csv;
    csv << "shape,voxels_across,voxel_size,mesher,normals,triangles,time_ms,mean_voxels,rms_voxels,hausdorff_voxels,"
           "normal_mean_deg,normal_over5_percent,watertight,boundary_edges,non_manifold_edges\n";
    for (const MeshBenchRow& r : result.rows) {
        csv << r.shape << "," << r.across << "," << r.voxel << "," << r.mesher << "," << r.normals << "," << r.triangles
            << "," << fixedDigits(1000 * r.seconds, 3) << "," << fixedDigits(r.error.mean, 5) << ","
            << fixedDigits(r.error.rms, 5) << "," << fixedDigits(r.error.hausdorff, 4) << ","
            << fixedDigits(r.error.normalMeanDegrees, 3) << "," << fixedDigits(r.error.normalOver5Percent, 3) << ","
            << (r.watertight ? "yes" : "no") << "," << r.boundaryEdges << "," << r.nonManifoldEdges << "\n";
    }
    csv << "\nthroughput,chunks,triangles,time_ms,mtri_per_s,ns_per_voxel,ms_per_chunk\n";
    for (const MeshThroughput& t : result.throughput) {
        const Rates r = rates(t);
        csv << "\"" << t.what << "\"," << t.chunks << "," << t.triangles << "," << fixedDigits(1000 * t.seconds, 3)
            << "," << fixedDigits(r.mtris, 3) << "," << fixedDigits(r.ns, 3) << "," << fixedDigits(r.perChunk, 4)
            << "\n";
    }
    return csv.str();
}

} // namespace strata::bench
