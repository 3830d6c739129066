// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GridToMesh.h>

#include <strata/Error.h>
#include <strata/meshing/GridNormals.h>
#include <strata/meshing/ProjectToSurface.h>

#include <openvdb/tools/VolumeToMesh.h>

#include <cmath>
#include <string>

namespace strata::meshing {

namespace {

double distance2(const openvdb::Vec3s& a, const openvdb::Vec3s& b)
{
    return double((a - b).lengthSqr());
}

} // namespace

TriangleMesh gridToMesh(const openvdb::FloatGrid& grid, const GridToMeshOptions& options)
{
    if (!std::isfinite(options.isovalue)) {
        throw Error(ErrorKind::BadInput, "meshing: isovalue = " + std::to_string(options.isovalue) + " must be finite");
    }
    if (!(options.adaptivity >= 0.0 && options.adaptivity <= 1.0)) {
        throw Error(ErrorKind::BadInput, "meshing: adaptivity = " + std::to_string(options.adaptivity) + " must be in [0, 1]");
    }
    if (!std::isfinite(options.origin.x) || !std::isfinite(options.origin.y) || !std::isfinite(options.origin.z)) {
        throw Error(ErrorKind::BadInput, "meshing: origin must be finite");
    }
    if (options.computeNormals && options.normals == NormalMethod::Gradient && !options.gradient) {
        throw Error(ErrorKind::BadInput, "meshing: normals = gradient needs a gradient function");
    }

    std::vector<openvdb::Vec3s> points;
    std::vector<openvdb::Vec3I> triangles;
    std::vector<openvdb::Vec4I> quads;
    // volumeToMesh returns float points in the grid's world space: far from
    // the world origin (1e7 m) that rounds them to a metre. Mesh a shallow
    // copy (shared tree) whose transform is moved by −origin instead, so the
    // points come out relative to the origin, subtracted in double.
    openvdb::math::Transform::Ptr relative = grid.transform().copy();
    relative->postTranslate(openvdb::Vec3d(-options.origin.x, -options.origin.y, -options.origin.z));
    const openvdb::FloatGrid::ConstPtr local = grid.copyReplacingTransform(relative);
    openvdb::tools::volumeToMesh(*local, points, triangles, quads, options.isovalue, options.adaptivity);

    TriangleMesh mesh;
    mesh.origin = options.origin;
    mesh.positions.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        mesh.positions[i] = glm::vec3(points[i].x(), points[i].y(), points[i].z());
    }

    // volumeToMesh winds level-set polygons clockwise seen from outside:
    // every polygon is emitted reversed.
    mesh.indices.reserve(3 * triangles.size() + 6 * quads.size());
    for (const openvdb::Vec3I& t : triangles) {
        mesh.indices.insert(mesh.indices.end(), {t[2], t[1], t[0]});
    }
    for (const openvdb::Vec4I& q : quads) {
        const std::uint32_t a = q[3], b = q[2], c = q[1], d = q[0];
        // Split along the shorter diagonal: better-shaped triangles.
        if (distance2(points[a], points[c]) <= distance2(points[b], points[d])) {
            mesh.indices.insert(mesh.indices.end(), {a, b, c, a, c, d});
        } else {
            mesh.indices.insert(mesh.indices.end(), {b, c, d, b, d, a});
        }
    }

    if (options.projectionSteps > 0) {
        ProjectOptions project;
        project.steps = options.projectionSteps;
        project.isovalue = options.isovalue;
        projectToSurface(grid, mesh, project);
    }
    if (options.computeNormals) {
        switch (options.normals) {
        case NormalMethod::Grid: computeGridNormals(grid, mesh); break;
        case NormalMethod::Gradient: computeGradientNormals(options.gradient, mesh); break;
        case NormalMethod::Face: computeFaceNormals(mesh); break;
        case NormalMethod::None: break;
        }
    }
    return mesh;
}

} // namespace strata::meshing
