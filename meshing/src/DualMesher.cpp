#include "DualMesher.h"

#include <strata/Error.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

namespace strata::meshing {

using openvdb::Coord;

namespace {

constexpr std::uint32_t UNSET = 0xffffffffu;
constexpr std::size_t NO_SAMPLE = ~std::size_t(0);
constexpr int APRON = 3;             // block samples below the first owned cell (ENO stencils)
constexpr double QUANTUM = 65536.0;  // vertex offsets inside a cell are multiples of 1/65536
constexpr float MIN_LENGTH2 = 1e-20f;

// Index space to world space for a linear transform: world = t + A * ijk,
// and world gradients from index gradients through the inverse transpose.
struct Frame
{
    openvdb::Vec3d t, a[3], g[3];

    explicit Frame(const openvdb::math::Transform& transform)
    {
        const openvdb::math::MapBase& map = *transform.baseMap();
        t = transform.indexToWorld(openvdb::Vec3d(0.0));
        for (int i = 0; i < 3; ++i) {
            openvdb::Vec3d e(0.0);
            e[i] = 1.0;
            a[i] = map.applyJacobian(e);
            g[i] = map.applyIJT(e);
        }
    }
    glm::dvec3 world(const openvdb::Vec3d& ijk) const
    {
        const openvdb::Vec3d w = t + a[0] * ijk[0] + a[1] * ijk[1] + a[2] * ijk[2];
        return {w[0], w[1], w[2]};
    }
    // Linear part only (a difference of index positions).
    glm::dvec3 offset(const openvdb::Vec3d& ijk) const
    {
        const openvdb::Vec3d w = a[0] * ijk[0] + a[1] * ijk[1] + a[2] * ijk[2];
        return {w[0], w[1], w[2]};
    }
    glm::dvec3 worldGradient(const openvdb::Vec3d& indexGradient) const
    {
        const openvdb::Vec3d w = g[0] * indexGradient[0] + g[1] * indexGradient[1] + g[2] * indexGradient[2];
        return {w[0], w[1], w[2]};
    }
    // Index-space direction of a world gradient: A^T * g.
    openvdb::Vec3d indexGradient(const glm::dvec3& world) const
    {
        const openvdb::Vec3d w(world.x, world.y, world.z);
        return {a[0].dot(w), a[1].dot(w), a[2].dot(w)};
    }
};

// The dense samples a chunk needs: its cells, the one-cell apron below and
// one more layer on each side for central differences.
struct Block
{
    Coord min;   // index coordinates of sample (0,0,0)
    int n[3];    // samples per axis
    std::vector<float> values;
    std::vector<std::uint8_t> inside;

    std::size_t at(int x, int y, int z) const { return (std::size_t(x) * n[1] + y) * n[2] + z; }
    std::size_t stride(int axis) const { return axis == 0 ? std::size_t(n[1]) * n[2] : axis == 1 ? n[2] : 1; }

