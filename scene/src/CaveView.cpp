// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/CaveView.h>

#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <vector>

namespace strata::scene {

namespace {

enum : std::uint8_t
{
    ROCK = 0,
    SKY = 1,
    CAVE = 2
};

struct Cells
{
    int nx = 0, ny = 0, nz = 0;
    double size = 0.0;
    glm::dvec3 origin{0.0}; // world position of cell (0, 0, 0)'s corner

    std::size_t count() const { return std::size_t(nx) * std::size_t(ny) * std::size_t(nz); }
    std::size_t index(int i, int j, int k) const
    {
        return (std::size_t(k) * std::size_t(ny) + std::size_t(j)) * std::size_t(nx) + std::size_t(i);
    }
    bool inside(int i, int j, int k) const { return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz; }
    glm::dvec3 centre(int i, int j, int k) const { return origin + (glm::dvec3(i, j, k) + 0.5) * size; }
    glm::ivec3 coords(std::size_t index) const
    {
        const auto i = int(index % std::size_t(nx));
        const auto j = int((index / std::size_t(nx)) % std::size_t(ny));
        const auto k = int(index / (std::size_t(nx) * std::size_t(ny)));
        return {i, j, k};
    }
};

constexpr std::array<glm::ivec3, 6> FACES = {glm::ivec3{-1, 0, 0}, glm::ivec3{1, 0, 0},  glm::ivec3{0, -1, 0},
                                             glm::ivec3{0, 1, 0},  glm::ivec3{0, 0, -1}, glm::ivec3{0, 0, 1}};

/// True when every point of the segment a→b (sampled every quarter cell)
/// lies in a non-rock cell inside the box.
bool lineOfSight(const Cells& cells, const std::vector<std::uint8_t>& kind, const glm::dvec3& a, const glm::dvec3& b)
{
    const double length = glm::length(b - a);
    const int steps = std::max(1, ceilToInt<int>(length / (0.25 * cells.size)));
    for (int s = 0; s <= steps; ++s) {
        const glm::dvec3 p = a + (b - a) * (double(s) / double(steps));
        const glm::dvec3 c = glm::floor((p - cells.origin) / cells.size);
        const int i = int(c.x), j = int(c.y), k = int(c.z);
        if (!cells.inside(i, j, k) || kind[cells.index(i, j, k)] == ROCK) {
            return false;
        }
    }
    return true;
}

constexpr std::int32_t NONE = -1;
constexpr std::size_t NO_CELL = std::numeric_limits<std::size_t>::max();

/// The cells over the region: the option's size (or two voxels), grown by a
/// quarter until there are at most maxCells of them.
Cells cellsOver(const openvdb::FloatGrid& grid, const glm::dvec3& regionMin, const glm::dvec3& extent,
                const CaveViewOptions& options)
{
    Cells cells;
    cells.size = options.cellSize > 0.0 ? options.cellSize : 2.0 * grid.voxelSize()[0];
    auto dimensions = [&] {
        cells.nx = std::max(1, ceilToInt<int>(extent.x / cells.size));
        cells.ny = std::max(1, ceilToInt<int>(extent.y / cells.size));
        cells.nz = std::max(1, ceilToInt<int>(extent.z / cells.size));
    };
    dimensions();
    while (cells.count() > options.maxCells) {
        cells.size *= 1.25;
        dimensions();
    }
    cells.origin = regionMin;
    return cells;
}

/// 1. Air (SKY) or rock at each cell centre.
std::vector<std::uint8_t> sampleAir(const openvdb::FloatGrid& grid, const Cells& cells)
{
    std::vector<std::uint8_t> kind(cells.count(), ROCK);
    const openvdb::math::Transform& xform = grid.transform();
    tbb::parallel_for(tbb::blocked_range<int>(0, cells.nz), [&](const tbb::blocked_range<int>& r) {
        auto accessor = grid.getConstAccessor();
        for (int k = r.begin(); k != r.end(); ++k) {
            for (int j = 0; j < cells.ny; ++j) {
                for (int i = 0; i < cells.nx; ++i) {
                    const glm::dvec3 p = cells.centre(i, j, k);
                    const openvdb::Coord ijk = xform.worldToIndexCellCentered(openvdb::Vec3d(p.x, p.y, p.z));
                    kind[cells.index(i, j, k)] = accessor.getValue(ijk) > 0.0f ? SKY : ROCK;
                }
            }
        }
    });
    return kind;
}

/// 2. Air under rock in its column is cave air.
void markCaveAir(const Cells& cells, std::vector<std::uint8_t>& kind)
{
    for (int k = 0; k < cells.nz; ++k) {
        for (int i = 0; i < cells.nx; ++i) {
            bool roofed = false;
            for (int j = cells.ny - 1; j >= 0; --j) {
                std::uint8_t& cell = kind[cells.index(i, j, k)];
                if (cell == ROCK) {
                    roofed = true;
                } else if (roofed) {
                    cell = CAVE;
                }
            }
        }
    }
}

/// The 6-connected regions of cave air and the largest of them.
struct Caves
{
    std::vector<std::int32_t> label; ///< region of each cell, NONE outside cave air
    std::int32_t count = 0;          ///< regions
    std::int32_t best = NONE;        ///< the largest (the first of equals)
    std::size_t bestSize = 0;        ///< its cells

