// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: TriangleMesh to OpenMesh, shared by the OpenMesh file writers.

#include <strata/meshing/TriangleMesh.h>

// MeshIO must come before the kernel header (OpenMesh registers its readers
// and writers through it).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <glm/vec3.hpp>

namespace strata::meshing::detail {

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

/// Fills `om` with world positions (origin added, then rounded to float) and
/// the normals if present. Triangles OpenMesh cannot attach to its half-edge
/// structure (non-manifold configurations) get their own copies of their
/// vertices, so no face is lost. Returns whether normals were set.
inline bool toOpenMesh(const TriangleMesh& mesh, OmMesh& om)
{
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
    omerr().disable();
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        if (om.add_face(handles[a], handles[b], handles[c]).is_valid()) continue;
        om.add_face(addVertex(a), addVertex(b), addVertex(c));
    }
    omerr().enable();
    return hasNormals;
}

} // namespace strata::meshing::detail
