// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/SurfaceError.h>

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

// Triangles binned into a uniform grid of cubes `h` wide (world metres).
class TriangleBuckets
{
public:
    TriangleBuckets(const TriangleMesh& mesh, double h)
        : mMesh(mesh), mH(h)
    {
        for (std::uint32_t t = 0; t < mesh.triangleCount(); ++t) {
            glm::dvec3 lo(std::numeric_limits<double>::max()), hi(std::numeric_limits<double>::lowest());
            for (int k = 0; k < 3; ++k) {
                const glm::dvec3 p = vertex(mesh.indices[3 * t + k]);
                lo = glm::min(lo, p);
                hi = glm::max(hi, p);
            }
            const std::array<int, 3> a = cell(lo), b = cell(hi);
            for (int x = a[0]; x <= b[0]; ++x)
                for (int y = a[1]; y <= b[1]; ++y)
                    for (int z = a[2]; z <= b[2]; ++z) mEntries.push_back({{x, y, z}, t});
        }
        std::sort(mEntries.begin(), mEntries.end());
    }

    glm::dvec3 vertex(std::uint32_t i) const { return mMesh.origin + glm::dvec3(mMesh.positions[i]); }

    std::array<int, 3> cell(const glm::dvec3& p) const
    {
        return {int(std::floor(p.x / mH)), int(std::floor(p.y / mH)), int(std::floor(p.z / mH))};
    }

    // Distance from p to the nearest triangle (infinity for an empty mesh), exact.
    // Shells of cells at growing Chebyshev radius r around p's cell; once the
    // best distance is no more than the distance from p to the faces of the
    // cube of cells scanned so far, no triangle outside it can be nearer (a
    // triangle is in every cell its box touches). Stopping at that face, not
    // at r·h, usually ends the search in p's own cell.
    double distance(const glm::dvec3& p) const
    {
        if (mEntries.empty()) return std::numeric_limits<double>::infinity();
        const std::array<int, 3> c = cell(p);
        // Cell rounding (floor(p / h)) may put p an ulp outside its cell: slack.
        const double slack = 1e-9 * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + mH);
        double best = std::numeric_limits<double>::infinity();
        for (int r = 0; r <= 64; ++r) {
            for (int x = c[0] - r; x <= c[0] + r; ++x)
                for (int y = c[1] - r; y <= c[1] + r; ++y) {
                    // A column (or cell) whose box is no nearer than `best` cannot hold a nearer
                    // triangle: that triangle's nearest point lies in a cell it also touches.
                    const double dx = gap(p.x, x), dy = gap(p.y, y), dxy2 = dx * dx + dy * dy;
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
                reach = std::min({reach, p[a] - double(c[a] - r) * mH, double(c[a] + r + 1) * mH - p[a]});
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
        std::array<int, 3> cell;
        std::uint32_t triangle;
        // Component by component: std::array's operators call memcmp, which
        // dominated the lookups.
        bool operator<(const Entry& o) const
        {
            if (cell[0] != o.cell[0]) return cell[0] < o.cell[0];
            if (cell[1] != o.cell[1]) return cell[1] < o.cell[1];
            if (cell[2] != o.cell[2]) return cell[2] < o.cell[2];
            return triangle < o.triangle;
        }
    };
    // Distance from v to the cell interval [i·h, (i + 1)·h] on one axis (0 inside).
    double gap(double v, int i) const { return std::max({0.0, double(i) * mH - v, v - double(i + 1) * mH}); }

    // Lowers `best` to the distance from p to each triangle in cells (x, y, z0..z1):
    // consecutive in the sorted entries, so one binary search. Cells whose box
    // lies no nearer than `best` (dxy2: the squared distance across x and y) are skipped.
    void nearestInColumn(const glm::dvec3& p, int x, int y, int z0, int z1, double dxy2, double& best) const
    {
        int z = z0 - 1;
        bool skip = false;
        for (auto it = std::lower_bound(mEntries.begin(), mEntries.end(), Entry{{x, y, z0}, 0});
             it != mEntries.end() && it->cell[0] == x && it->cell[1] == y && it->cell[2] <= z1; ++it) {
            if (it->cell[2] != z) {
                z = it->cell[2];
                const double dz = gap(p.z, z);
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
    double mH;
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
    if (!distance) throw Error(ErrorKind::BadInput, "surface error: no distance function");
    const double voxel = options.voxelSize;

    // Per-sample values first (parallel), then summed in order: deterministic.
    const std::size_t vertices = mesh.vertexCount(), triangles = mesh.triangleCount();
    std::vector<double> meshDistances(vertices + triangles);
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

    if (options.gradient && mesh.normals.size() == mesh.positions.size() && vertices > 0) {
        std::vector<double> angles(vertices);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, vertices, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) {
                const glm::dvec3 g = options.gradient(mesh.origin + glm::dvec3(mesh.positions[i]));
                const glm::dvec3 n(mesh.normals[i]);
                const double len = glm::length(g) * glm::length(n);
                angles[i] = len > 0 ? std::acos(std::clamp(glm::dot(g, n) / len, -1.0, 1.0)) * 180.0 / std::numbers::pi : 180.0;
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