    bool inBest(const Cells& cells, int i, int j, int k) const
    {
        return cells.inside(i, j, k) && label[cells.index(i, j, k)] == best;
    }
};

/// 3. 6-connected regions of cave air, in index order; keeps the largest.
/// Throws when there is none of at least 8 cells.
Caves labelCaves(const Cells& cells, const std::vector<std::uint8_t>& kind)
{
    Caves caves;
    caves.label.assign(cells.count(), NONE);
    std::vector<std::int32_t>& label = caves.label;
    std::vector<std::size_t> queue;
    for (std::size_t start = 0; start < cells.count(); ++start) {
        if (kind[start] != CAVE || label[start] != NONE) continue;
        queue.assign(1, start);
        label[start] = caves.count;
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const glm::ivec3 c = cells.coords(queue[q]);
            for (const glm::ivec3& d : FACES) {
                const glm::ivec3 n = c + d;
                if (!cells.inside(n.x, n.y, n.z)) continue;
                const std::size_t ni = cells.index(n.x, n.y, n.z);
                if (kind[ni] == CAVE && label[ni] == NONE) {
                    label[ni] = caves.count;
                    queue.push_back(ni);
                }
            }
        }
        if (queue.size() > caves.bestSize) {
            caves.bestSize = queue.size();
            caves.best = caves.count;
        }
        ++caves.count;
    }
    if (caves.best == NONE || caves.bestSize < 8) {
        throw Error(ErrorKind::BadInput,
                    "--view cave: the terrain has no cave (no air under rock inside the region, at " +
                        std::to_string(cells.size) + " m cells)");
    }
    return caves;
}

/// 4. Breadth-first distance (26 neighbours, in cells, 1 at the walls) from
/// the largest cave's walls, NONE outside it. `deepest` is set to its
/// deepest cell (the first of equals, starting from the first wall cell).
std::vector<std::int32_t> distanceFromWalls(const Cells& cells, const Caves& caves, std::size_t& deepest)
{
    std::vector<std::int32_t> distance(cells.count(), NONE);
    std::vector<std::size_t> queue;
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (caves.label[index] != caves.best) continue;
        const glm::ivec3 c = cells.coords(index);
        bool wall = false;
        for (const glm::ivec3& d : FACES) {
            wall = wall || !caves.inBest(cells, c.x + d.x, c.y + d.y, c.z + d.z);
        }
        if (wall) {
            distance[index] = 1;
            queue.push_back(index);
        }
    }
    deepest = queue.empty() ? 0 : queue.front();
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const glm::ivec3 c = cells.coords(queue[q]);
        const std::int32_t next = distance[queue[q]] + 1;
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    if (!caves.inBest(cells, c.x + dx, c.y + dy, c.z + dz)) continue;
                    const std::size_t ni = cells.index(c.x + dx, c.y + dy, c.z + dz);
                    if (distance[ni] == NONE) {
                        distance[ni] = next;
                        queue.push_back(ni);
                    }
                }
            }
        }
    }
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (caves.label[index] == caves.best && distance[index] > distance[deepest]) deepest = index;
    }
    return distance;
}

/// The nearest opening from the camera's cell, and the path to it.
struct Opening
{
    std::vector<std::size_t> parent; ///< each reached cell's predecessor towards the camera
    std::size_t cell = NO_CELL;      ///< the cave cell at the opening; NO_CELL when enclosed
    glm::ivec3 outward{0};           ///< the face through which it opens
};

/// 5. The nearest opening through the cave (6-connected shortest path).
Opening findOpening(const Cells& cells, const std::vector<std::uint8_t>& kind, const Caves& caves, std::size_t camera)
{
    Opening opening;
    std::vector<std::size_t>& parent = opening.parent;
    parent.assign(cells.count(), NO_CELL);
    std::vector<std::size_t> queue(1, camera);
    parent[camera] = camera;
    for (std::size_t q = 0; q < queue.size() && opening.cell == NO_CELL; ++q) {
        const glm::ivec3 c = cells.coords(queue[q]);
        for (const glm::ivec3& d : FACES) {
            const glm::ivec3 n = c + d;
            const bool outside = !cells.inside(n.x, n.y, n.z) ? d.y == 0 // the box's sides, not its bottom
                                                              : kind[cells.index(n.x, n.y, n.z)] == SKY;
            if (outside) {
                opening.cell = queue[q];
                opening.outward = d;
                break;
            }
        }
        for (const glm::ivec3& d : FACES) {
            const glm::ivec3 n = c + d;
            if (!caves.inBest(cells, n.x, n.y, n.z)) continue;
            const std::size_t ni = cells.index(n.x, n.y, n.z);
            if (parent[ni] == NO_CELL) {
                parent[ni] = queue[q];
                queue.push_back(ni);
            }
        }
    }
    return opening;
}

