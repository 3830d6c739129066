// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/world/TerrainTile.h>

#include "SampleArray.h"
#include "TileSurface.h"

#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace strata::world {

namespace {

constexpr std::int64_t MAX_ACROSS = 1024; // x and z, as meshTile()
constexpr std::int64_t MAX_UP = 4096;     // y: one column, TILE_QUANTUM keeps it exact in float

void checkBox(const TileBox& box, const TerrainTileOptions& options)
{
    if (!(options.voxelSize > 0.0) || !std::isfinite(options.voxelSize))
        throw Error(ErrorKind::BadInput,
                    "terrain tile voxel size must be a positive number, got " + std::to_string(options.voxelSize));
    for (int a = 0; a < 3; ++a) {
        const std::int64_t limit = a == 1 ? MAX_UP : MAX_ACROSS;
        if (box.size[a] <= 0 || box.size[a] > limit)
            throw Error(ErrorKind::BadInput, "terrain tile axis " + std::to_string(a) + " holds " +
                                                 std::to_string(box.size[a]) + " voxels; it must hold 1 to " +
                                                 std::to_string(limit));
        if (box.min[a] - 4 < INT32_MIN || box.min[a] + box.size[a] + 4 > INT32_MAX)
            throw Error(ErrorKind::BadInput,
                        "terrain tile axis " + std::to_string(a) + " lies beyond the 32-bit voxel lattice");
    }
}

/// The lattice values, x fastest, with the two-point apron of the samples.
struct Lattice
{
    const float* values = nullptr;
    std::array<int, 3> dims{};
    float at(int i, int j, int k) const
    {
        return values[(std::size_t(k + 2) * dims[1] + std::size_t(j + 2)) * dims[0] + std::size_t(i + 2)];
    }
};

} // namespace

std::size_t terrainTileBytes(const TileBox& box)
{
    return detail::SampleArray::bytesFor({int(box.size[0]) + 4, int(box.size[1]) + 4, int(box.size[2]) + 4});
}

TerrainTile extractTerrainTile(const terrain::DensityField& field, const TileBox& box, const TerrainTileOptions& options)
{
    checkBox(box, options);
    const double v = options.voxelSize;
    const std::array<int, 3> cells{int(box.size[0]), int(box.size[1]), int(box.size[2])};
    const std::int64_t sampleOrigin[3] = {box.min[0] - 2, box.min[1] - 2, box.min[2] - 2};
    detail::SampleArray samples;
    // Step 1 and margin 1, as meshTile() at level 0: the same floats.
    samples.init(&field, nullptr, v, sampleOrigin, 1, {cells[0] + 4, cells[1] + 4, cells[2] + 4}, 1);
    samples.fillAll();
    const Lattice lattice{samples.data(), samples.dims()};

    TerrainTile tile;
    tile.voxelSize = v;
    tile.box = box;
    tile.columns = cells[0] + 1;
    tile.rows = cells[2] + 1;
    const std::size_t columnCount = std::size_t(tile.columns) * tile.rows;
    tile.heights.resize(columnCount);
    // Per column: the lattice index of its top rock point (−1: none), and
    // of the highest air point below it (−1: none).
    std::vector<int> topIndex(columnCount, -1), airBelow(columnCount, -1);
    const int top = cells[1];
    for (int k = 0; k < tile.rows; ++k)
        for (int i = 0; i < tile.columns; ++i) {
            const std::size_t c = std::size_t(k) * tile.columns + i;
            int j = top;
            while (j >= 0 && lattice.at(i, j, k) > 0.0f) --j;
            topIndex[c] = j;
            if (j < 0) {
                tile.heights[c] = double(box.min[1]) * v;
                ++tile.columnsAtBottom;
                continue;
            }
            if (j == top) {
                tile.heights[c] = double(box.min[1] + top) * v;
                ++tile.columnsAtTop;
            } else {
                // Rock a <= 0 at j, air b > 0 at j + 1: the zero of the
                // linear interpolant, as the mesher's edge crossing.
                const double a = lattice.at(i, j, k), b = lattice.at(i, j + 1, k);
                tile.heights[c] = (double(box.min[1] + j) + a / (a - b)) * v;
            }
            int air = j - 1;
            while (air >= 0 && lattice.at(i, air, k) <= 0.0f) --air;
            airBelow[c] = air;
        }

    tile.holes.assign(std::size_t(cells[0]) * cells[2], 0);
    for (int k = 0; k < cells[2]; ++k)
        for (int i = 0; i < cells[0]; ++i) {
            const std::size_t corners[4] = {std::size_t(k) * tile.columns + i, std::size_t(k) * tile.columns + i + 1,
                                            std::size_t(k + 1) * tile.columns + i,
                                            std::size_t(k + 1) * tile.columns + i + 1};
            double lowest = HUGE_VAL;
            bool hole = false;
            for (std::size_t c : corners) {
                lowest = std::min(lowest, tile.heights[c]);
                hole = hole || topIndex[c] < 0;
            }
            // The lowest lattice index at or above lowest − HOLE_DEPTH voxels.
            const int floorIndex = ceilToInt<int>(lowest / v - double(box.min[1])) - HOLE_DEPTH;
            for (std::size_t c : corners) hole = hole || (airBelow[c] >= 0 && airBelow[c] >= floorIndex);
            tile.holes[std::size_t(k) * cells[0] + i] = hole ? 1 : 0;
        }

    const glm::dvec3 origin = glm::dvec3(double(box.min[0]), double(box.min[1]), double(box.min[2])) * v;
    tile.surface = detail::toTriangleMesh(detail::meshSampledBox(samples, cells), v, origin);
    return tile;
}