    // Trilinear interpolation at `p`, relative to sample `base`, p in
    // [-1, 2]^3 (a cell and one voxel around it). Relative coordinates make
    // the result independent of where the cell sits in the block, so every
    // chunk that meshes a cell gets the same bits.
    double sample(std::size_t base, const openvdb::Vec3d& p) const
    {
        const int x = std::clamp(int(std::floor(p[0])), -1, 1);
        const int y = std::clamp(int(std::floor(p[1])), -1, 1);
        const int z = std::clamp(int(std::floor(p[2])), -1, 1);
        const double u = p[0] - x, v = p[1] - y, w = p[2] - z;
        const std::size_t sx = stride(0), sy = stride(1);
        const std::size_t i = base + x * std::ptrdiff_t(sx) + y * std::ptrdiff_t(sy) + z;
        auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
        const double c00 = lerp(values[i], values[i + 1], w), c01 = lerp(values[i + sy], values[i + sy + 1], w);
        const double c10 = lerp(values[i + sx], values[i + sx + 1], w);
        const double c11 = lerp(values[i + sx + sy], values[i + sx + sy + 1], w);
        return lerp(lerp(c00, c01, v), lerp(c10, c11, v), u);
    }
    // Central differences one voxel apart on the trilinear interpolant,
    // p in [0, 1]^3 relative to sample `base`.
    openvdb::Vec3d gradient(std::size_t base, const openvdb::Vec3d& p) const
    {
        return {0.5 * (sample(base, p + openvdb::Vec3d(1, 0, 0)) - sample(base, p - openvdb::Vec3d(1, 0, 0))),
                0.5 * (sample(base, p + openvdb::Vec3d(0, 1, 0)) - sample(base, p - openvdb::Vec3d(0, 1, 0))),
                0.5 * (sample(base, p + openvdb::Vec3d(0, 0, 1)) - sample(base, p - openvdb::Vec3d(0, 0, 1)))};
    }
    // Gradient at a sample, per axis: central differences where the field is
    // smooth (small centred second difference), else the one-sided
    // difference whose side is smoother (ENO: smaller one-sided second
    // difference), so a kink (a sharp edge of the surface) next to the
    // sample does not bend the estimate. `smooth` bounds the second
    // difference of a smooth field (world units).
    openvdb::Vec3d enoGradient(std::size_t i, double smooth) const
    {
        openvdb::Vec3d g;
        for (int a = 0; a < 3; ++a) {
            const std::size_t s = stride(a);
            const double m2 = values[i - 2 * s], m1 = values[i - s], c = values[i], p1 = values[i + s],
                         p2 = values[i + 2 * s];
            const double back = c - m1, fore = p1 - c;
            const double back2 = std::abs(c - 2.0 * m1 + m2), fore2 = std::abs(p2 - 2.0 * p1 + c);
            if (std::abs(fore - back) < smooth) g[a] = 0.5 * (back + fore);
            else g[a] = back2 < fore2 ? back : fore;
        }
        return g;
    }
};

void fillBlock(const openvdb::FloatGrid& grid, double isovalue, Block& block)
{
    const std::size_t count = std::size_t(block.n[0]) * block.n[1] * block.n[2];
    block.values.resize(count);
    block.inside.resize(count);
    openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const Coord lo = block.min, hi = block.min + Coord(block.n[0] - 1, block.n[1] - 1, block.n[2] - 1);
    // Leaf by leaf: copy from the leaf buffer, or fill with the tile value.
    for (int lx = lo.x() & ~7; lx <= hi.x(); lx += 8) {
        for (int ly = lo.y() & ~7; ly <= hi.y(); ly += 8) {
            for (int lz = lo.z() & ~7; lz <= hi.z(); lz += 8) {
                const Coord origin(lx, ly, lz);
                const openvdb::FloatTree::LeafNodeType* leaf = accessor.probeConstLeaf(origin);
                const float tile = leaf ? 0.0f : accessor.getValue(origin);
                const int x0 = std::max(lx, lo.x()), x1 = std::min(lx + 7, hi.x());
                const int y0 = std::max(ly, lo.y()), y1 = std::min(ly + 7, hi.y());
                const int z0 = std::max(lz, lo.z()), z1 = std::min(lz + 7, hi.z());
                for (int x = x0; x <= x1; ++x) {
                    for (int y = y0; y <= y1; ++y) {
                        std::size_t i = block.at(x - lo.x(), y - lo.y(), z0 - lo.z());
                        if (leaf) {
                            const openvdb::Index base = openvdb::Index(((x & 7) << 6) | ((y & 7) << 3));
                            for (int z = z0; z <= z1; ++z, ++i) block.values[i] = leaf->getValue(base | (z & 7));
                        } else {
                            for (int z = z0; z <= z1; ++z, ++i) block.values[i] = tile;
                        }
                    }
                }
            }
        }
    }
    const float iso = float(isovalue);
    for (std::size_t i = 0; i < count; ++i) block.inside[i] = block.values[i] < iso ? 1 : 0;
}

// The 12 edges of a cell as corner pairs; corner k sits at
// (k >> 2 & 1, k >> 1 & 1, k & 1).
constexpr std::array<std::array<int, 2>, 12> CELL_EDGES = {{{0, 4}, {1, 5}, {2, 6}, {3, 7},   // x
                                                            {0, 2}, {1, 3}, {4, 6}, {5, 7},   // y
                                                            {0, 1}, {2, 3}, {4, 5}, {6, 7}}}; // z

// Surface components of a cell, per corner sign mask (bit k: corner k
// inside): which crossed edges belong to the same sheet of the surface, as
// in marching cubes. Crossed edges on one face are joined; on an ambiguous
// face (inside corners diagonal) the edges around each inside corner are
// joined, so inside corners stay apart. The rule depends on the face alone,
// so the two cells sharing a face agree, and the dual mesh is manifold.
struct ComponentTable
{
    std::int8_t component[256][12]; // -1 where the edge does not cross
    std::uint8_t count[256];
    // The one ambiguous face (0..5: x-, x+, y-, y+, z-, z+) that a single
    // sheet crosses twice (a tunnel through the face), else -1. Two such
    // cells facing each other would share a dual edge four times: both then
    // group their edges as the complement configuration does (OpenVDB's
    // correctCellSigns), which splits the sheet at that face.
    std::int8_t tunnelFace[256];

