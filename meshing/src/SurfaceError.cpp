// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/SurfaceError.h>

#include <strata/DeterministicMath.h>
#include <strata/Error.h>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace strata::meshing {

namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection 5.1.5).
glm::dvec3 closestOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c)
{
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

// Triangles binned into a uniform grid of cubes about `h` wide (world
// metres), counted from the mesh's lower corner, stored by columns: for each
// (x, y) the (z, triangle) entries of its cells, sorted by z.
class TriangleBuckets
{
public:
    TriangleBuckets(const TriangleMesh& mesh, double h)
        : mMesh(mesh)
    {
        const std::size_t triangles = mesh.triangleCount();
        if (triangles == 0) return;
        glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
        for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
            const glm::dvec3 p = vertex(mesh.indices[i]);
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        // Wider cubes where h would make more than 2^20 cells on an axis or
        // far more columns than triangles (only the speed depends on the
        // width: every distance is exact).
        mLo = lo;
        mH = std::max(h, std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / double(1 << 20));
        const double columnBudget = std::max(65536.0, 8.0 * double(triangles));
        for (;;) {
            for (int a = 0; a < 3; ++a) mCells[a] = cellOf(hi[a], a) + 1;
            if (double(mCells[0]) * double(mCells[1]) <= columnBudget) break;
            mH *= 2.0;
        }
        // Count, then place: each column's entries in one run.
        mColumnStart.assign(std::size_t(mCells[0] * mCells[1]) + 1, 0);
        const auto range = [&](std::uint32_t t, std::int64_t (&c0)[3], std::int64_t (&c1)[3]) {
            glm::dvec3 tlo = vertex(mesh.indices[3 * t]), thi = tlo;
            for (int k = 1; k < 3; ++k) {
                const glm::dvec3 p = vertex(mesh.indices[3 * t + k]);
                tlo = glm::min(tlo, p);
                thi = glm::max(thi, p);
            }
            for (int a = 0; a < 3; ++a) {
                c0[a] = cellOf(tlo[a], a);
                c1[a] = cellOf(thi[a], a);
            }
        };
        std::int64_t c0[3], c1[3];
        for (std::uint32_t t = 0; t < triangles; ++t) {
            range(t, c0, c1);
            for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
                for (std::int64_t y = c0[1]; y <= c1[1]; ++y) mColumnStart[column(x, y) + 1] += std::size_t(c1[2] - c0[2] + 1);
        }
        for (std::size_t i = 1; i < mColumnStart.size(); ++i) mColumnStart[i] += mColumnStart[i - 1];
        mEntries.resize(mColumnStart.back());
        std::vector<std::size_t> next(mColumnStart.begin(), mColumnStart.end() - 1);
        for (std::uint32_t t = 0; t < triangles; ++t) {
            range(t, c0, c1);
            for (std::int64_t x = c0[0]; x <= c1[0]; ++x)
                for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
                    std::size_t& at = next[column(x, y)];
                    for (std::int64_t z = c0[2]; z <= c1[2]; ++z) mEntries[at++] = {std::uint32_t(z), t};
                }
        }
        for (std::size_t c = 0; c + 1 < mColumnStart.size(); ++c) {
            std::sort(mEntries.begin() + std::ptrdiff_t(mColumnStart[c]), mEntries.begin() + std::ptrdiff_t(mColumnStart[c + 1]),
                      [](const Entry& a, const Entry& b) { return a.z < b.z; });
        }
    }

    glm::dvec3 vertex(std::uint32_t i) const { return mMesh.origin + glm::dvec3(mMesh.positions[i]); }

    // Distance from p to the nearest triangle (infinity for an empty mesh), exact.
    // Shells of cells at growing Chebyshev radius r around p's cell; once the
    // best distance is no more than the distance from p to the faces of the
    // cube of cells scanned so far, no triangle outside it can be nearer (a
    // triangle is in every cell its box touches). Stopping at that face, not
    // at r·h, usually ends the search in p's own cell.
    double distance(const glm::dvec3& p) const
    {
        if (mEntries.empty()) return std::numeric_limits<double>::infinity();
        // Far outside the grid the cell is clamped: the faces below then lie
        // behind p, so the search goes on to the fallback, still exact.
        std::int64_t c[3];
        for (int a = 0; a < 3; ++a) c[a] = std::clamp<std::int64_t>(cellOf(p[a], a), -(1 << 24), mCells[a] + (1 << 24));
        // Cell rounding (floor) may put p an ulp outside its cell: slack.
        const double slack = 1e-9 * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + mH);
        double best = std::numeric_limits<double>::infinity();
        for (std::int64_t r = 0; r <= 64; ++r) {
            for (std::int64_t x = c[0] - r; x <= c[0] + r; ++x)
                for (std::int64_t y = c[1] - r; y <= c[1] + r; ++y) {
                    // A column (or cell) whose box is no nearer than `best` cannot hold a nearer
                    // triangle: that triangle's nearest point lies in a cell it also touches.
                    const double dx = gap(p.x, x, 0), dy = gap(p.y, y, 1), dxy2 = dx * dx + dy * dy;
                    if (dxy2 >= best * best) continue;
                    if (std::abs(x - c[0]) == r || std::abs(y - c[1]) == r) {
                        nearestInColumn(p, x, y, c[2] - r, c[2] + r, dxy2, best); // the whole column is on the shell
                    } else {
                        nearestInColumn(p, x, y, c[2] - r, c[2] - r, dxy2, best);
                        nearestInColumn(p, x, y, c[2] + r, c[2] + r, dxy2, best);
                    }
                }
            double reach = std::numeric_limits<double>::infinity();
            for (int a = 0; a < 3; ++a) {
                reach = std::min({reach, p[a] - lower(c[a] - r, a), lower(c[a] + r + 1, a) - p[a]});
            }
            if (best <= reach - slack) return best;
        }
        // Far from every triangle (beyond 64 shells): all of them.
        for (std::uint32_t t = 0; t < mMesh.triangleCount(); ++t) {
            const glm::dvec3 q = closestOnTriangle(p, vertex(mMesh.indices[3 * t]), vertex(mMesh.indices[3 * t + 1]),
                                                   vertex(mMesh.indices[3 * t + 2]));
            best = std::min(best, glm::length(p - q));
        }
        return best;
    }

