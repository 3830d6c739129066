#include <strata/meshing/PlyIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include "FilePlace.h"
#include "OpenMeshConvert.h"

namespace strata::meshing {

namespace {

using detail::OmMesh;

} // namespace

void writePly(const TriangleMesh& mesh, const std::filesystem::path& path)
{
    OmMesh om;
    const bool hasNormals = detail::toOpenMesh(mesh, om);

    OpenMesh::IO::Options options = OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::LSB;
    if (hasNormals) options += OpenMesh::IO::Options::VertexNormal;
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        if (!OpenMesh::IO::write_mesh(om, temporary.string(), options)) {
            throw Error(ErrorKind::Io, "cannot write mesh file '" + path.string() + "'", detail::filePlace(path));
        }
    });
}

TriangleMesh readMeshFile(const std::filesystem::path& path)
{
    if (!std::filesystem::exists(path)) {
        throw Error("mesh file '" + path.string() + "' does not exist");
    }
    OmMesh om;
    om.request_vertex_normals();
    OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexNormal;
    if (!OpenMesh::IO::read_mesh(om, path.string(), options)) {
        throw Error("cannot read mesh file '" + path.string() + "'");
    }
    TriangleMesh mesh;
    mesh.positions.reserve(om.n_vertices());
    for (OmMesh::VertexHandle v : om.vertices()) {
        const OmMesh::Point& p = om.point(v);
        mesh.positions.emplace_back(p[0], p[1], p[2]);
        if (options.check(OpenMesh::IO::Options::VertexNormal)) {
            const OmMesh::Normal& n = om.normal(v);
            mesh.normals.emplace_back(n[0], n[1], n[2]);
        }
    }
    for (OmMesh::FaceHandle f : om.faces()) {
        std::vector<std::uint32_t> loop;
        for (OmMesh::VertexHandle v : om.fv_range(f)) loop.push_back(std::uint32_t(v.idx()));
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
            mesh.indices.insert(mesh.indices.end(), {loop[0], loop[i], loop[i + 1]});
        }
    }
    return mesh;
}

} // namespace strata::meshing