    ComponentTable()
    {
        // Corners of the faces x-, x+, y-, y+, z-, z+ in cyclic order.
        constexpr int FACES[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
        auto edgeOf = [](int a, int b) {
            for (int e = 0; e < 12; ++e) {
                if ((CELL_EDGES[e][0] == a && CELL_EDGES[e][1] == b) || (CELL_EDGES[e][0] == b && CELL_EDGES[e][1] == a)) {
                    return e;
                }
            }
            return -1;
        };
        for (int mask = 0; mask < 256; ++mask) {
            auto inside = [mask](int corner) { return (mask >> corner & 1) != 0; };
            int parent[12];
            for (int e = 0; e < 12; ++e) parent[e] = e;
            auto find = [&](int e) {
                while (parent[e] != e) e = parent[e];
                return e;
            };
            for (const auto& face : FACES) {
                int crossing[4], n = 0;
                for (int i = 0; i < 4; ++i) {
                    if (inside(face[i]) != inside(face[(i + 1) % 4])) crossing[n++] = edgeOf(face[i], face[(i + 1) % 4]);
                }
                if (n == 2) {
                    parent[find(crossing[0])] = find(crossing[1]);
                } else if (n == 4) {
                    for (int i = 0; i < 4; ++i) { // edges i-1 and i meet at corner i
                        if (!inside(face[i])) continue;
                        const int before = edgeOf(face[(i + 3) % 4], face[i]), after = edgeOf(face[i], face[(i + 1) % 4]);
                        parent[find(before)] = find(after);
                    }
                }
            }
            count[mask] = 0;
            int label[12];
            for (int e = 0; e < 12; ++e) label[e] = -1;
            for (int e = 0; e < 12; ++e) {
                component[mask][e] = -1;
                if (inside(CELL_EDGES[e][0]) == inside(CELL_EDGES[e][1])) continue;
                const int root = find(e);
                if (label[root] < 0) label[root] = count[mask]++;
                component[mask][e] = std::int8_t(label[root]);
            }
            tunnelFace[mask] = -1;
            int ambiguous = 0, tunnel = -1;
            for (int f = 0; f < 6; ++f) {
                const int* face = FACES[f];
                if (inside(face[0]) != inside(face[2]) || inside(face[1]) != inside(face[3]) ||
                    inside(face[0]) == inside(face[1])) {
                    continue; // not the diagonal pattern
                }
                ++ambiguous;
                const int first = inside(face[0]) ? 0 : 1; // the two inside corners: first, first + 2
                const int a = edgeOf(face[first], face[first + 1]), b = edgeOf(face[first + 2], face[(first + 3) % 4]);
                if (component[mask][a] == component[mask][b]) tunnel = f;
            }
            if (ambiguous == 1 && tunnel >= 0) tunnelFace[mask] = std::int8_t(tunnel);
        }
    }
};

const ComponentTable& componentTable()
{
    static const ComponentTable table;
    return table;
}

// Index in CELL_EDGES of the edge along `axis` whose lower corner sits at
// local offset (x, y, z) in {0, 1} (the offset along `axis` is ignored).
int cellEdge(int axis, int x, int y, int z)
{
    switch (axis) {
    case 0: return y * 2 + z;
    case 1: return 4 + x * 2 + z;
    default: return 8 + x * 2 + y;
    }
}

// Symmetric 3x3 eigen decomposition by cyclic Jacobi rotations
// (deterministic, fixed sweep count). Columns of `v` are the eigenvectors.
void symmetricEigen(double m[3][3], double eigenvalues[3], double v[3][3])
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) v[i][j] = i == j ? 1.0 : 0.0;
    for (int sweep = 0; sweep < 8; ++sweep) {
        const double off = m[0][1] * m[0][1] + m[0][2] * m[0][2] + m[1][2] * m[1][2];
        if (off < 1e-24) break;
        for (int p = 0; p < 2; ++p) {
            for (int q = p + 1; q < 3; ++q) {
                if (std::abs(m[p][q]) < 1e-30) continue;
                const double theta = (m[q][q] - m[p][p]) / (2.0 * m[p][q]);
                const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < 3; ++k) { // m = J^T m J
                    const double mkp = m[k][p], mkq = m[k][q];
                    m[k][p] = c * mkp - s * mkq;
                    m[k][q] = s * mkp + c * mkq;
                }
                for (int k = 0; k < 3; ++k) {
                    const double mpk = m[p][k], mqk = m[q][k];
                    m[p][k] = c * mpk - s * mqk;
                    m[q][k] = s * mpk + c * mqk;
                }
                for (int k = 0; k < 3; ++k) {
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
        }
    }
    for (int i = 0; i < 3; ++i) eigenvalues[i] = m[i][i];
}

// Internal result of one chunk: positions in index space relative to the
// chunk's first cell (exact in float: integer plus a multiple of 1/65536).
struct ChunkData
{
    Coord min;
    Coord dim; // cells per axis
    std::vector<openvdb::Vec3f> local;
    std::vector<glm::vec3> normals; // Grid or Gradient methods only
    std::vector<Coord> cells;
    std::vector<std::uint8_t> components; // which surface sheet of the cell
    std::vector<std::uint32_t> indices;