/// The farthest cell of the path to the opening in sight of the camera; out
/// through the opening when that is the opening itself (or when the camera
/// sees nothing farther than half a cell).
glm::dvec3 targetTowardsOpening(const Cells& cells, const std::vector<std::uint8_t>& kind, const Opening& opening,
                                std::size_t camera, const glm::dvec3& position, bool& looksOut)
{
    std::vector<std::size_t> path; // camera … opening
    for (std::size_t at = opening.cell; at != camera; at = opening.parent[at]) path.push_back(at);
    std::reverse(path.begin(), path.end());
    glm::dvec3 target = position;
    for (std::size_t at : path) {
        const glm::ivec3 c = cells.coords(at);
        const glm::dvec3 p = cells.centre(c.x, c.y, c.z);
        if (lineOfSight(cells, kind, position, p)) target = p;
    }
    if (!path.empty() && target == cells.centre(cells.coords(opening.cell).x, cells.coords(opening.cell).y,
                                                cells.coords(opening.cell).z)) {
        // The opening is in sight: look through it, out of the cave.
        target += glm::dvec3(opening.outward) * (4.0 * cells.size);
        looksOut = true;
    }
    if (glm::length(target - position) < 0.5 * cells.size) {
        target = position + glm::dvec3(opening.outward) * (4.0 * cells.size);
        looksOut = true;
    }
    return target;
}

/// Enclosed: along the principal axis of the cave's cells (power
/// iteration), towards its longer side from the camera.
glm::dvec3 targetAlongAxis(const Cells& cells, const Caves& caves, const glm::dvec3& position)
{
    glm::dvec3 mean(0.0);
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (caves.label[index] != caves.best) continue;
        const glm::ivec3 c = cells.coords(index);
        mean += cells.centre(c.x, c.y, c.z);
    }
    mean /= double(caves.bestSize);
    glm::dmat3 covariance(0.0);
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (caves.label[index] != caves.best) continue;
        const glm::ivec3 c = cells.coords(index);
        const glm::dvec3 d = cells.centre(c.x, c.y, c.z) - mean;
        covariance += glm::outerProduct(d, d);
    }
    glm::dvec3 axis(1.0, 0.5, 0.25);
    for (int iteration = 0; iteration < 64; ++iteration) {
        const glm::dvec3 next = covariance * axis;
        const double len = glm::length(next);
        if (!(len > 0.0)) break;
        axis = next / len;
    }
    axis = glm::normalize(axis);
    double ahead = 0.0, behind = 0.0;
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (caves.label[index] != caves.best) continue;
        const glm::ivec3 c = cells.coords(index);
        const double t = glm::dot(cells.centre(c.x, c.y, c.z) - position, axis);
        ahead = std::max(ahead, t);
        behind = std::max(behind, -t);
    }
    if (behind > ahead) axis = -axis;
    return position + axis * std::max({ahead, behind, cells.size});
}

} // namespace

CaveView findCaveView(const openvdb::FloatGrid& grid, const glm::dvec3& regionMin, const glm::dvec3& regionMax,
                      const CaveViewOptions& options)
{
    const glm::dvec3 extent = regionMax - regionMin;
    if (!(extent.x > 0.0 && extent.y > 0.0 && extent.z > 0.0)) {
        throw Error(ErrorKind::BadInput, "--view cave: the region is empty");
    }
    const Cells cells = cellsOver(grid, regionMin, extent, options);
    std::vector<std::uint8_t> kind = sampleAir(grid, cells);
    markCaveAir(cells, kind);
    const Caves caves = labelCaves(cells, kind);
    std::size_t camera = 0;
    const std::vector<std::int32_t> distance = distanceFromWalls(cells, caves, camera);
    const glm::ivec3 cameraCell = cells.coords(camera);
    const glm::dvec3 position = cells.centre(cameraCell.x, cameraCell.y, cameraCell.z);
    const Opening opening = findOpening(cells, kind, caves, camera);

    CaveView view;
    view.cellSize = cells.size;
    view.caveCells = caves.bestSize;
    view.caveCount = std::size_t(caves.count);
    view.clearance = (double(distance[camera]) - 0.5) * cells.size;
    const glm::dvec3 target = opening.cell != NO_CELL
                                  ? targetTowardsOpening(cells, kind, opening, camera, position, view.looksOut)
                                  : targetAlongAxis(cells, caves, position);

    render::Camera& cam = view.camera;
    cam.position = position;
    cam.target = target;
    const glm::dvec3 forward = glm::normalize(target - position);
    cam.up = std::abs(forward.y) > 0.99 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 1.0, 0.0);
    cam.fovYDegrees = options.fovYDegrees;
    cam.nearPlane = std::clamp(0.25 * view.clearance, 0.01, 0.1);
    cam.farPlane = glm::length(extent) * 2.0 + 1.0;
    return view;
}

} // namespace strata::scene
