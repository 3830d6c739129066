// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata mesh`: a level set .vdb to a mesh file, with any of the three
// meshers, normals, projection and simplification.

#include "Commands.h"

#include <strata/Error.h>
#include <strata/meshing/DualContouring.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshFile.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/RemoveSmallComponents.h>
#include <strata/meshing/Simplify.h>
#include <strata/meshing/SurfaceNets.h>

#include <tbb/global_control.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

namespace strata::app {

namespace {

struct MeshArguments
{
    std::string input;
    std::string output;
    std::string mesher = "volume";
    std::optional<double> adaptivity;
    std::string normals = "grid";
    int project = 0;
    std::optional<double> simplifyRatio;
    std::string simplifier = "meshoptimizer";
    double maxErrorVoxels = 0.5;
    int chunk = 32;
    double minComponent = 0.0; ///< metres: closed pieces with a smaller bounding-box diagonal are dropped
    int threads = 0;
    bool quiet = false;
};

double secondsSince(std::chrono::steady_clock::time_point start)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string fixed(double value, int digits)
{
    char text[64];
    std::snprintf(text, sizeof(text), "%.*f", digits, value);
    return text;
}

int runMesh(const MeshArguments& args)
{
    const bool volume = args.mesher == "volume";
    if (args.adaptivity && !volume) {
        throw Error(ErrorKind::BadInput, "--adaptivity applies to --mesher volume only (got --mesher " + args.mesher + ")");
    }
    const std::map<std::string, meshing::NormalMethod> normalMethods = {
        {"grid", meshing::NormalMethod::Grid}, {"mesh", meshing::NormalMethod::Face}, {"none", meshing::NormalMethod::None}};
    const meshing::NormalMethod normals = normalMethods.at(args.normals);

    std::unique_ptr<tbb::global_control> threadLimit;
    if (args.threads > 0) {
        threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                            std::size_t(args.threads));
    }
    auto say = [&](const std::string& line) {
        if (!args.quiet) std::cout << line << std::endl;
    };

    // The output name is checked before any work, and its folder is made
    // only when the mesh is ready to be written: a bad run leaves nothing.
    const std::filesystem::path output(args.output);
    meshing::checkMeshFileExtension(output);
    std::error_code ec;
    if (std::filesystem::is_directory(output, ec)) {
        throw Error(ErrorKind::BadInput, "cannot write mesh file '" + args.output + "': it is a folder",
                    {.file = args.output});
    }

    auto start = std::chrono::steady_clock::now();
    const openvdb::FloatGrid::Ptr grid = meshing::readLevelSet(args.input);
    const double voxel = grid->voxelSize()[0];
    say("read     " + fixed(secondsSince(start), 3) + " s  " + args.input + ": " +
        std::to_string(grid->activeVoxelCount()) + " active voxels, voxel " + fixed(voxel, 4) + " m");

    // Positions relative to the middle of the grid (a whole voxel), placed by
    // the .glb node translation: float precision holds far from the origin.
    const openvdb::CoordBBox box = grid->evalActiveVoxelBoundingBox();
    const openvdb::Vec3d middle = grid->indexToWorld((box.min() + box.max()) >> 1);
    const glm::dvec3 origin(middle.x(), middle.y(), middle.z());

    start = std::chrono::steady_clock::now();
    meshing::TriangleMesh mesh;
    std::string what = args.mesher;
    if (volume) {
        meshing::GridToMeshOptions options;
        options.adaptivity = args.adaptivity.value_or(0.0);
        options.normals = normals;
        options.projectionSteps = args.project;
        options.origin = origin;
        mesh = meshing::gridToMesh(*grid, options);
        what += " (adaptivity " + fixed(options.adaptivity, 2) + ")";
    } else {
        meshing::DualContouringOptions options;
        options.chunkSize = args.chunk;
        options.normals = normals;
        options.projectionSteps = args.project;
        options.origin = origin;
        mesh = args.mesher == "surface-nets" ? meshing::surfaceNets(*grid, options) : meshing::dualContouring(*grid, options);
        what += args.chunk == 0 ? " (one chunk)" : " (chunks of " + std::to_string(args.chunk) + "^3)";
    }
    say("mesh     " + fixed(secondsSince(start), 3) + " s  " + what + ": " + std::to_string(mesh.triangleCount()) +
        " triangles, " + std::to_string(mesh.vertexCount()) + " vertices");

    if (args.simplifyRatio) {
        start = std::chrono::steady_clock::now();
        meshing::SimplifyOptions options;
        options.method = args.simplifier == "quadric" ? meshing::Simplifier::Quadric : meshing::Simplifier::MeshOptimizer;
        options.ratio = *args.simplifyRatio;
        options.maxError = args.maxErrorVoxels * voxel;
        options.lockBorder = true;
        const std::size_t before = mesh.triangleCount();
        mesh = meshing::simplify(mesh, options);
        if (normals == meshing::NormalMethod::Face) meshing::computeFaceNormals(mesh);
        say("simplify " + fixed(secondsSince(start), 3) + " s  " + args.simplifier + ": " + std::to_string(before) +
            " -> " + std::to_string(mesh.triangleCount()) + " triangles (max error " + fixed(args.maxErrorVoxels, 2) +
            " voxel, borders kept)");
    }