    bool onBorder(const Coord& cell) const // meshed by a neighbour chunk too
    {
        for (int a = 0; a < 3; ++a) {
            const int i = cell[a] - min[a];
            if (i == -1 || i == dim[a] - 1) return true;
        }
        return false;
    }
};

class ChunkMesher
{
public:
    ChunkMesher(const openvdb::FloatGrid& grid, const detail::DualSettings& settings)
        : mGrid(grid), mSettings(settings), mFrame(grid.transform()), mSmooth(0.1 * grid.voxelSize()[0])
    {
    }

    ChunkData mesh(const Coord& min, const Coord& dim) const;

private:
    // Cell-local vertex position in [0,1]^3 for cell (block index of its
    // first corner), and its normal if the method computes one per vertex.
    // Only the crossed edges of surface component `component` are used.
    openvdb::Vec3d place(const Block& block, std::size_t corner0, const Coord& cell, int mask, int component) const;

    const openvdb::FloatGrid& mGrid;
    const detail::DualSettings& mSettings;
    Frame mFrame;
    double mSmooth; // second differences below this are smooth (world units)
};

openvdb::Vec3d ChunkMesher::place(const Block& block, std::size_t corner0, const Coord& cell, int mask,
                                  int component) const
{
    const ComponentTable& table = componentTable();
    const double iso = mSettings.options.isovalue;
    std::size_t corner[8];
    for (int k = 0; k < 8; ++k) {
        corner[k] = corner0 + (k >> 2 & 1) * block.stride(0) + (k >> 1 & 1) * block.stride(1) + (k & 1);
    }
    openvdb::Vec3d points[12], normals[12];
    int count = 0;
    openvdb::Vec3d mean(0.0);
    const bool dual = mSettings.method == detail::DualMethod::DualContouring;
    for (int e = 0; e < 12; ++e) {
        const auto& edge = CELL_EDGES[e];
        if (table.component[mask][e] != component) continue;
        const std::size_t i0 = corner[edge[0]], i1 = corner[edge[1]];
        const double v0 = block.values[i0], v1 = block.values[i1];
        double t = std::clamp((iso - v0) / (v1 - v0), 0.0, 1.0);
        std::size_t normalAt = NO_SAMPLE; // else the sample whose side was trusted
        if (dual) {
            // Near a sharp edge the field is not linear along the grid edge
            // (the other face is nearer to the inside sample): of the
            // linear estimate and the two one-sided extrapolations, trust
            // the steepest, which is the one that does not cross a kink.
            const std::ptrdiff_t step = std::ptrdiff_t(block.stride(e / 4)) * (block.inside[i0] ? 1 : -1);
            const std::size_t in = block.inside[i0] ? i0 : i1, out = block.inside[i0] ? i1 : i0;
            const double dIn = block.values[in] - iso, dOut = block.values[out] - iso;
            const double sOut = block.values[out + step] - iso - dOut, sIn = dIn - (block.values[in - step] - iso);
            double best = dOut - dIn, u = -dIn / best;
            if (sOut > 1.001 * best && dOut / sOut <= 1.0) {
                best = sOut;
                u = 1.0 - dOut / sOut;
                normalAt = out;
            }
            if (sIn > 1.001 * best && -dIn / sIn <= 1.0) {
                u = -dIn / sIn;
                normalAt = in;
            }
            t = block.inside[i0] ? u : 1.0 - u;
        }
        const openvdb::Vec3d p0(edge[0] >> 2 & 1, edge[0] >> 1 & 1, edge[0] & 1);
        const openvdb::Vec3d p1(edge[1] >> 2 & 1, edge[1] >> 1 & 1, edge[1] & 1);
        points[count] = p0 + (p1 - p0) * t;
        mean += points[count];
        if (dual) {
            if (mSettings.options.gradient) {
                const openvdb::Vec3d ijk = openvdb::Vec3d(cell.x(), cell.y(), cell.z()) + points[count];
                normals[count] = mFrame.indexGradient(mSettings.options.gradient(mFrame.world(ijk)));
            } else if (normalAt != NO_SAMPLE) {
                normals[count] = block.enoGradient(normalAt, mSmooth);
            } else {
                normals[count] = block.enoGradient(i0, mSmooth) * (1.0 - t) + block.enoGradient(i1, mSmooth) * t;
            }
            const double len = normals[count].length();
            normals[count] = len > 1e-12 && std::isfinite(len) ? normals[count] / len : openvdb::Vec3d(0.0);
        }
        ++count;
    }
    openvdb::Vec3d p = count > 0 ? mean / double(count) : openvdb::Vec3d(0.5);

    if (mSettings.method == detail::DualMethod::DualContouring && count > 0) {
        // Minimise sum (n_i . (x - p_i))^2 about the mass point, ignoring
        // near-singular directions (there x stays at the mass point).
        double ata[3][3] = {}, atb[3] = {};
        for (int i = 0; i < count; ++i) {
            const openvdb::Vec3d& n = normals[i];
            const double d = n.dot(points[i] - p);
            for (int r = 0; r < 3; ++r) {
                atb[r] += n[r] * d;
                for (int c = 0; c < 3; ++c) ata[r][c] += n[r] * n[c];
            }
        }
        double lambda[3], v[3][3];
        symmetricEigen(ata, lambda, v);
        const double largest = std::max({std::abs(lambda[0]), std::abs(lambda[1]), std::abs(lambda[2])});
        openvdb::Vec3d x(0.0);
        for (int e = 0; e < 3; ++e) {
            if (largest <= 0.0 || std::abs(lambda[e]) < mSettings.singularThreshold * largest) continue;
            const double proj = (v[0][e] * atb[0] + v[1][e] * atb[1] + v[2][e] * atb[2]) / lambda[e];
            for (int r = 0; r < 3; ++r) x[r] += v[r][e] * proj;
        }
        p += x;
    }

    const int steps = mSettings.options.projectionSteps;
    for (int s = 0; s < steps; ++s) {
        const double f = block.sample(corner0, p) - iso;
        const openvdb::Vec3d g = block.gradient(corner0, p);
        const double g2 = g.lengthSqr();
        if (!(g2 > 1e-12)) break;
        p -= g * (f / g2);
        for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], 0.0, 1.0);
    }
    for (int a = 0; a < 3; ++a) p[a] = std::floor(std::clamp(p[a], 0.0, 1.0) * QUANTUM + 0.5) / QUANTUM;
    return p;
}

