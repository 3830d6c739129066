// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/Simplify.h>

#include <strata/Error.h>
#include <strata/IntegerMath.h>

// MeshIO before the kernel header: OpenMesh registers its readers and writers
// only when IO is included first.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <meshoptimizer.h>

#include <cmath>
#include <string>

namespace strata::meshing {

namespace {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

// Keeps the vertices `indices` uses, in their original order.
TriangleMesh compact(const TriangleMesh& mesh, std::vector<std::uint32_t> indices)
{
    std::vector<std::uint32_t> remap(mesh.positions.size(), 0xffffffffu);
    for (std::uint32_t i : indices) remap[i] = 0;
    TriangleMesh out;
    out.origin = mesh.origin;
    const bool normals = mesh.normals.size() == mesh.positions.size();
    for (std::uint32_t v = 0; v < mesh.positions.size(); ++v) {
        if (remap[v] == 0xffffffffu) continue;
        remap[v] = std::uint32_t(out.positions.size());
        out.positions.push_back(mesh.positions[v]);
        if (normals) out.normals.push_back(mesh.normals[v]);
    }
    for (std::uint32_t& i : indices) i = remap[i];
    out.indices = std::move(indices);
    return out;
}

std::vector<std::uint32_t> simplifyMeshOptimizer(const TriangleMesh& mesh, const SimplifyOptions& options,
                                                 std::size_t target)
{
    const float scale = meshopt_simplifyScale(&mesh.positions[0].x, mesh.positions.size(), sizeof(glm::vec3));
    const float relative = scale > 0.0f ? float(options.maxError / scale) : 0.0f;
    std::vector<std::uint32_t> out(mesh.indices.size());
    const std::size_t count = meshopt_simplify(out.data(), mesh.indices.data(), mesh.indices.size(),
                                               &mesh.positions[0].x, mesh.positions.size(), sizeof(glm::vec3),
                                               target * 3, relative,
                                               options.lockBorder ? meshopt_SimplifyLockBorder : 0, nullptr);
    out.resize(count);
    return out;
}

std::vector<std::uint32_t> simplifyQuadric(const TriangleMesh& mesh, const SimplifyOptions& options, std::size_t target)
{
    OmMesh om;
    om.request_vertex_status();
    om.request_edge_status();
    om.request_face_status();
    std::vector<OmMesh::VertexHandle> handles;
    handles.reserve(mesh.positions.size());
    for (const glm::vec3& p : mesh.positions) handles.push_back(om.add_vertex(OmMesh::Point(p.x, p.y, p.z)));
    // Faces OpenMesh cannot attach (non-manifold) are kept as they are.
    std::vector<std::uint32_t> rejected;
    omerr().disable();
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if (!om.add_face(handles[a], handles[b], handles[c]).is_valid()) rejected.insert(rejected.end(), {a, b, c});
    }
    omerr().enable();
    for (std::uint32_t i : rejected) om.status(handles[i]).set_locked(true);
    if (options.lockBorder) {
        for (OmMesh::VertexHandle v : om.vertices()) {
            if (om.is_boundary(v)) om.status(v).set_locked(true);
        }
    }

    OpenMesh::Decimater::DecimaterT<OmMesh> decimater(om);
    OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
    decimater.add(quadric);
    decimater.module(quadric).set_max_err(options.maxError * options.maxError, /*binary*/ true);
    decimater.initialize();
    const std::size_t keep = rejected.size() / 3;
    decimater.decimate_to_faces(0, target > keep ? target - keep : 0);
    // No garbage collection: vertex handles stay our indices, and the face
    // range skips the deleted faces.
    std::vector<std::uint32_t> out;
    out.reserve(om.n_faces() * 3 + rejected.size());
    for (OmMesh::FaceHandle f : om.faces()) {
        if (om.status(f).deleted()) continue;
        for (OmMesh::VertexHandle v : om.fv_range(f)) out.push_back(std::uint32_t(v.idx()));
    }
    out.insert(out.end(), rejected.begin(), rejected.end());
    return out;
}

} // namespace

const char* toString(Simplifier method)
{
    return method == Simplifier::MeshOptimizer ? "meshoptimizer" : "quadric";
}

TriangleMesh simplify(const TriangleMesh& mesh, const SimplifyOptions& options)
{
    if (!(options.ratio > 0.0 && options.ratio <= 1.0)) {
        throw Error(ErrorKind::BadInput, "simplify: ratio " + std::to_string(options.ratio) + " must be in (0, 1]");
    }
    if (!(options.maxError >= 0.0) || !std::isfinite(options.maxError)) {
        throw Error(ErrorKind::BadInput, "simplify: maximum error must be finite and non-negative");
    }
    if (mesh.indices.empty() || options.ratio == 1.0) return compact(mesh, mesh.indices);
    const std::size_t target = roundToInt<std::size_t>(options.ratio * double(mesh.triangleCount()));
    if (options.method == Simplifier::MeshOptimizer) {
        return compact(mesh, simplifyMeshOptimizer(mesh, options, target));
    }
    return compact(mesh, simplifyQuadric(mesh, options, target));
}

} // namespace strata::meshing