double latticeHeight(const TerrainTile& tile, double fx, double fz)
{
    fx = std::clamp(fx, 0.0, double(tile.columns - 1));
    fz = std::clamp(fz, 0.0, double(tile.rows - 1));
    const int i = std::min(int(fx), tile.columns - 2), k = std::min(int(fz), tile.rows - 2);
    const double tx = fx - i, tz = fz - k;
    // No fraction: the column itself, bit for bit (no 0 · h terms).
    const auto along = [&](int row) {
        return tx == 0.0 ? tile.height(i, row) : tx == 1.0 ? tile.height(i + 1, row)
                                                          : (1.0 - tx) * tile.height(i, row) + tx * tile.height(i + 1, row);
    };
    return tz == 0.0 ? along(k) : tz == 1.0 ? along(k + 1) : (1.0 - tz) * along(k) + tz * along(k + 1);
}

double heightAt(const TerrainTile& tile, double x, double z)
{
    return latticeHeight(tile, x / tile.voxelSize, z / tile.voxelSize);
}

HeightfieldHoles engineHoles(const TerrainTile& tile, int cellsX, int cellsZ, double cellSize)
{
    HeightfieldHoles out;
    out.cellsX = cellsX;
    out.cellsZ = cellsZ;
    out.cellSize = cellSize;
    out.cells.assign(std::size_t(std::max(cellsX, 0)) * std::max(cellsZ, 0), 0);
    const double ratio = cellSize / tile.voxelSize; // lattice cells per engine cell
    const int latticeX = tile.columns - 1, latticeZ = tile.rows - 1;
    for (int z = 0; z < cellsZ; ++z) {
        const int z0 = std::clamp(floorToInt<int>(z * ratio + 1e-9), 0, latticeZ - 1);
        const int z1 = std::clamp(ceilToInt<int>((z + 1) * ratio - 1e-9) - 1, z0, latticeZ - 1);
        for (int x = 0; x < cellsX; ++x) {
            const int x0 = std::clamp(floorToInt<int>(x * ratio + 1e-9), 0, latticeX - 1);
            const int x1 = std::clamp(ceilToInt<int>((x + 1) * ratio - 1e-9) - 1, x0, latticeX - 1);
            bool hole = false;
            for (int k = z0; k <= z1 && !hole; ++k)
                for (int i = x0; i <= x1 && !hole; ++i) hole = tile.hole(i, k);
            out.cells[std::size_t(z) * cellsX + x] = hole ? 1 : 0;
        }
    }
    return out;
}

