// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata info FILE`: what a .vdb or a mesh file holds.

#include "Commands.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/MeshMetrics.h>

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cstdio>
#include <iostream>
#include <memory>

namespace strata::app {

namespace {

std::string format(const char* pattern, double a, double b = 0, double c = 0)
{
    char text[160];
    std::snprintf(text, sizeof(text), pattern, a, b, c);
    return text;
}

void describeVdb(const std::filesystem::path& path, std::ostream& out)
{
    const meshing::VdbFile file = meshing::readVdbFile(path);
    const openvdb::GridPtrVecPtr& grids = file.grids;
    const std::string& version = file.version;
    out << path.string() << ": OpenVDB file (version " << version << "), "
        << (grids ? grids->size() : 0) + file.unread.size() << " grid(s)\n";
    for (const meshing::UnreadGrid& grid : file.unread) {
        out << "  grid '" << grid.name << "': " << grid.type << ", not read (Strata reads float, double, integer and vector grids)\n";
    }
    if (!grids) return;
    for (const openvdb::GridBase::Ptr& grid : *grids) {
        out << "  grid '" << grid->getName() << "': " << grid->valueType() << ", class "
            << openvdb::GridBase::gridClassToString(grid->getGridClass()) << "\n";
        const openvdb::Vec3d voxel = grid->voxelSize();
        out << "    voxel size       " << format("%.6g x %.6g x %.6g m", voxel[0], voxel[1], voxel[2])
            << (grid->hasUniformVoxels() ? "" : " (not cubic)") << "\n";
        out << "    active voxels    " << grid->activeVoxelCount() << "\n";
        out << "    memory           " << format("%.1f MB", double(grid->memUsage()) / 1e6) << "\n";
        if (grid->activeVoxelCount() > 0) {
            const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
            const openvdb::Vec3d lo = grid->indexToWorld(box.min()), hi = grid->indexToWorld(box.max());
            out << "    index bounds     [" << box.min() << ", " << box.max() << "]\n";
            out << "    world bounds     " << format("[%.3f, %.3f, %.3f]", lo[0], lo[1], lo[2]) << " to "
                << format("[%.3f, %.3f, %.3f] m", hi[0], hi[1], hi[2]) << "\n";
        }
        if (const auto floats = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) {
            out << "    background       " << floats->background() << "\n";
            const openvdb::Index64 leaves = floats->tree().leafCount();
            out << "    leaf nodes       " << leaves << "\n";
        }
        std::string usable = "usable by `strata mesh`";
        if (!openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) usable = "not a float grid: `strata mesh` cannot use it";
        else if (grid->getGridClass() != openvdb::GRID_LEVEL_SET) usable = "not a level set: `strata mesh` cannot use it";
        else if (grid->activeVoxelCount() == 0) usable = "empty: `strata mesh` cannot use it";
        out << "    " << usable << "\n";
    }
}

void describeMesh(const std::filesystem::path& path, std::ostream& out)
{
    const meshing::TriangleMesh mesh = meshing::readMesh(path);
    const meshing::MeshTopology topology = meshing::analyzeTopology(mesh);
    const meshing::Bounds bounds = meshing::worldBounds(mesh);
    const meshing::AngleStatistics angles = meshing::angleStatistics(mesh);
    out << path.string() << ": triangle mesh\n";
    out << "  vertices           " << mesh.vertexCount() << (mesh.normals.empty() ? " (no normals)" : " (with normals)")
        << "\n";
    out << "  triangles          " << mesh.triangleCount() << "\n";
    out << "  origin             " << format("[%.3f, %.3f, %.3f] m", mesh.origin.x, mesh.origin.y, mesh.origin.z) << "\n";
    out << "  world bounds       " << format("[%.3f, %.3f, %.3f]", bounds.min.x, bounds.min.y, bounds.min.z) << " to "
        << format("[%.3f, %.3f, %.3f] m", bounds.max.x, bounds.max.y, bounds.max.z) << "\n";
    out << "  edges              " << topology.edges << ": " << topology.boundaryEdges << " boundary, "
        << topology.nonManifoldEdges << " non-manifold, " << topology.inconsistentEdges << " inconsistently wound\n";
    out << "  non-manifold verts " << topology.nonManifoldVertices << "\n";
    out << "  degenerate tris    " << topology.degenerateTriangles << "\n";
    out << "  watertight         " << (topology.watertight() ? "yes" : "no") << "\n";
    out << "  signed volume      " << format("%.6g m^3", meshing::signedVolume(mesh)) << "\n";
    out << "  smallest angle     " << format("%.2f deg (mean per triangle %.2f, %.2f%% under 10 deg)", angles.minDegrees,
                                             angles.meanMinDegrees, angles.below10Percent)
        << "\n";
}

} // namespace

Command registerInfoCommand(CLI::App& app)
{
    auto file = std::make_shared<std::string>();
    CLI::App* info = app.add_subcommand("info", "Print what a .vdb or a mesh file (.glb, .ply, .obj, .stl, .off) holds");
    info->add_option("file", *file, "The file to describe")->required();
    return {info, [file]() {
                const std::filesystem::path path(*file);
                if (!std::filesystem::exists(path)) throw Error(ErrorKind::BadInput, "'" + path.string() + "' does not exist");
                if (path.extension() == ".vdb") describeVdb(path, std::cout);
                else describeMesh(path, std::cout);
                return 0;
            }};
}

} // namespace strata::app