ChunkData ChunkMesher::mesh(const Coord& min, const Coord& dim) const
{
    ChunkData out;
    out.min = min;
    out.dim = dim;

    Block block;
    block.min = min - Coord(APRON);
    for (int a = 0; a < 3; ++a) block.n[a] = dim[a] + 2 * APRON;
    fillBlock(mGrid, mSettings.options.isovalue, block);

    // Vertices of each cell in [min - 1, min + dim), one per surface
    // component, created on first use: cellSlot indexes `slots`.
    const int cx = dim[0] + 1, cy = dim[1] + 1, cz = dim[2] + 1;
    std::vector<std::uint32_t> cellSlot(std::size_t(cx) * cy * cz, UNSET);
    std::vector<std::array<std::uint32_t, 5>> slots; // 4 vertices, then the corner signs
    const NormalMethod normalMethod = mSettings.options.normals;
    const bool perVertexNormals = normalMethod == NormalMethod::Grid || normalMethod == NormalMethod::Gradient;
    const ComponentTable& table = componentTable();
    const std::size_t sx = block.stride(0), sy = block.stride(1);

    // The vertex of cell (i, j, k) relative to `min` (i in [-1, dim)) on
    // the surface sheet through its edge `edge`.
    auto vertexOf = [&](int i, int j, int k, int edge) -> std::uint32_t {
        const std::size_t corner0 = block.at(i + APRON, j + APRON, k + APRON);
        std::uint32_t& slotIndex = cellSlot[(std::size_t(i + 1) * cy + (j + 1)) * cz + (k + 1)];
        if (slotIndex == UNSET) { // first visit: the corner signs, once per cell
            auto signsAt = [&](std::size_t first) {
                int signs = 0;
                for (int c = 0; c < 8; ++c) {
                    signs |= block.inside[first + (c >> 2 & 1) * sx + (c >> 1 & 1) * sy + (c & 1)] << c;
                }
                return signs;
            };
            int signs = signsAt(corner0);
            const int face = table.tunnelFace[signs];
            if (face >= 0) {
                // The neighbour across that face (inside the block: the apron
                // leaves room for one more cell on each side).
                const int axis = face / 2;
                const std::ptrdiff_t step = std::ptrdiff_t(block.stride(axis)) * (face % 2 ? 1 : -1);
                if (table.tunnelFace[signsAt(std::size_t(std::ptrdiff_t(corner0) + step))] == (face ^ 1)) {
                    signs = ~signs & 0xff; // group as the complement does
                }
            }
            slotIndex = std::uint32_t(slots.size());
            slots.push_back({UNSET, UNSET, UNSET, UNSET, std::uint32_t(signs)});
        }
        const int mask = int(slots[slotIndex][4]);
        const int component = table.component[mask][edge];
        std::uint32_t& vertex = slots[slotIndex][std::size_t(component)];
        if (vertex != UNSET) return vertex;
        vertex = std::uint32_t(out.local.size());
        const Coord cell = min + Coord(i, j, k);
        const openvdb::Vec3d p = place(block, corner0, cell, mask, component);
        out.local.emplace_back(float(i + p[0]), float(j + p[1]), float(k + p[2]));
        out.cells.push_back(cell);
        out.components.push_back(std::uint8_t(component));
        if (perVertexNormals) {
            glm::dvec3 g;
            if (normalMethod == NormalMethod::Gradient) {
                g = mSettings.options.gradient(mFrame.world(openvdb::Vec3d(cell.x(), cell.y(), cell.z()) + p));
            } else {
                g = mFrame.worldGradient(block.gradient(corner0, p));
            }
            const glm::vec3 n(g);
            const float len2 = glm::dot(n, n);
            // Zero marks a vanished gradient; assembly replaces it.
            out.normals.push_back(len2 > MIN_LENGTH2 && std::isfinite(len2) ? n / std::sqrt(len2) : glm::vec3(0.0f));
        }
        return vertex;
    };

    auto emitQuad = [&](std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
        // Split along the shorter diagonal (ties: q0-q2), deterministic.
        const float d02 = (out.local[q0] - out.local[q2]).lengthSqr();
        const float d13 = (out.local[q1] - out.local[q3]).lengthSqr();
        if (d02 <= d13) {
            out.indices.insert(out.indices.end(), {q0, q1, q2, q0, q2, q3});
        } else {
            out.indices.insert(out.indices.end(), {q1, q2, q3, q1, q3, q0});
        }
    };

    // One quad per owned edge (lower voxel inside the chunk) that crosses.
    for (int x = 0; x < dim[0]; ++x) {
        for (int y = 0; y < dim[1]; ++y) {
            std::size_t b = block.at(x + APRON, y + APRON, APRON);
            for (int z = 0; z < dim[2]; ++z, ++b) {
                const std::uint8_t s = block.inside[b];
                const std::size_t strides[3] = {sx, sy, 1};
                // Most voxels cross nothing: one test for all three edges.
                if (block.inside[b + sx] == s && block.inside[b + sy] == s && block.inside[b + 1] == s) continue;
                for (int a = 0; a < 3; ++a) {
                    if (block.inside[b + strides[a]] == s) continue;
                    const int ab = (a + 1) % 3, ac = (a + 2) % 3;
                    // The four cells around the edge, and the edge's place
                    // in each: offsets (along b, along c) of 1 or 0.
                    auto around = [&](int db, int dc) {
                        int c[3] = {x, y, z}, local[3] = {0, 0, 0};
                        c[ab] -= db;
                        c[ac] -= dc;
                        local[ab] = db;
                        local[ac] = dc;
                        return vertexOf(c[0], c[1], c[2], cellEdge(a, local[0], local[1], local[2]));
                    };
                    const std::uint32_t q00 = around(1, 1), q10 = around(0, 1), q11 = around(0, 0), q01 = around(1, 0);
                    // Inside at the lower voxel: the surface faces +a, and
                    // (b, c) is counter-clockwise seen from +a.
                    if (s) emitQuad(q00, q10, q11, q01);
                    else emitQuad(q00, q01, q11, q10);
                }
            }
        }
    }
    return out;
}

