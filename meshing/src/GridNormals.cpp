// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GridNormals.h>

#include <strata/Error.h>

#include <openvdb/tools/Interpolation.h>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace strata::meshing {

namespace {

// Below this squared length a gradient or a face-normal sum carries no
// direction worth trusting.
constexpr float MIN_LENGTH2 = 1e-20f;

const glm::vec3 FALLBACK_NORMAL{0.0f, 1.0f, 0.0f};

std::vector<glm::vec3> areaWeightedNormals(const TriangleMesh& mesh)
{
    // Unnormalised cross products are twice the triangle area times its normal.
    std::vector<glm::vec3> sums(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
        const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
        sums[a] += n;
        sums[b] += n;
        sums[c] += n;
    }
    return sums;
}

glm::vec3 unitOr(const glm::vec3& v, const glm::vec3& fallback)
{
    const float len2 = glm::dot(v, v);
    return (len2 > MIN_LENGTH2 && std::isfinite(len2)) ? v / std::sqrt(len2) : fallback;
}

// The normalised gradient `g` becomes vertex i's normal; a vanishing or
// non-finite gradient flags the vertex for fillDegenerateNormals().
void storeNormal(const glm::vec3& g, std::size_t i, TriangleMesh& mesh, std::vector<unsigned char>& degenerate)
{
    const float len2 = glm::dot(g, g);
    if (len2 > MIN_LENGTH2 && std::isfinite(len2)) {
        mesh.normals[i] = g / std::sqrt(len2);
    } else {
        degenerate[i] = 1;
    }
}

// Flagged vertices get the area-weighted face normal (or +Y), so every
// normal is finite and unit length.
void fillDegenerateNormals(TriangleMesh& mesh, const std::vector<unsigned char>& degenerate)
{
    if (std::find(degenerate.begin(), degenerate.end(), 1) == degenerate.end()) return;
    const std::vector<glm::vec3> faceSums = areaWeightedNormals(mesh);
    for (std::size_t i = 0; i < degenerate.size(); ++i) {
        if (degenerate[i]) mesh.normals[i] = unitOr(faceSums[i], FALLBACK_NORMAL);
    }
}

} // namespace

std::size_t orientNormalsToFaces(TriangleMesh& mesh)
{
    if (mesh.normals.size() != mesh.positions.size()) return 0;
    const std::vector<glm::vec3> faceSums = areaWeightedNormals(mesh);
    std::size_t replaced = 0;
    for (std::size_t i = 0; i < faceSums.size(); ++i) {
        const float len2 = glm::dot(faceSums[i], faceSums[i]);
        if (!(len2 > MIN_LENGTH2) || !std::isfinite(len2)) continue; // no faces, or they cancel out
        if (glm::dot(mesh.normals[i], faceSums[i]) < 0.0f) {
            mesh.normals[i] = faceSums[i] / std::sqrt(len2);
            ++replaced;
        }
    }
    return replaced;
}

void computeFaceNormals(TriangleMesh& mesh)
{
    std::vector<glm::vec3> sums = areaWeightedNormals(mesh);
    for (glm::vec3& n : sums) {
        n = unitOr(n, FALLBACK_NORMAL);
    }
    mesh.normals = std::move(sums);
}

void computeGridNormals(const openvdb::FloatGrid& grid, TriangleMesh& mesh)
{
    using Accessor = openvdb::FloatGrid::ConstAccessor;
    using Sampler = openvdb::tools::GridSampler<Accessor, openvdb::tools::BoxSampler>;

    const double h = grid.voxelSize()[0];
    const openvdb::Vec3d origin(mesh.origin.x, mesh.origin.y, mesh.origin.z);
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    std::vector<unsigned char> degenerate(mesh.positions.size(), 0);

    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
        Accessor accessor = grid.getConstAccessor();
        Sampler sampler(accessor, grid.transform());
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const glm::vec3& p = mesh.positions[i];
            const openvdb::Vec3d w = origin + openvdb::Vec3d(p.x, p.y, p.z);
            // Central differences on the trilinear interpolant, one voxel apart.
            const glm::vec3 g(
                sampler.wsSample(w + openvdb::Vec3d(h, 0, 0)) - sampler.wsSample(w - openvdb::Vec3d(h, 0, 0)),
                sampler.wsSample(w + openvdb::Vec3d(0, h, 0)) - sampler.wsSample(w - openvdb::Vec3d(0, h, 0)),
                sampler.wsSample(w + openvdb::Vec3d(0, 0, h)) - sampler.wsSample(w - openvdb::Vec3d(0, 0, h)));
            storeNormal(g, i, mesh, degenerate);
        }
    });

    fillDegenerateNormals(mesh, degenerate);
    orientNormalsToFaces(mesh);
}

const char* toString(NormalMethod method)
{
    switch (method) {
    case NormalMethod::Grid: return "grid";
    case NormalMethod::Gradient: return "gradient";
    case NormalMethod::Face: return "face";
    case NormalMethod::None: return "none";
    }
    return "?";
}

void computeGradientNormals(const GradientFunction& gradient, TriangleMesh& mesh)
{
    if (!gradient) throw Error(ErrorKind::BadInput, "meshing: gradient normals need a gradient function");
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    std::vector<unsigned char> degenerate(mesh.positions.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mesh.positions.size(), 4096),
                      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) {
            const glm::vec3 g(gradient(mesh.origin + glm::dvec3(mesh.positions[i])));
            storeNormal(g, i, mesh, degenerate);
        }
    });
    fillDegenerateNormals(mesh, degenerate);
    orientNormalsToFaces(mesh);
}

} // namespace strata::meshing