meshing::TriangleMesh heightfieldRemainder(const TerrainTile& tile, const HeightfieldHoles& holes)
{
    const meshing::TriangleMesh& surface = tile.surface;
    const double v = tile.voxelSize;
    const int latticeX = tile.columns - 1, latticeZ = tile.rows - 1;
    std::vector<std::uint8_t> drawn(surface.positions.size(), 0);
    for (std::size_t n = 0; n < surface.positions.size(); ++n) {
        const glm::vec3 p = surface.positions[n];
        // The lattice cells the vertex lies in (two or four on a cell edge:
        // its dual cube may be either).
        const double fx = double(p.x) / v, fz = double(p.z) / v;
        const int i0 = std::clamp(floorToInt<int>(fx - 1e-6), 0, latticeX - 1);
        const int i1 = std::clamp(floorToInt<int>(fx + 1e-6), 0, latticeX - 1);
        const int k0 = std::clamp(floorToInt<int>(fz - 1e-6), 0, latticeZ - 1);
        const int k1 = std::clamp(floorToInt<int>(fz + 1e-6), 0, latticeZ - 1);
        bool open = true;
        double lowest = HUGE_VAL;
        for (int k = k0; k <= k1; ++k)
            for (int i = i0; i <= i1; ++i) {
                open = open && !tile.hole(i, k);
                lowest = std::min({lowest, tile.height(i, k), tile.height(i + 1, k), tile.height(i, k + 1),
                                   tile.height(i + 1, k + 1)});
            }
        if (!open) continue;
        if (holes.cellsX > 0 && holes.cellsZ > 0) {
            const double ex = double(p.x) / holes.cellSize, ez = double(p.z) / holes.cellSize;
            const int x0 = std::clamp(floorToInt<int>(ex - 1e-6), 0, holes.cellsX - 1);
            const int x1 = std::clamp(floorToInt<int>(ex + 1e-6), 0, holes.cellsX - 1);
            const int z0 = std::clamp(floorToInt<int>(ez - 1e-6), 0, holes.cellsZ - 1);
            const int z1 = std::clamp(floorToInt<int>(ez + 1e-6), 0, holes.cellsZ - 1);
            for (int z = z0; z <= z1; ++z)
                for (int x = x0; x <= x1; ++x) open = open && !holes.cells[std::size_t(z) * holes.cellsX + x];
            if (!open) continue;
        }
        drawn[n] = surface.origin.y + double(p.y) >= lowest - v ? 1 : 0;
    }

    meshing::TriangleMesh out;
    out.origin = surface.origin;
    std::vector<std::uint32_t> remap(surface.positions.size(), UINT32_MAX);
    for (std::size_t t = 0; t + 2 < surface.indices.size(); t += 3) {
        const std::uint32_t* tri = &surface.indices[t];
        if (drawn[tri[0]] && drawn[tri[1]] && drawn[tri[2]]) continue;
        for (int c = 0; c < 3; ++c) out.indices.push_back(tri[c]);
    }
    // Keep the vertices in their order: mark used, then renumber.
    for (std::uint32_t index : out.indices) remap[index] = 0;
    std::uint32_t next = 0;
    for (std::size_t n = 0; n < remap.size(); ++n)
        if (remap[n] == 0) {
            remap[n] = next++;
            out.positions.push_back(surface.positions[n]);
            if (!surface.normals.empty()) out.normals.push_back(surface.normals[n]);
        }
    for (std::uint32_t& index : out.indices) index = remap[index];
    return out;
}

} // namespace strata::world
