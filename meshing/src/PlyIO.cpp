#include <strata/meshing/PlyIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

// MeshIO must come before the kernel header (OpenMesh registers its readers
// and writers through it).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

namespace strata::meshing {

namespace {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

} // namespace

void writePly(const TriangleMesh& mesh, const std::filesystem::path& path)
{
    OmMesh om;
    om.request_vertex_normals();
    const bool hasNormals = mesh.normals.size() == mesh.positions.size();
    std::vector<OmMesh::VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    auto addVertex = [&](std::uint32_t i) {
        const glm::dvec3 p = mesh.origin + glm::dvec3(mesh.positions[i]);
        OmMesh::VertexHandle v = om.add_vertex(OmMesh::Point(float(p.x), float(p.y), float(p.z)));
        if (hasNormals) om.set_normal(v, OmMesh::Normal(mesh.normals[i].x, mesh.normals[i].y, mesh.normals[i].z));
        return v;
    };
    for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) handles.push_back(addVertex(i));

    // OpenMesh's half-edge structure refuses faces that would make an edge or
    // vertex non-manifold (it prints a warning): give those their own vertices.
    omerr().disable();
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if (om.add_face(handles[a], handles[b], handles[c]).is_valid()) continue;
        om.add_face(addVertex(a), addVertex(b), addVertex(c));
    }
    omerr().enable();

    OpenMesh::IO::Options options = OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::LSB;
    if (hasNormals) options += OpenMesh::IO::Options::VertexNormal;
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        if (!OpenMesh::IO::write_mesh(om, temporary.string(), options)) {
            throw Error("cannot write mesh file '" + path.string() + "'");
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