    if (args.minComponent > 0.0) {
        meshing::SmallComponentOptions options;
        options.minDiagonal = args.minComponent;
        const meshing::ComponentRemoval removed = meshing::removeSmallComponents(mesh, options);
        say("clean    " + std::to_string(removed.removedComponents) + " of " + std::to_string(removed.components) +
            " components removed (closed, under " + fixed(args.minComponent, 3) + " m across): " +
            std::to_string(removed.removedTriangles) + " triangles");
    }

    const meshing::MeshTopology topology = meshing::analyzeTopology(mesh);
    say("check    " + std::string(topology.watertight() ? "watertight" : "open") + ": " +
        std::to_string(topology.boundaryEdges) + " boundary edges, " + std::to_string(topology.nonManifoldEdges) +
        " non-manifold edges, " + std::to_string(topology.nonManifoldVertices) + " non-manifold vertices, " +
        std::to_string(topology.degenerateTriangles) + " degenerate triangles, " +
        std::to_string(topology.components) + " components, Euler characteristic " +
        std::to_string(topology.eulerCharacteristic()) + " (vertices welded by position)");

    start = std::chrono::steady_clock::now();
    if (output.has_parent_path()) {
        std::filesystem::create_directories(output.parent_path(), ec);
        if (ec || !std::filesystem::is_directory(output.parent_path())) {
            throw Error(ErrorKind::Io,
                        "cannot create output directory '" + output.parent_path().string() + "': " +
                            (ec ? ec.message() : "a file of that name is in the way"),
                        {.file = output.parent_path().string()});
        }
    }
    // The mesh is named after its source (the grid's name, else the input file's stem).
    meshing::MeshFileOptions fileOptions;
    fileOptions.name = grid->getName().empty() ? std::filesystem::path(args.input).stem().string() : grid->getName();
    meshing::writeMeshFile(mesh, args.output, fileOptions);
    say("write    " + fixed(secondsSince(start), 3) + " s  " + args.output);
    return 0;
}

} // namespace

Command registerMeshCommand(CLI::App& app)
{
    auto args = std::make_shared<MeshArguments>();
    CLI::App* mesh = app.add_subcommand("mesh", "Mesh a level set .vdb into a .glb, .ply, .obj, .stl or .off file");
    mesh->add_option("input", args->input, "Level set .vdb (a float grid of class level set)")->required();
    mesh->add_option("-o,--output", args->output, "Output mesh; the extension picks the format")->required();
    mesh->add_option("--mesher", args->mesher, "volume (OpenVDB volumeToMesh), surface-nets or dual-contouring")
        ->check(CLI::IsMember({"volume", "surface-nets", "dual-contouring"}));
    mesh->add_option("--adaptivity", args->adaptivity, "0..1, volume mesher only (default 0)")->check(CLI::Range(0.0, 1.0));
    mesh->add_option("--normals", args->normals, "grid (gradient of the grid), mesh (area-weighted faces) or none")
        ->check(CLI::IsMember({"grid", "mesh", "none"}));
    mesh->add_option("--project", args->project, "Newton steps moving vertices onto the surface (default 0)")
        ->check(CLI::Range(0, 16));
    mesh->add_option("--simplify", args->simplifyRatio, "Target triangle fraction in (0, 1]")
        ->check(CLI::Range(1e-6, 1.0));
    mesh->add_option("--simplifier", args->simplifier, "meshoptimizer (fast, default) or quadric (OpenMesh, accurate)")
        ->check(CLI::IsMember({"meshoptimizer", "quadric"}));
    mesh->add_option("--max-error", args->maxErrorVoxels, "Simplification error bound in voxels (default 0.5)")
        ->check(CLI::Range(0.0, 1000.0));
    mesh->add_option("--chunk", args->chunk, "Chunk size in cells for surface-nets and dual-contouring: "
                                             "a multiple of 8, or 0 for one chunk (default 32)")
        ->check(CLI::Range(0, 512));
    mesh->add_option("--min-component", args->minComponent,
                     "Drop closed pieces whose bounding box is under this many metres across (default 0: keep all)")
        ->check(CLI::Range(0.0, 1e9));
    mesh->add_option("--threads", args->threads, "Worker threads (0 = all cores); output is identical for any count")
        ->check(CLI::Range(0, 1024));
    mesh->add_flag("-q,--quiet", args->quiet, "Print nothing but errors");
    return {mesh, [args]() { return runMesh(*args); }};
}

} // namespace strata::app