private:
    struct Entry
    {
        std::uint32_t z, triangle;
    };

    // The cell of coordinate v on axis a (may lie outside [0, mCells[a])).
    std::int64_t cellOf(double v, int a) const
    {
        const double c = std::floor((v - mLo[a]) / mH);
        return std::int64_t(std::clamp(c, -4.0e15, 4.0e15)); // no overflow in the conversion
    }
    double lower(std::int64_t i, int a) const { return mLo[a] + double(i) * mH; }
    // Distance from v to cell i's interval on axis a (0 inside).
    double gap(double v, std::int64_t i, int a) const { return std::max({0.0, lower(i, a) - v, v - lower(i + 1, a)}); }
    std::size_t column(std::int64_t x, std::int64_t y) const { return std::size_t(x * mCells[1] + y); }

    // Lowers `best` to the distance from p to each triangle in cells (x, y, z0..z1).
    // Cells whose box lies no nearer than `best` (dxy2: the squared distance
    // across x and y) are skipped.
    void nearestInColumn(const glm::dvec3& p, std::int64_t x, std::int64_t y, std::int64_t z0, std::int64_t z1,
                         double dxy2, double& best) const
    {
        if (x < 0 || x >= mCells[0] || y < 0 || y >= mCells[1]) return;
        z0 = std::max<std::int64_t>(z0, 0);
        z1 = std::min<std::int64_t>(z1, mCells[2] - 1);
        if (z0 > z1) return;
        const std::size_t c = column(x, y);
        const auto end = mEntries.begin() + std::ptrdiff_t(mColumnStart[c + 1]);
        std::int64_t z = -1;
        bool skip = false;
        for (auto it = std::lower_bound(mEntries.begin() + std::ptrdiff_t(mColumnStart[c]), end, std::uint32_t(z0),
                                        [](const Entry& e, std::uint32_t v) { return e.z < v; });
             it != end && std::int64_t(it->z) <= z1; ++it) {
            if (std::int64_t(it->z) != z) {
                z = it->z;
                const double dz = gap(p.z, z, 2);
                skip = dxy2 + dz * dz >= best * best;
            }
            if (skip) continue;
            const std::uint32_t t = it->triangle;
            const glm::dvec3 q = closestOnTriangle(p, vertex(mMesh.indices[3 * t]), vertex(mMesh.indices[3 * t + 1]),
                                                   vertex(mMesh.indices[3 * t + 2]));
            best = std::min(best, glm::length(p - q));
        }
    }

    const TriangleMesh& mMesh;
    double mH = 1.0;
    glm::dvec3 mLo{0.0};
    std::int64_t mCells[3] = {1, 1, 1};
    std::vector<std::size_t> mColumnStart; ///< entries of column x·cells[1] + y: [start[c], start[c + 1])
    std::vector<Entry> mEntries;
};

struct Accumulator
{
    double sum = 0.0, sum2 = 0.0, max = 0.0;
    std::size_t count = 0;
    void add(double d)
    {
        sum += d;
        sum2 += d * d;
        max = std::max(max, d);
        ++count;
    }
};

} // namespace

