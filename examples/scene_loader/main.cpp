// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Loads a scene file (or the embedded default scene) through strata::scene,
// samples and meshes a column of 32³ chunks of it as a voxel game would, then runs
// the whole terrain through the same stages as `strata generate` and writes
// OUT_DIR/terrain.vdb and OUT_DIR/terrain.glb: the same bytes the CLI writes.
//
//   strata_scene_loader [SCENE.toml] OUT_DIR

#include <strata/Error.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/SurfaceNets.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include <strata/terrain/SampleLevelSet.h>

#include <filesystem>
#include <iostream>

int main(int argc, char** argv)
{
    if (argc < 2 || argc > 3) {
        std::cerr << "usage: strata_scene_loader [SCENE.toml] OUT_DIR\n";
        return 2;
    }
    try {
        using namespace strata;
        const scene::Scene sceneFile = argc == 3 ? scene::loadScene(argv[1]) : scene::defaultScene();
        const std::filesystem::path out = argv[argc - 1];

        // One column of chunks: the scene's own density field over a 16 m
        // square at the origin, the region's full height, at the scene's
        // voxel size, meshed by surface nets in 32³ chunks.
        terrain::SampleOptions chunk;
        chunk.voxelSize = sceneFile.voxelSize;
        chunk.halfWidth = sceneFile.halfWidth;
        chunk.region.min = glm::dvec3(-8.0, sceneFile.region.min.y, -8.0);
        chunk.region.max = glm::dvec3(8.0, sceneFile.region.max.y, 8.0);
        const openvdb::FloatGrid::Ptr grid = terrain::sampleLevelSet(*sceneFile.field, chunk);
        meshing::DualContouringOptions meshOptions;
        meshOptions.chunkSize = 32;
        const meshing::TriangleMesh chunkMesh = meshing::surfaceNets(*grid, meshOptions);
        std::cout << "a column of chunks at the origin: " << grid->activeVoxelCount() << " active voxels, "
                  << chunkMesh.triangleCount() << " triangles\n";

        // The whole terrain, stage by stage, as `strata generate` runs it.
        const scene::QualitySettings quality = scene::resolveQuality(sceneFile, std::nullopt, {});
        const scene::Scene effective = scene::applyQuality(sceneFile, quality);
        const scene::SampledTerrain terrain = scene::sampleTerrain(effective);
        const meshing::TriangleMesh mesh = scene::meshTerrain(effective, quality, terrain);
        std::filesystem::create_directories(out);
        scene::writeTerrain(terrain, mesh, out);
        std::cout << sceneFile.source << ": " << terrain.grid->activeVoxelCount() << " active voxels, "
                  << mesh.triangleCount() << " triangles, written to " << out.string() << "\n";
        return 0;
    } catch (const strata::Error& e) {
        std::cerr << "strata_scene_loader: error: " << e.what() << "\n";
        return e.kind() == strata::ErrorKind::BadInput ? 2 : 1;
    }
}
