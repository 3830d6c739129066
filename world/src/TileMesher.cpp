// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/world/TileMesh.h>

#include "ClipToBox.h"
#include "SampleArray.h"
#include "Skirts.h"
#include "TileSurface.h"

#include <strata/Error.h>
#include <strata/meshing/DualMesh.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace strata::world {

namespace {

constexpr int MAX_CELLS = 1024;

std::array<int, 3> tileCells(const TileBox& box, int level)
{
    std::array<int, 3> cells{};
    for (int a = 0; a < 3; ++a) cells[a] = int(box.size[a] >> level);
    return cells;
}

void checkTile(const TileBox& box, const TileMeshOptions& options)
{
    if (!(options.voxelSize > 0.0) || !std::isfinite(options.voxelSize))
        throw Error(ErrorKind::BadInput, "tile voxel size must be a positive number, got " + std::to_string(options.voxelSize));
    if (options.level < 0 || options.level > 20)
        throw Error(ErrorKind::BadInput, "tile level must be in [0, 20], got " + std::to_string(options.level));
    const std::int64_t step = std::int64_t(1) << options.level;
    for (int a = 0; a < 3; ++a) {
        if (box.size[a] <= 0 || box.min[a] % step != 0 || box.size[a] % step != 0 || (box.size[a] >> options.level) > MAX_CELLS)
            throw Error(ErrorKind::BadInput, "tile box axis " + std::to_string(a) + " (min " + std::to_string(box.min[a]) +
                                                 ", size " + std::to_string(box.size[a]) + " voxels) is not a positive multiple of " +
                                                 std::to_string(step) + " voxels with at most " + std::to_string(MAX_CELLS) +
                                                 " cells at level " + std::to_string(options.level));
        if (box.min[a] - 4 * step < INT32_MIN || box.min[a] + box.size[a] + 4 * step > INT32_MAX)
            throw Error(ErrorKind::BadInput, "tile box axis " + std::to_string(a) + " lies beyond the 32-bit voxel lattice");
    }
}

} // namespace

std::size_t tileSampleBytes(const TileBox& box, int level)
{
    const std::array<int, 3> cells = tileCells(box, level);
    return detail::SampleArray::bytesFor({cells[0] + 4, cells[1] + 4, cells[2] + 4});
}

namespace detail {

ClipMesh meshSampledBox(const SampleArray& samples, const std::array<int, 3>& cells)
{
    const std::array<int, 3>& dims = samples.dims();
    meshing::DualSamples input;
    input.values = samples.data();
    input.cells = {cells[0] + 1, cells[1] + 1, cells[2] + 1};
    input.size = dims;
    input.stride = {1, dims[0], std::ptrdiff_t(dims[0]) * dims[1]};
    input.apron = 2;
    meshing::DualMeshSettings settings;
    settings.gradients = meshing::DualGradient::Cell;
    settings.quantum = TILE_QUANTUM;
    meshing::DualMeshResult result = meshing::dualMesh(input, settings);

    ClipMesh mesh;
    mesh.positions = std::move(result.positions);
    mesh.normals.reserve(result.gradients.size());
    for (const glm::dvec3& g : result.gradients) {
        const double len = glm::length(g);
        mesh.normals.push_back(len > 0.0 ? g / len : glm::dvec3(0.0, 1.0, 0.0));
    }
    mesh.indices = std::move(result.indices);
    const glm::dvec3 lo(0.0);
    const glm::dvec3 hi{double(cells[0]), double(cells[1]), double(cells[2])};
    clipToBox(mesh, lo, hi, TILE_QUANTUM);
    return mesh;
}

meshing::TriangleMesh toTriangleMesh(const ClipMesh& mesh, double cellMetres, const glm::dvec3& origin)
{
    meshing::TriangleMesh out;
    out.origin = origin;
    out.positions.reserve(mesh.positions.size());
    out.normals.reserve(mesh.normals.size());
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::dvec3 p = mesh.positions[i] * cellMetres;
        out.positions.emplace_back(float(p.x), float(p.y), float(p.z));
        out.normals.emplace_back(glm::vec3(mesh.normals[i]));
    }
    out.indices = mesh.indices;
    return out;
}

} // namespace detail

TileMeshData meshTile(const terrain::DensityField& field, const TileBox& box, const TileMeshOptions& options)
{
    checkTile(box, options);
    const std::int64_t step = std::int64_t(1) << options.level;
    const std::array<int, 3> cells = tileCells(box, options.level);
    const double cellMetres = double(step) * options.voxelSize;
    TileMeshData out;
    const glm::dvec3 origin = glm::dvec3(double(box.min[0]), double(box.min[1]), double(box.min[2])) * options.voxelSize;
    out.surface.origin = out.skirt.origin = origin;

    // Cells [−1, cells] per axis: one cell past each face, so the polygons
    // that cross a face are made here exactly as in the tile beyond it.
    const std::int64_t sampleOrigin[3] = {box.min[0] - 2 * step, box.min[1] - 2 * step, box.min[2] - 2 * step};
    const std::array<int, 3> dims{cells[0] + 4, cells[1] + 4, cells[2] + 4};
    detail::SampleArray samples;
    samples.init(&field, nullptr, options.voxelSize, sampleOrigin, step, dims, step);
    samples.fillAll();

    const detail::ClipMesh mesh = detail::meshSampledBox(samples, cells);
    const glm::dvec3 hi{double(cells[0]), double(cells[1]), double(cells[2])};
    // The samples' trilinear field, in cells from the box minimum (sample
    // index = cell + 2): the same field the level's surface was cut from.
    const float* values = samples.data();
    const auto density = [&](const glm::dvec3& c) {
        const glm::dvec3 s = glm::clamp(c + 2.0, glm::dvec3(0.0), glm::dvec3(dims[0] - 1, dims[1] - 1, dims[2] - 1));
        const int i = std::min(int(s.x), dims[0] - 2), j = std::min(int(s.y), dims[1] - 2), k = std::min(int(s.z), dims[2] - 2);
        const double fx = s.x - i, fy = s.y - j, fz = s.z - k;
        const auto at = [&](int di, int dj, int dk) {
            return double(values[(std::size_t(k + dk) * std::size_t(dims[1]) + std::size_t(j + dj)) * std::size_t(dims[0]) +
                                 std::size_t(i + di)]);
        };
        const double x00 = at(0, 0, 0) + fx * (at(1, 0, 0) - at(0, 0, 0)), x10 = at(0, 1, 0) + fx * (at(1, 1, 0) - at(0, 1, 0));
        const double x01 = at(0, 0, 1) + fx * (at(1, 0, 1) - at(0, 0, 1)), x11 = at(0, 1, 1) + fx * (at(1, 1, 1) - at(0, 1, 1));
        const double y0 = x00 + fy * (x10 - x00), y1 = x01 + fy * (x11 - x01);
        return y0 + fz * (y1 - y0);
    };
    const detail::ClipMesh skirt =
        detail::makeSkirts(mesh, glm::dvec3(0.0), hi, box.neighbourFaces, options.skirtDepth / cellMetres, density);

    out.surface = detail::toTriangleMesh(mesh, cellMetres, origin);
    out.skirt = detail::toTriangleMesh(skirt, cellMetres, origin);
    return out;
}

} // namespace strata::world
