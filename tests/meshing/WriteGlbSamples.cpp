// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Writes the .glb files the Khronos validator checks (RunGltfValidator.cmake):
// each mesher, chunked and whole, far from the origin, a lone chunk, a
// simplified mesh, one with the terrain attributes and an empty one.
// Usage: write_glb_samples DIR

#include <strata/meshing/AnalyticShapes.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/Simplify.h>
#include <strata/meshing/SurfaceNets.h>

#include <cmath>
#include <exception>
#include <filesystem>
#include <iostream>

using namespace strata::meshing;

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: write_glb_samples DIR\n";
        return 2;
    }
    try {
        const std::filesystem::path dir(argv[1]);
        std::filesystem::create_directories(dir);

        const auto torus = analyticTorus({0.1, 0.2, -0.3}, 5.5, 2.5);
        const auto torusGrid = levelSetFromShape(torus, 0.25);
        ChunkMeshOptions chunked;
        chunked.chunkSize = 16;
        const TriangleMesh nets = surfaceNets(*torusGrid, chunked);
        if (!analyzeTopology(nets).watertight()) throw std::runtime_error("chunked torus is not watertight");
        writeGlb(nets, dir / "torus-surface-nets-chunked.glb");

        const auto box = analyticBox({-3.13, -2.41, -2.77}, {2.94, 2.58, 3.06});
        DualContouringOptions dual;
        dual.chunkSize = 0;
        dual.gradient = box.gradient;
        dual.normals = NormalMethod::Gradient;
        writeGlb(dualContouring(*levelSetFromShape(box, 0.25), dual), dir / "box-dual-contouring.glb");

        GridToMeshOptions volume;
        volume.adaptivity = 0.25;
        volume.origin = {1.0e5, 0.0, -1.0e5};
        writeGlb(gridToMesh(*levelSetFromShape(analyticSphere({1.0e5, 0.0, -1.0e5}, 4.0), 0.25), volume),
                 dir / "sphere-volume-far.glb");

        ChunkMesh fullest;
        for (const openvdb::Coord& c : listChunks(*torusGrid, 16)) {
            ChunkMesh chunk = surfaceNetsChunk(*torusGrid, c, chunked);
            if (chunk.mesh.triangleCount() > fullest.mesh.triangleCount()) fullest = std::move(chunk);
        }
        writeGlb(fullest.mesh, dir / "torus-one-chunk.glb"); // open at the chunk borders

        SimplifyOptions simple;
        simple.ratio = 0.2;
        simple.maxError = 0.05;
        writeGlb(simplify(nets, simple), dir / "torus-simplified.glb");

        // Terrain attributes: _SURFACE (VEC2) and _LANDFORM (VEC4) beside the normals.
        TriangleMesh attributed = nets;
        for (const glm::vec3& p : attributed.positions) {
            attributed.surface.emplace_back(0.5f + 0.5f * p.y / 8.0f, p.y > 0.0f ? 1.0f : 0.0f);
            attributed.landform.emplace_back(std::abs(p.x), std::abs(p.z), 0.0f, p.y < 0.0f ? 1.0f : 0.0f);
        }
        writeGlb(attributed, dir / "torus-terrain-attributes.glb");

        writeGlb(TriangleMesh{}, dir / "empty.glb");
    } catch (const std::exception& e) {
        std::cerr << "write_glb_samples: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
