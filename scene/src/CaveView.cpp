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

} // namespace

CaveView findCaveView(const openvdb::FloatGrid& grid, const glm::dvec3& regionMin, const glm::dvec3& regionMax,
                      const CaveViewOptions& options)
{
    const glm::dvec3 extent = regionMax - regionMin;
    if (!(extent.x > 0.0 && extent.y > 0.0 && extent.z > 0.0)) {
        throw Error(ErrorKind::BadInput, "--view cave: the region is empty");
    }
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

    // 1. Air or rock at each cell centre.
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
    // 2. Air under rock in its column is cave air.
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

    // 3. 6-connected regions of cave air, in index order; keep the largest.
    constexpr std::int32_t NONE = -1;
    std::vector<std::int32_t> label(cells.count(), NONE);
    std::int32_t labels = 0, best = NONE;
    std::size_t bestSize = 0;
    std::vector<std::size_t> queue;
    for (std::size_t start = 0; start < cells.count(); ++start) {
        if (kind[start] != CAVE || label[start] != NONE) continue;
        queue.assign(1, start);
        label[start] = labels;
        for (std::size_t q = 0; q < queue.size(); ++q) {
            const glm::ivec3 c = cells.coords(queue[q]);
            for (const glm::ivec3& d : FACES) {
                const glm::ivec3 n = c + d;
                if (!cells.inside(n.x, n.y, n.z)) continue;
                const std::size_t ni = cells.index(n.x, n.y, n.z);
                if (kind[ni] == CAVE && label[ni] == NONE) {
                    label[ni] = labels;
                    queue.push_back(ni);
                }
            }
        }
        if (queue.size() > bestSize) {
            bestSize = queue.size();
            best = labels;
        }
        ++labels;
    }
    if (best == NONE || bestSize < 8) {
        throw Error(ErrorKind::BadInput, "--view cave: the terrain has no cave (no air under rock inside the region, at " +
                    std::to_string(cells.size) + " m cells)");
    }
    auto inCave = [&](int i, int j, int k) { return cells.inside(i, j, k) && label[cells.index(i, j, k)] == best; };

    // 4. Breadth-first distance (26 neighbours) from the cave's walls.
    std::vector<std::int32_t> distance(cells.count(), NONE);
    queue.clear();
    for (std::size_t index = 0; index < cells.count(); ++index) {
        if (label[index] != best) continue;
        const glm::ivec3 c = cells.coords(index);
        bool wall = false;
        for (const glm::ivec3& d : FACES) {
            wall = wall || !inCave(c.x + d.x, c.y + d.y, c.z + d.z);
        }
        if (wall) {
            distance[index] = 1;
            queue.push_back(index);
        }
    }
    std::size_t camera = queue.empty() ? 0 : queue.front();
    for (std::size_t q = 0; q < queue.size(); ++q) {
        const glm::ivec3 c = cells.coords(queue[q]);
        const std::int32_t next = distance[queue[q]] + 1;
        for (int dz = -1; dz <= 1; ++dz) {
            for (int dy = -1; dy <= 1; ++dy) {
                for (int dx = -1; dx <= 1; ++dx) {
                    if (!inCave(c.x + dx, c.y + dy, c.z + dz)) continue;
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
        if (label[index] == best && distance[index] > distance[camera]) camera = index;
    }
    const glm::ivec3 cameraCell = cells.coords(camera);
    const glm::dvec3 position = cells.centre(cameraCell.x, cameraCell.y, cameraCell.z);

    // 5. The nearest opening through the cave (6-connected shortest path).
    std::vector<std::size_t> parent(cells.count(), std::numeric_limits<std::size_t>::max());
    queue.assign(1, camera);
    parent[camera] = camera;
    std::size_t opening = std::numeric_limits<std::size_t>::max();
    glm::ivec3 outward{0};
    for (std::size_t q = 0; q < queue.size() && opening == std::numeric_limits<std::size_t>::max(); ++q) {
        const glm::ivec3 c = cells.coords(queue[q]);
        for (const glm::ivec3& d : FACES) {
            const glm::ivec3 n = c + d;
            const bool outside = !cells.inside(n.x, n.y, n.z) ? d.y == 0 // the box's sides, not its bottom
                                                              : kind[cells.index(n.x, n.y, n.z)] == SKY;
            if (outside) {
                opening = queue[q];
                outward = d;
                break;
            }
        }
        for (const glm::ivec3& d : FACES) {
            const glm::ivec3 n = c + d;
            if (!inCave(n.x, n.y, n.z)) continue;
            const std::size_t ni = cells.index(n.x, n.y, n.z);
            if (parent[ni] == std::numeric_limits<std::size_t>::max()) {
                parent[ni] = queue[q];
                queue.push_back(ni);
            }
        }
    }

    CaveView view;
    view.cellSize = cells.size;
    view.caveCells = bestSize;
    view.caveCount = std::size_t(labels);
    view.clearance = (double(distance[camera]) - 0.5) * cells.size;
    glm::dvec3 target;
    if (opening != std::numeric_limits<std::size_t>::max()) {
        std::vector<std::size_t> path; // camera … opening
        for (std::size_t at = opening; at != camera; at = parent[at]) path.push_back(at);
        std::reverse(path.begin(), path.end());
        target = position;
        for (std::size_t at : path) {
            const glm::ivec3 c = cells.coords(at);
            const glm::dvec3 p = cells.centre(c.x, c.y, c.z);
            if (lineOfSight(cells, kind, position, p)) target = p;
        }
        if (!path.empty() &&
            target == cells.centre(cells.coords(opening).x, cells.coords(opening).y, cells.coords(opening).z)) {
            // The opening is in sight: look through it, out of the cave.
            target += glm::dvec3(outward) * (4.0 * cells.size);
            view.looksOut = true;
        }
        if (glm::length(target - position) < 0.5 * cells.size) {
            target = position + glm::dvec3(outward) * (4.0 * cells.size);
            view.looksOut = true;
        }
    } else {
        // Enclosed: the principal axis of the cave's cells (power iteration).
        glm::dvec3 mean(0.0);
        for (std::size_t index = 0; index < cells.count(); ++index) {
            if (label[index] != best) continue;
            const glm::ivec3 c = cells.coords(index);
            mean += cells.centre(c.x, c.y, c.z);
        }
        mean /= double(bestSize);
        glm::dmat3 covariance(0.0);
        for (std::size_t index = 0; index < cells.count(); ++index) {
            if (label[index] != best) continue;
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
            if (label[index] != best) continue;
            const glm::ivec3 c = cells.coords(index);
            const double t = glm::dot(cells.centre(c.x, c.y, c.z) - position, axis);
            ahead = std::max(ahead, t);
            behind = std::max(behind, -t);
        }
        if (behind > ahead) axis = -axis;
        target = position + axis * std::max({ahead, behind, cells.size});
    }

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
