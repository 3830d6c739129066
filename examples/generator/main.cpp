// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The smallest use of Strata as a library: a terrain with caves, sampled into
// an OpenVDB level set, meshed, and saved as binary glTF.
//
//   strata_generator_example OUT.glb

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/TerrainField.h>

#include <iostream>

int main(int argc, char** argv)
{
    if (argc != 2) {
        std::cerr << "usage: " << argv[0] << " OUT.glb\n";
        return 2;
    }
    try {
        strata::terrain::TerrainOptions terrainOptions;
        terrainOptions.seed = 42;
        const strata::terrain::TerrainField field(terrainOptions);

        strata::terrain::SampleOptions sampling;
        sampling.voxelSize = 1.0;
        sampling.region = {{-32.0, -32.0, -32.0}, {32.0, 32.0, 32.0}};
        const openvdb::FloatGrid::Ptr grid = strata::terrain::sampleLevelSet(field, sampling);

        const strata::meshing::TriangleMesh mesh = strata::meshing::gridToMesh(*grid);
        strata::meshing::writeGlb(mesh, argv[1]);

        std::cout << grid->activeVoxelCount() << " active voxels, " << mesh.triangleCount() << " triangles, "
                  << "signed volume " << strata::meshing::signedVolume(mesh) << " m^3 → " << argv[1] << "\n";
        return mesh.triangleCount() > 0 ? 0 : 1;
    } catch (const strata::Error& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
}
