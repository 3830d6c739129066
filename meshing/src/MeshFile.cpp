#include <strata/meshing/MeshFile.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/PlyIO.h>

#include "FilePlace.h"
#include "OpenMeshConvert.h"

#include <algorithm>
#include <cctype>
#include <limits>

namespace strata::meshing {

namespace {

std::string lowerExtension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

} // namespace

std::string meshFileExtensions()
{
    return ".glb, .ply, .obj, .stl, .off";
}

void writeMeshFile(const TriangleMesh& mesh, const std::filesystem::path& path, const MeshFileOptions& fileOptions)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".glb") {
        GlbOptions glb;
        glb.name = fileOptions.name;
        return writeGlb(mesh, path, glb);
    }
    if (ext == ".ply") return writePly(mesh, path);
    if (ext != ".obj" && ext != ".stl" && ext != ".off") {
        throw Error(ErrorKind::BadInput,
                    "cannot write mesh file '" + path.string() + "': unknown extension '" + ext + "' (use " +
                        meshFileExtensions() + ")",
                    detail::filePlace(path));
    }
    detail::OmMesh om;
    const bool hasNormals = detail::toOpenMesh(mesh, om);
    OpenMesh::IO::Options options;
    if (ext == ".stl") {
        options += OpenMesh::IO::Options::Binary;
    } else if (hasNormals) {
        options += OpenMesh::IO::Options::VertexNormal;
    }
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        // OpenMesh picks the writer from the extension: give it a lower-case one.
        std::filesystem::path lower = temporary;
        lower.replace_extension(ext == temporary.extension().string() ? ext : ext + ".tmp" + ext);
        omlog().disable();
        // max_digits10 significant digits: every float reads back bit-identical
        // (OpenMesh's default of 6 merges nearby vertices into zero-area triangles).
        const bool ok = OpenMesh::IO::write_mesh(om, lower.string(), options, std::numeric_limits<float>::max_digits10);
        omlog().enable();
        std::error_code ec;
        if (ok && lower != temporary) std::filesystem::rename(lower, temporary, ec);
        if (!ok || ec) {
            std::filesystem::remove(lower, ec);
            throw Error(ErrorKind::Io, "cannot write mesh file '" + path.string() + "'", detail::filePlace(path));
        }
    });
}

TriangleMesh readMesh(const std::filesystem::path& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".glb" || ext == ".gltf") {
        if (!std::filesystem::exists(path)) throw Error("mesh file '" + path.string() + "' does not exist");
        return readGltf(path);
    }
    return readMeshFile(path);
}

} // namespace strata::meshing