std::vector<Coord> chunksOf(const openvdb::FloatGrid& grid, int chunkSize)
{
    std::vector<Coord> chunks;
    auto floorDiv = [chunkSize](int v) { return v >= 0 ? v / chunkSize : -((-v + chunkSize - 1) / chunkSize); };
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const Coord origin = leaf->origin();
        // Cells touching this leaf lie in [origin - 1, origin + 7].
        for (int k = 0; k < 8; ++k) {
            const Coord c(origin.x() - (k >> 2 & 1), origin.y() - (k >> 1 & 1), origin.z() - (k & 1));
            chunks.emplace_back(floorDiv(c.x()) * chunkSize, floorDiv(c.y()) * chunkSize, floorDiv(c.z()) * chunkSize);
        }
    }
    std::sort(chunks.begin(), chunks.end());
    chunks.erase(std::unique(chunks.begin(), chunks.end()), chunks.end());
    return chunks;
}

// Replaces the zero normals (vanished gradients) by face normals.
void repairNormals(TriangleMesh& mesh)
{
    bool any = false;
    for (const glm::vec3& n : mesh.normals) any |= n == glm::vec3(0.0f);
    if (!any) return;
    TriangleMesh faces = mesh;
    computeFaceNormals(faces);
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
        if (mesh.normals[i] == glm::vec3(0.0f)) mesh.normals[i] = faces.normals[i];
    }
}

} // namespace