SurfaceError measureSurfaceError(const TriangleMesh& mesh, const DistanceFunction& distance,
                                 const SurfaceErrorOptions& options)
{
    if (!(options.voxelSize > 0.0) || !std::isfinite(options.voxelSize)) {
        throw Error(ErrorKind::BadInput, "surface error: voxel size must be positive");
    }
    if (!distance && options.meshToSurface) throw Error(ErrorKind::BadInput, "surface error: no distance function");
    const double voxel = options.voxelSize;

    // Per-sample values first (parallel), then summed in order: deterministic.
    const std::size_t vertices = mesh.vertexCount(), triangles = mesh.triangleCount();
    std::vector<double> meshDistances(options.meshToSurface ? vertices + triangles : 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, meshDistances.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            glm::dvec3 p;
            if (i < vertices) {
                p = mesh.origin + glm::dvec3(mesh.positions[i]);
            } else {
                const std::size_t t = i - vertices;
                p = mesh.origin + (glm::dvec3(mesh.positions[mesh.indices[3 * t]]) +
                                   glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) +
                                   glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]])) / 3.0;
            }
            meshDistances[i] = std::abs(distance(p)) / voxel;
        }
    });

    std::vector<double> surfaceDistances(options.surfacePoints.size());
    if (!surfaceDistances.empty()) {
        const TriangleBuckets buckets(mesh, 2.0 * voxel);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, surfaceDistances.size(), 256),
                          [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                surfaceDistances[i] = buckets.distance(options.surfacePoints[i]) / voxel;
            }
        });
    }

    Accumulator toSurface, toMesh, both;
    for (double d : meshDistances) {
        toSurface.add(d);
        both.add(d);
    }
    for (double d : surfaceDistances) {
        toMesh.add(d);
        both.add(d);
    }
    SurfaceError e;
    auto meanOf = [](const Accumulator& a) { return a.count ? a.sum / double(a.count) : 0.0; };
    auto rmsOf = [](const Accumulator& a) { return a.count ? std::sqrt(a.sum2 / double(a.count)) : 0.0; };
    e.meshToSurfaceMean = meanOf(toSurface);
    e.meshToSurfaceRms = rmsOf(toSurface);
    e.meshToSurfaceMax = toSurface.max;
    e.surfaceToMeshMean = meanOf(toMesh);
    e.surfaceToMeshRms = rmsOf(toMesh);
    e.surfaceToMeshMax = toMesh.max;
    e.mean = meanOf(both);
    e.rms = rmsOf(both);
    e.hausdorff = std::max(toSurface.max, toMesh.max);
    e.meshSamples = toSurface.count;
    e.surfaceSamples = toMesh.count;

    if (options.meshToSurface && options.gradient && mesh.normals.size() == mesh.positions.size() && vertices > 0) {
        std::vector<double> angles(vertices);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const glm::dvec3 g = options.gradient(mesh.origin + glm::dvec3(mesh.positions[i]));
                const glm::dvec3 n(mesh.normals[i]);
                const double len = glm::length(g) * glm::length(n);
                angles[i] = len > 0
                                ? dmath::acos(std::clamp(glm::dot(g, n) / len, -1.0, 1.0)) * 180.0 / std::numbers::pi
                                : 180.0;
            }
        });
        double sum = 0.0;
        std::size_t over = 0;
        for (double a : angles) {
            sum += a;
            over += a > 5.0 ? 1 : 0;
        }
        e.normalMeanDegrees = sum / double(vertices);
        e.normalOver5Percent = 100.0 * double(over) / double(vertices);
    }
    return e;
}

std::vector<glm::dvec3> sampleSurface(const DistanceFunction& distance, const GradientFunction& gradient,
                                      const glm::dvec3& min, const glm::dvec3& max, double spacing)
{
    if (!distance || !gradient) throw Error(ErrorKind::BadInput, "sampleSurface: needs a distance and a gradient function");
    if (!(spacing > 0.0)) throw Error(ErrorKind::BadInput, "sampleSurface: spacing must be positive");
    const glm::ivec3 n = glm::ivec3(glm::ceil((max - min) / spacing)) + 1;
    std::vector<std::vector<glm::dvec3>> slabs(std::size_t(std::max(n.x, 0)));
    tbb::parallel_for(0, std::max(n.x, 0), [&](int x) {
        for (int y = 0; y < n.y; ++y) {
            for (int z = 0; z < n.z; ++z) {
                glm::dvec3 p = min + glm::dvec3(x, y, z) * spacing;
                double d = distance(p);
                if (std::abs(d) > spacing) continue;
                for (int step = 0; step < 8 && std::abs(d) > 1e-9 * spacing; ++step) {
                    const glm::dvec3 g = gradient(p);
                    const double g2 = glm::dot(g, g);
                    if (!(g2 > 0.0)) break;
                    p -= g * (d / g2);
                    d = distance(p);
                }
                if (std::abs(d) <= 1e-6 * spacing) slabs[std::size_t(x)].push_back(p);
            }
        }
    });
    std::vector<glm::dvec3> points;
    for (const auto& slab : slabs) points.insert(points.end(), slab.begin(), slab.end());
    return points;
}

} // namespace strata::meshing