namespace detail {

void validate(const DualSettings& settings)
{
    const ChunkMeshOptions& o = settings.options;
    if (!std::isfinite(o.isovalue)) {
        throw Error("meshing: isovalue = " + std::to_string(o.isovalue) + " must be finite");
    }
    if (o.chunkSize != 0 && (o.chunkSize < 8 || o.chunkSize > 512 || o.chunkSize % 8 != 0)) {
        throw Error("meshing: chunk size " + std::to_string(o.chunkSize) +
                    " must be 0 (one chunk) or a multiple of 8 in [8, 512]");
    }
    if (!std::isfinite(o.origin.x) || !std::isfinite(o.origin.y) || !std::isfinite(o.origin.z)) {
        throw Error("meshing: origin must be finite");
    }
    if (o.normals == NormalMethod::Gradient && !o.gradient) {
        throw Error("meshing: normals = gradient needs a gradient function");
    }
    if (o.projectionSteps < 0 || o.projectionSteps > 16) {
        throw Error("meshing: projection steps " + std::to_string(o.projectionSteps) + " must be in [0, 16]");
    }
    if (!(settings.singularThreshold > 0.0 && settings.singularThreshold < 1.0)) {
        throw Error("meshing: QEF singular threshold " + std::to_string(settings.singularThreshold) +
                    " must be in (0, 1)");
    }
}

static void requireLinear(const openvdb::FloatGrid& grid)
{
    if (!grid.transform().isLinear()) {
        throw Error("meshing: grid '" + grid.getName() + "' needs a linear transform (got '" +
                    grid.transform().mapType() + "')");
    }
}

ChunkMesh meshChunk(const openvdb::FloatGrid& grid, const Coord& chunkMin, const DualSettings& settings)
{
    requireLinear(grid);
    const int n = settings.options.chunkSize == 0 ? 32 : settings.options.chunkSize;
    for (int a = 0; a < 3; ++a) {
        if (chunkMin[a] % n != 0) {
            throw Error("meshing: chunk minimum (" + std::to_string(chunkMin.x()) + ", " +
                        std::to_string(chunkMin.y()) + ", " + std::to_string(chunkMin.z()) +
                        ") is not a multiple of the chunk size " + std::to_string(n));
        }
    }
    const Frame frame(grid.transform());
    ChunkData data = ChunkMesher(grid, settings).mesh(chunkMin, Coord(n));
    ChunkMesh chunk;
    chunk.chunkMin = chunkMin;
    chunk.mesh.origin = frame.world(openvdb::Vec3d(chunkMin.x(), chunkMin.y(), chunkMin.z()));
    chunk.mesh.positions.reserve(data.local.size());
    for (const openvdb::Vec3f& p : data.local) chunk.mesh.positions.emplace_back(frame.offset(p));
    chunk.mesh.indices = std::move(data.indices);
    chunk.mesh.normals = std::move(data.normals);
    chunk.cells = std::move(data.cells);
    chunk.components = std::move(data.components);
    if (settings.options.normals == NormalMethod::Face) computeFaceNormals(chunk.mesh);
    else repairNormals(chunk.mesh);
    return chunk;
}

TriangleMesh meshChunks(const openvdb::FloatGrid& grid, const DualSettings& settings)
{
    requireLinear(grid);
    const ChunkMeshOptions& options = settings.options;
    std::vector<Coord> mins, dims;
    if (options.chunkSize == 0) {
        openvdb::CoordBBox box;
        if (grid.tree().evalLeafBoundingBox(box)) {
            mins.push_back(box.min() - Coord(1));
            dims.push_back(box.dim() + Coord(1));
        }
    } else {
        mins = chunksOf(grid, options.chunkSize);
        dims.assign(mins.size(), Coord(options.chunkSize));
    }

    std::vector<ChunkData> chunks(mins.size());
    const ChunkMesher mesher(grid, settings);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, mins.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t c = r.begin(); c != r.end(); ++c) chunks[c] = mesher.mesh(mins[c], dims[c]);
    });

    // Weld the border vertices: a cell meshed by several chunks keeps the
    // vertex of the first chunk (in chunk order) that uses it.
    struct BorderEntry
    {
        Coord cell;
        std::uint8_t component;
        std::uint32_t chunk, vertex;
        bool sameVertex(const BorderEntry& o) const { return cell == o.cell && component == o.component; }
        bool operator<(const BorderEntry& o) const
        {
            if (cell != o.cell) return cell < o.cell;
            return component != o.component ? component < o.component : chunk < o.chunk;
        }
    };
    std::vector<BorderEntry> border;
    for (std::uint32_t c = 0; c < chunks.size(); ++c) {
        for (std::uint32_t v = 0; v < chunks[c].cells.size(); ++v) {
            if (chunks[c].onBorder(chunks[c].cells[v])) {
                border.push_back({chunks[c].cells[v], chunks[c].components[v], c, v});
            }
        }
    }
    std::sort(border.begin(), border.end());
    std::vector<std::vector<std::uint32_t>> global(chunks.size());
    for (std::size_t c = 0; c < chunks.size(); ++c) global[c].assign(chunks[c].local.size(), UNSET);
    // Non-first users point at the first user: marked by its (chunk, vertex).
    std::vector<std::vector<std::pair<std::uint32_t, std::uint32_t>>> alias(chunks.size());
    for (std::size_t c = 0; c < chunks.size(); ++c) alias[c].assign(chunks[c].local.size(), {UNSET, UNSET});
    for (std::size_t i = 0, first = 0; i < border.size(); ++i) {
        if (i == 0 || !border[i].sameVertex(border[i - 1])) first = i;
        else alias[border[i].chunk][border[i].vertex] = {border[first].chunk, border[first].vertex};
    }

    const Frame frame(grid.transform());
    TriangleMesh mesh;
    mesh.origin = options.origin;
    const bool withNormals = options.normals == NormalMethod::Grid || options.normals == NormalMethod::Gradient;
    std::size_t triangles = 0;
    for (const ChunkData& chunk : chunks) triangles += chunk.indices.size();
    mesh.indices.reserve(triangles);
    for (std::size_t c = 0; c < chunks.size(); ++c) {
        const ChunkData& chunk = chunks[c];
        for (std::size_t v = 0; v < chunk.local.size(); ++v) {
            const auto [ac, av] = alias[c][v];
            if (ac != UNSET) {
                global[c][v] = global[ac][av];
                continue;
            }
            global[c][v] = std::uint32_t(mesh.positions.size());
            const openvdb::Vec3d ijk = openvdb::Vec3d(chunk.min.x(), chunk.min.y(), chunk.min.z()) +
                                       openvdb::Vec3d(chunk.local[v]);
            mesh.positions.emplace_back(frame.world(ijk) - options.origin);
            if (withNormals) mesh.normals.push_back(chunk.normals[v]);
        }
        for (std::uint32_t i : chunk.indices) mesh.indices.push_back(global[c][i]);
    }
    if (options.normals == NormalMethod::Face) computeFaceNormals(mesh);
    else repairNormals(mesh);
    return mesh;
}

} // namespace detail

std::vector<Coord> listChunks(const openvdb::FloatGrid& grid, int chunkSize)
{
    if (chunkSize < 8 || chunkSize > 512 || chunkSize % 8 != 0) {
        throw Error("meshing: chunk size " + std::to_string(chunkSize) + " must be a multiple of 8 in [8, 512]");
    }
    return chunksOf(grid, chunkSize);
}

} // namespace strata::meshing
