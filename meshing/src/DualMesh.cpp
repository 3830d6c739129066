// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/DualMesh.h>

#include <strata/IntegerMath.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace strata::meshing {

namespace {

constexpr std::uint32_t UNSET = 0xffffffffu;
constexpr int NO_SAMPLE = -1;

// Inside this file corners and edges of a cell use one numbering: corner k
// sits at (k >> 2 & 1, k >> 1 & 1, k & 1), and these are the 12 edges as
// corner pairs. Visiting orders (memory order of the samples) are tables
// into it, built per call.
constexpr int CELL_EDGES[12][2] = {{0, 4}, {1, 5}, {2, 6}, {3, 7},  // x
                                   {0, 2}, {1, 3}, {4, 6}, {5, 7},  // y
                                   {0, 1}, {2, 3}, {4, 5}, {6, 7}}; // z

// Bit i (i < n <= 16): the samples at row[i] and row[i + offset] differ,
// i.e. the lattice edge from row + i towards row + i + offset crosses.
unsigned crossings(const std::uint8_t* row, std::ptrdiff_t offset, int n)
{
#if defined(__SSE2__)
    if (n == 16) {
        const __m128i s = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row));
        const __m128i o = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + offset));
        return unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(s, o))) ^ 0xffffu;
    }
#endif
    unsigned bits = 0;
    for (int i = 0; i < n; ++i) bits |= unsigned(row[i] != row[i + offset]) << i;
    return bits;
}

// Set bits of a 16-bit mask (std::popcount is a library call without POPCNT).
int popcount16(unsigned x)
{
    x = x - ((x >> 1) & 0x5555u);
    x = (x & 0x3333u) + ((x >> 2) & 0x3333u);
    x = (x + (x >> 4)) & 0x0f0fu;
    return int((x + (x >> 8)) & 0x1fu);
}

// Per edge of CELL_EDGES: its corners, axis and the position of corner k0.
struct EdgeCorner
{
    int k0, k1, axis;
    double at[3];
};

constexpr std::array<EdgeCorner, 12> edgeCorners()
{
    std::array<EdgeCorner, 12> table{};
    for (int e = 0; e < 12; ++e) {
        const int k0 = CELL_EDGES[e][0];
        table[std::size_t(e)] = {k0, CELL_EDGES[e][1], e / 4, {double(k0 >> 2 & 1), double(k0 >> 1 & 1), double(k0 & 1)}};
    }
    return table;
}

constexpr std::array<EdgeCorner, 12> EDGE_CORNERS = edgeCorners();

int cornerAt(const int o[3])
{
    return o[0] << 2 | o[1] << 1 | o[2];
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
    std::uint16_t edges[256][4]; // per component, its edges (bit e: edge e)
    std::uint16_t crossed[256];  // all crossed edges
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
            crossed[mask] = 0;
            for (std::uint16_t& bits : edges[mask]) bits = 0;
            for (int e = 0; e < 12; ++e) {
                component[mask][e] = -1;
                if (inside(CELL_EDGES[e][0]) == inside(CELL_EDGES[e][1])) continue;
                const int root = find(e);
                if (label[root] < 0) label[root] = count[mask]++;
                component[mask][e] = std::int8_t(label[root]);
                edges[mask][label[root]] |= std::uint16_t(1 << e);
                crossed[mask] |= std::uint16_t(1 << e);
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

// The walker's buffers, kept per thread from one chunk to the next.
// Allocated and freed per chunk, they made the allocator return pages to the
// system and fault them in again (a third of the time went to the kernel).
// A buffer larger than KEEP_BYTES (a 64^3 chunk needs about 1 MB) is freed,
// so one huge chunk does not pin its memory to a thread.
struct WalkerScratch
{
    static constexpr std::size_t KEEP_BYTES = std::size_t(16) << 20;
    std::unique_ptr<std::uint8_t[]> inside;
    std::size_t insideCapacity = 0;
    std::vector<std::uint32_t> cellSlot;
    std::vector<std::array<std::uint32_t, 5>> slots;
    std::vector<glm::vec3> chunkPosition;
    bool busy = false; // in use further up this thread's stack (a callback that meshes)
};

WalkerScratch& threadScratch()
{
    thread_local WalkerScratch scratch;
    return scratch;
}

template <class T> void keep(std::vector<T>& from, std::vector<T>& to)
{
    from.clear();
    if (from.capacity() * sizeof(T) <= WalkerScratch::KEEP_BYTES) to = std::move(from);
}

class Walker
{
public:
    Walker(const DualSamples& samples, const DualMeshSettings& settings, DualMeshResult&& reuse)
        : mS(samples)
        , mP(settings)
        , mTable(componentTable())
        , mOut(std::move(reuse))
    {
        mOut.vertices.clear();
        mOut.positions.clear();
        mOut.gradients.clear();
        mOut.indices.clear();
        WalkerScratch& scratch = threadScratch();
        if (!scratch.busy) {
            mScratch = &scratch;
            scratch.busy = true;
            mInside = std::move(scratch.inside);
            mInsideCapacity = std::exchange(scratch.insideCapacity, 0);
            mCellSlot = std::move(scratch.cellSlot);
            mSlots = std::move(scratch.slots);
            mSlots.clear();
            mChunkPosition = std::move(scratch.chunkPosition);
            mChunkPosition.clear();
        }
        assert(mS.values);
        assert(mS.apron >= 2);
        for (int a = 0; a < 3; ++a) assert(mS.size[a] - mS.apron >= mS.cells[a] + 1);
        // Memory order: perm[0] has the largest stride (outermost loop);
        // axis a is bit mBit[a] of the memory-order corner numbering.
        int perm[3] = {0, 1, 2};
        std::sort(perm, perm + 3, [&](int a, int b) { return mS.stride[a] > mS.stride[b]; });
        for (int i = 0; i < 3; ++i) {
            mOuter[i] = perm[i];
            mBit[perm[i]] = 2 - i;
        }
        for (int m = 0; m < 8; ++m) {
            int o[3];
            for (int a = 0; a < 3; ++a) o[a] = m >> mBit[a] & 1;
            mCornerOrder[m] = cornerAt(o);
        }
        int n = 0;
        for (int a = 0; a < 3; ++a) {
            for (int m = 0; m < 8; ++m) {
                if (m >> mBit[a] & 1) continue;
                int o[3];
                for (int b = 0; b < 3; ++b) o[b] = m >> mBit[b] & 1;
                mEdgeOrder[n++] = cellEdge(a, o[0], o[1], o[2]);
            }
        }
        for (int half = 0; half < 2; ++half) {
            for (int bits = 0; bits < 64; ++bits) {
                mMemoryOrderBits[half][bits] = 0;
                for (int m = 0; m < 12; ++m)
                    if ((bits << 6 * half) >> mEdgeOrder[m] & 1) mMemoryOrderBits[half][bits] |= std::uint16_t(1 << m);
            }
        }
        for (int k = 0; k < 8; ++k) {
            const std::ptrdiff_t d[3] = {k >> 2 & 1, k >> 1 & 1, k & 1};
            mCornerOffset[k] = d[0] * mS.stride[0] + d[1] * mS.stride[1] + d[2] * mS.stride[2];
        }
        const std::ptrdiff_t slotStride[3] = {std::ptrdiff_t(mS.cells[1] + 1) * (mS.cells[2] + 1), mS.cells[2] + 1, 1};
        for (int a = 0; a < 3; ++a) {
            const int b = (a + 1) % 3, c = (a + 2) % 3;
            for (int i = 0; i < 4; ++i) { // the cells at (-1, -1), (0, -1), (0, 0), (-1, 0) across the edge in (b, c)
                const int db = i == 0 || i == 3 ? 1 : 0, dc = i < 2 ? 1 : 0;
                OwnCorner& corner = mOwnCorners[a][i];
                for (int k = 0; k < 3; ++k) corner.delta[k] = 0;
                corner.delta[b] = db;
                corner.delta[c] = dc;
                corner.slot = -(db * slotStride[b] + dc * slotStride[c]);
                corner.edge = cellEdge(a, corner.delta[0], corner.delta[1], corner.delta[2]);
            }
        }
        mAnyFiner = mAnyLevel = false;
        for (int m = 1; m < 8; ++m) {
            mAnyFiner = mAnyFiner || mS.signature[m] < 0;
            mAnyLevel = mAnyLevel || mS.signature[m] != 0;
        }
        assert(!mAnyFiner || mS.fine);
        assert(!mAnyLevel || (mP.sheets == DualSheets::One && mP.placement == DualPlacement::SurfaceNets));
        mIso = float(mP.isovalue);
        mQuantum = mP.quantum;
        // Dividing by a power of two is multiplying by its exact inverse.
        int exponent = 0;
        if (mQuantum > 0.0 && std::frexp(mQuantum, &exponent) == 0.5) mQuantumInverse = std::ldexp(1.0, 1 - exponent);
        if (!std::isfinite(mQuantumInverse)) mQuantumInverse = 0.0;
    }

    ~Walker()
    {
        if (!mScratch) return;
        if (mInsideCapacity <= WalkerScratch::KEEP_BYTES) {
            mScratch->inside = std::move(mInside);
            mScratch->insideCapacity = mInsideCapacity;
        }
        keep(mCellSlot, mScratch->cellSlot);
        keep(mSlots, mScratch->slots);
        keep(mChunkPosition, mScratch->chunkPosition);
        mScratch->busy = false;
    }

    Walker(const Walker&) = delete;
    Walker& operator=(const Walker&) = delete;

    DualMeshResult run()
    {
        fillInside();
        const int cx = mS.cells[0] + 1, cy = mS.cells[1] + 1, cz = mS.cells[2] + 1;
        mCellSlot.assign(std::size_t(cx) * cy * cz, UNSET);

        // One polygon per owned edge that crosses, lattice points in memory order.
        const int u0 = mOuter[0], u1 = mOuter[1], u2 = mOuter[2];
        const std::ptrdiff_t sx = mS.stride[0], sy = mS.stride[1], sz = mS.stride[2];
        const std::ptrdiff_t strides[3] = {sx, sy, sz};
        const std::uint8_t* inside = mInside.get();
        const int n0 = mS.cells[u0], n1 = mS.cells[u1], n2 = mS.cells[u2];
        const std::ptrdiff_t step = strides[u2];
        int p[3];
        if (!mAnyLevel && step == 1) {
            walkOwnLevel();
            return std::move(mOut);
        }
        for (int i0 = 0; i0 < n0; ++i0) {
            for (int i1 = 0; i1 < n1; ++i1) {
                p[u0] = i0;
                p[u1] = i1;
                p[u2] = 0;
                const std::uint8_t* row = inside + dense(p[0], p[1], p[2]);
                for (int i2 = 0; i2 < n2; ++i2, row += step) {
                    const std::uint8_t s = row[0];
                    // Most points cross nothing: one test for all three edges.
                    if (row[sx] == s && row[sy] == s && row[sz] == s) continue;
                    p[u2] = i2;
                    for (int a = 0; a < 3; ++a) {
                        if (row[strides[a]] == s) continue;
                        if (!mAnyLevel) {
                            ownPolygon(a, p, s != 0);
                            continue;
                        }
                        if (minNeighbourLevel(p, a) < 0) continue; // subdivided by a finer neighbour
                        const std::int64_t q[3] = {2 * p[0], 2 * p[1], 2 * p[2]};
                        polygon(a, q, 2, s != 0);
                    }
                }
            }
        }
        // The seam with finer lower neighbours: their edges on this chunk's
        // lower faces (fine lattice points with a coordinate 0).
        if (mAnyFiner) {
            for (p[u0] = 0; p[u0] < 2 * mS.cells[u0]; ++p[u0]) {
                for (p[u1] = 0; p[u1] < 2 * mS.cells[u1]; ++p[u1]) {
                    const bool all = p[u0] == 0 || p[u1] == 0;
                    for (p[u2] = 0; p[u2] < 2 * mS.cells[u2]; p[u2] = all ? p[u2] + 1 : 2 * mS.cells[u2]) {
                        for (int a = 0; a < 3; ++a) {
                            if (minNeighbourLevel(p, a) != -1) continue;
                            int e[3] = {p[0], p[1], p[2]};
                            ++e[a];
                            const float v0 = mS.fine(p[0], p[1], p[2]), v1 = mS.fine(e[0], e[1], e[2]);
                            if ((v0 < mIso) == (v1 < mIso)) continue;
                            const std::int64_t q[3] = {p[0], p[1], p[2]};
                            polygon(a, q, 1, v0 < mIso);
                        }
                    }
                }
            }
        }
        return std::move(mOut);
    }

private:
    /// The walk of run() when every neighbour has the chunk's level and rows
    /// are contiguous: 16 lattice points at a time, the crossing edges as
    /// bit masks, counted first to size the outputs; then the polygons in
    /// the same order (points in memory order, axes 0, 1, 2 per point).
    void walkOwnLevel()
    {
        const int u0 = mOuter[0], u1 = mOuter[1], u2 = mOuter[2];
        const std::ptrdiff_t strides[3] = {mS.stride[0], mS.stride[1], mS.stride[2]};
        const std::uint8_t* inside = mInside.get();
        const int n0 = mS.cells[u0], n1 = mS.cells[u1], n2 = mS.cells[u2];
        auto rowAt = [&](int i0, int i1) {
            int p[3];
            p[u0] = i0;
            p[u1] = i1;
            p[u2] = 0;
            return inside + dense(p[0], p[1], p[2]);
        };
        std::size_t edges = 0;
        for (int i0 = 0; i0 < n0; ++i0) {
            for (int i1 = 0; i1 < n1; ++i1) {
                const std::uint8_t* row = rowAt(i0, i1);
                for (int i2 = 0; i2 < n2; i2 += 16) {
                    const int n = std::min(16, n2 - i2);
                    for (int a = 0; a < 3; ++a) edges += std::size_t(popcount16(crossings(row + i2, strides[a], n)));
                }
            }
        }
        // One quad per edge; about as many vertices (cells) as quads, more
        // in small chunks (the apron cells): growth past this is only slower.
        mOut.indices.reserve(6 * edges);
        const std::size_t vertices = edges + edges / 2 + 64;
        mOut.positions.reserve(vertices);
        mOut.vertices.reserve(vertices);
        if (mP.gradients != DualGradient::None) mOut.gradients.reserve(vertices);
        if (mP.split == DualQuadSplit::ShorterDiagonal) mChunkPosition.reserve(vertices);
        mSlots.reserve(vertices);

        int p[3];
        for (int i0 = 0; i0 < n0; ++i0) {
            for (int i1 = 0; i1 < n1; ++i1) {
                p[u0] = i0;
                p[u1] = i1;
                const std::uint8_t* row = rowAt(i0, i1);
                for (int i2 = 0; i2 < n2; i2 += 16) {
                    const int n = std::min(16, n2 - i2);
                    const unsigned cross[3] = {crossings(row + i2, strides[0], n), crossings(row + i2, strides[1], n),
                                               crossings(row + i2, strides[2], n)};
                    for (unsigned any = cross[0] | cross[1] | cross[2]; any != 0; any &= any - 1) {
                        const int i = std::countr_zero(any);
                        p[u2] = i2 + i;
                        const bool lowerInside = row[i2 + i] != 0;
                        for (int a = 0; a < 3; ++a)
                            if (cross[a] >> i & 1) ownPolygon(a, p, lowerInside);
                    }
                }
            }
        }
    }

    std::size_t dense(std::int64_t x, std::int64_t y, std::int64_t z) const
    {
        return std::size_t((x + mS.apron) * mS.stride[0] + (y + mS.apron) * mS.stride[1] +
                           (z + mS.apron) * mS.stride[2]);
    }

    void fillInside()
    {
        std::size_t count = 1;
        for (int a = 0; a < 3; ++a) count += std::size_t(mS.size[a] - 1) * std::size_t(mS.stride[a]);
        // Dense layouts (no gaps between rows) are written in full below.
        std::size_t points = 1;
        for (int a = 0; a < 3; ++a) points *= std::size_t(mS.size[a]);
        if (count > mInsideCapacity) {
            mInside.reset(new std::uint8_t[count]);
            mInsideCapacity = count;
        }
        if (points != count) std::fill(mInside.get(), mInside.get() + count, std::uint8_t(0));
        // Memory order: rows along the axis of the smallest stride.
        const int u0 = mOuter[0], u1 = mOuter[1], u2 = mOuter[2];
        const std::ptrdiff_t step = mS.stride[u2];
        const float iso = mIso;
        for (int i0 = 0; i0 < mS.size[u0]; ++i0)
            for (int i1 = 0; i1 < mS.size[u1]; ++i1) {
                const std::ptrdiff_t first = i0 * mS.stride[u0] + i1 * mS.stride[u1];
                const float* from = mS.values + first;
                std::uint8_t* to = mInside.get() + first;
                const int n = mS.size[u2];
                if (step == 1) {
                    int i2 = 0;
#if defined(__SSE2__)
                    const __m128 isoV = _mm_set1_ps(iso);
                    for (; i2 + 16 <= n; i2 += 16) { // NaN compares false, as below
                        const __m128i a = _mm_castps_si128(_mm_cmplt_ps(_mm_loadu_ps(from + i2), isoV));
                        const __m128i b = _mm_castps_si128(_mm_cmplt_ps(_mm_loadu_ps(from + i2 + 4), isoV));
                        const __m128i c = _mm_castps_si128(_mm_cmplt_ps(_mm_loadu_ps(from + i2 + 8), isoV));
                        const __m128i d = _mm_castps_si128(_mm_cmplt_ps(_mm_loadu_ps(from + i2 + 12), isoV));
                        const __m128i bytes = _mm_packs_epi16(_mm_packs_epi32(a, b), _mm_packs_epi32(c, d));
                        _mm_storeu_si128(reinterpret_cast<__m128i*>(to + i2), _mm_and_si128(bytes, _mm_set1_epi8(1)));
                    }
#endif
                    for (; i2 < n; ++i2) to[i2] = from[i2] < iso ? 1 : 0;
                } else {
                    for (int i2 = 0; i2 < n; ++i2) to[i2 * step] = from[i2 * step] < iso ? 1 : 0;
                }
            }
    }

    /// The level (relative to this chunk's) of the finest chunk touching the
    /// edge from p along axis a; in {-1, 0} (the scale of p does not matter).
    int minNeighbourLevel(const int p[3], int a) const
    {
        int face = 0;
        for (int b = 0; b < 3; ++b)
            if (b != a && p[b] == 0) face |= 1 << b;
        int level = 0;
        for (int sub = face; sub; sub = (sub - 1) & face) level = std::min(level, int(mS.signature[sub]));
        return level;
    }

    /// The polygon around the edge from q along a, length h: q and h in fine
    /// lattice units (an own-level cell is 2), lowerInside the sign at q.
    void polygon(int a, const std::int64_t p[3], std::int64_t h, bool lowerInside)
    {
        static const int SB[4] = {-1, 1, 1, -1};
        static const int SC[4] = {-1, -1, 1, 1};
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        std::uint32_t corners[4];
        for (int i = 0; i < 4; ++i) {
            std::int64_t q[3] = {2 * p[0], 2 * p[1], 2 * p[2]}; // half fine units
            q[a] += h;
            q[b] += SB[i] * h;
            q[c] += SC[i] * h;
            const int mask = (q[0] < 0 ? 1 : 0) | (q[1] < 0 ? 2 : 0) | (q[2] < 0 ? 4 : 0);
            const int level = mS.signature[mask];
            // Cells are 2^(level + 2) half fine units: floor division by a shift.
            const int shift = level + 2;
            const int cell[3] = {int(q[0] >> shift), int(q[1] >> shift), int(q[2] >> shift)};
            int local[3] = {0, 0, 0}; // the edge's place in the cell (own level only)
            local[b] = SB[i] < 0;
            local[c] = SC[i] < 0;
            corners[i] = vertexOf(level, cell, cellEdge(a, local[0], local[1], local[2]));
        }
        emit(corners, lowerInside);
    }

    /// polygon() for an own-level edge from lattice point p along a when every
    /// neighbour has the chunk's level (the same cells, without the levels).
    void ownPolygon(int a, const int p[3], bool lowerInside)
    {
        const std::size_t slot0 = slotOf(p);
        std::uint32_t corners[4];
        for (int i = 0; i < 4; ++i) {
            const OwnCorner& corner = mOwnCorners[a][i];
            std::uint32_t& slot = mCellSlot[std::size_t(std::ptrdiff_t(slot0) + corner.slot)];
            if (slot != UNSET) { // the common case: the cell's vertices exist
                const std::uint32_t vertex = mSlots[slot][std::size_t(sheetOf(int(mSlots[slot][4]), corner.edge))];
                if (vertex != UNSET) {
                    corners[i] = vertex;
                    continue;
                }
            }
            const int cell[3] = {p[0] - corner.delta[0], p[1] - corner.delta[1], p[2] - corner.delta[2]};
            corners[i] = ownVertex(cell, corner.edge);
        }
        // Four distinct cells: always a quad.
        const std::uint32_t q0 = corners[0], q1 = lowerInside ? corners[1] : corners[3], q2 = corners[2],
                            q3 = lowerInside ? corners[3] : corners[1];
        emitQuad(q0, q1, q2, q3, lowerInside);
    }

    std::size_t slotOf(const int cell[3]) const
    {
        const int cy = mS.cells[1] + 1, cz = mS.cells[2] + 1;
        return (std::size_t(cell[0] + 1) * cy + (cell[1] + 1)) * cz + (cell[2] + 1);
    }

    int sheetOf(int mask, int edge) const
    {
        return mP.sheets == DualSheets::Separate ? mTable.component[mask][edge] : 0;
    }

    /// The polygon through the vertices of the four cells around an edge.
    void emit(const std::uint32_t (&corners)[4], bool lowerInside)
    {
        // Two cells around the edge may be the same coarse cell: a triangle.
        std::uint32_t poly[4];
        int n = 0;
        for (std::uint32_t v : corners)
            if (n == 0 || poly[n - 1] != v) poly[n++] = v;
        if (n > 1 && poly[n - 1] == poly[0]) --n;
        if (n < 3) return;
        std::vector<std::uint32_t>& idx = mOut.indices;
        if (n == 3) {
            if (!lowerInside) std::reverse(poly, poly + 3);
            idx.insert(idx.end(), {poly[0], poly[1], poly[2]});
            return;
        }
        // Counter-clockwise seen from outside: inside at the lower end means
        // the surface faces +a, and (b, c) turns counter-clockwise seen from +a.
        const std::uint32_t q0 = corners[0], q1 = lowerInside ? corners[1] : corners[3], q2 = corners[2],
                            q3 = lowerInside ? corners[3] : corners[1];
        emitQuad(q0, q1, q2, q3, lowerInside);
    }

    void emitQuad(std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3, bool lowerInside)
    {
        std::vector<std::uint32_t>& idx = mOut.indices;
        bool first;
        if (mP.split == DualQuadSplit::Fixed) {
            first = lowerInside;
        } else {
            first = distance2(q0, q2) <= distance2(q1, q3);
        }
        const std::size_t at = idx.size();
        idx.resize(at + 6);
        std::uint32_t* o = idx.data() + at;
        if (first) {
            o[0] = q0, o[1] = q1, o[2] = q2, o[3] = q0, o[4] = q2, o[5] = q3;
        } else {
            o[0] = q1, o[1] = q2, o[2] = q3, o[3] = q1, o[4] = q3, o[5] = q0;
        }
    }

    float distance2(std::uint32_t i, std::uint32_t j) const
    {
        const glm::vec3 d = mChunkPosition[i] - mChunkPosition[j];
        return d.x * d.x + d.y * d.y + d.z * d.z;
    }

    /// The vertex of cell `cell` (relative level `level`) on the surface
    /// sheet through its edge `edge`.
    std::uint32_t vertexOf(int level, const int cell[3], int edge)
    {
        if (level != 0) {
            const std::array<int, 4> key{level, cell[0], cell[1], cell[2]};
            const auto found = mOtherLevels.find(key);
            if (found != mOtherLevels.end()) return found->second;
            const std::uint32_t index = create(level, cell, 0, 0);
            mOtherLevels.emplace(key, index);
            return index;
        }
        return ownVertex(cell, edge);
    }

    /// vertexOf() at the chunk's own level.
    std::uint32_t ownVertex(const int cell[3], int edge)
    {
        std::uint32_t& slotIndex = mCellSlot[slotOf(cell)];
        if (slotIndex == UNSET) { // first visit: the corner signs, once per cell
            const std::size_t corner0 = dense(cell[0], cell[1], cell[2]);
            int signs = signsAt(corner0);
            if (mP.sheets == DualSheets::Separate) {
                const int face = mTable.tunnelFace[signs];
                if (face >= 0) {
                    // The neighbour across that face (inside the samples: the
                    // apron leaves room for one more cell on each side).
                    const std::ptrdiff_t step = mS.stride[face / 2] * (face % 2 ? 1 : -1);
                    if (mTable.tunnelFace[signsAt(std::size_t(std::ptrdiff_t(corner0) + step))] == (face ^ 1)) {
                        signs = ~signs & 0xff; // group as the complement does
                    }
                }
            }
            slotIndex = std::uint32_t(mSlots.size());
            mSlots.push_back({UNSET, UNSET, UNSET, UNSET, std::uint32_t(signs)});
        }
        const int mask = int(mSlots[slotIndex][4]);
        const int sheet = sheetOf(mask, edge);
        std::uint32_t& vertex = mSlots[slotIndex][std::size_t(sheet)];
        if (vertex == UNSET) vertex = create(0, cell, mask, sheet);
        return vertex;
    }

    int signsAt(std::size_t first) const
    {
        int signs = 0;
        for (int k = 0; k < 8; ++k) signs |= mInside[first + std::size_t(mCornerOffset[k])] << k;
        return signs;
    }

    std::uint32_t create(int level, const int cell[3], int mask, int sheet)
    {
        float f[8];
        std::size_t corner0 = 0;
        if (level == 0) {
            corner0 = dense(cell[0], cell[1], cell[2]);
            for (int k = 0; k < 8; ++k) f[k] = mS.values[corner0 + std::size_t(mCornerOffset[k])];
        } else if (level > 0) {
            const std::size_t c0 = dense(2 * cell[0], 2 * cell[1], 2 * cell[2]);
            for (int k = 0; k < 8; ++k) f[k] = mS.values[c0 + 2 * std::size_t(mCornerOffset[k])];
        } else {
            for (int k = 0; k < 8; ++k) f[k] = mS.fine(cell[0] + (k >> 2 & 1), cell[1] + (k >> 1 & 1), cell[2] + (k & 1));
        }
        const glm::dvec3 local = place(f, level == 0 ? corner0 : std::size_t(0), cell, mask, sheet);
        if (mP.gradients == DualGradient::Cell) mOut.gradients.push_back(cellGradient(f, local));
        else if (mP.gradients == DualGradient::Central) mOut.gradients.push_back(centralGradient(corner0, local));
        const double scale = level > 0 ? 2.0 : level < 0 ? 0.5 : 1.0;
        const glm::dvec3 position((double(cell[0]) + local.x) * scale, (double(cell[1]) + local.y) * scale,
                                  (double(cell[2]) + local.z) * scale);
        if (mP.split == DualQuadSplit::ShorterDiagonal) mChunkPosition.emplace_back(position);
        mOut.positions.push_back(position);
        mOut.vertices.push_back({std::int8_t(level), std::uint8_t(sheet), {cell[0], cell[1], cell[2]}});
        return std::uint32_t(mOut.vertices.size() - 1);
    }

    /// Cell-local vertex position in [0,1]^3 from the corner values `f`
    /// (corner0: the dense index of corner 0, own level only). With
    /// Separate sheets only the crossed edges of sheet `sheet` count.
    glm::dvec3 place(const float f[8], std::size_t corner0, const int cell[3], int mask, int sheet) const
    {
        // Surface nets (the common case) straight to the mean crossing.
        if (mP.placement == DualPlacement::SurfaceNets) return finish(meanCrossing(f, mask, sheet), corner0, true, 0.0);
        const int sheets = mP.sheets == DualSheets::Separate ? mTable.count[mask] : 1;
        if (sheets < 2) return placeSheet(f, corner0, cell, mask, sheet, true);
        // Two sheets of one cell can clamp to the same point (a thin slab
        // whose QEF minima both lie beyond the same corner): then every sheet
        // of the cell goes to its mean crossing instead, which lies next to
        // its own crossings, apart from the other sheets'. Decided from the
        // cell alone, so every chunk that meshes the cell agrees.
        glm::dvec3 all[4];
        for (int s = 0; s < sheets; ++s) all[s] = placeSheet(f, corner0, cell, mask, s, true);
        for (int a = 0; a < sheets; ++a)
            for (int b = a + 1; b < sheets; ++b)
                if (all[a] == all[b]) return placeSheet(f, corner0, cell, mask, sheet, false);
        return all[sheet];
    }

    /// place() for one sheet, dual contouring; `qef` false: the mean
    /// crossing, without projection (the fallback).
    glm::dvec3 placeSheet(const float f[8], std::size_t corner0, const int cell[3], int mask, int sheet,
                          bool qef) const
    {
        const double iso = mP.isovalue;
        const bool separate = mP.sheets == DualSheets::Separate;
        glm::dvec3 points[12], normals[12];
        int count = 0;
        glm::dvec3 mean(0.0);
        for (int n = 0; n < 12; ++n) {
            const int e = mEdgeOrder[n];
            const int k0 = CELL_EDGES[e][0], k1 = CELL_EDGES[e][1];
            if (separate ? mTable.component[mask][e] != sheet : (f[k0] < mIso) == (f[k1] < mIso)) continue;
            int normalAt = NO_SAMPLE; // else which end's side was trusted (0 or 1)
            // Near a sharp edge the field is not linear along the grid edge
            // (the other face is nearer to the inside sample): of the
            // linear estimate and the two one-sided extrapolations, trust
            // the steepest, which is the one that does not cross a kink.
            const std::size_t i0 = corner0 + std::size_t(mCornerOffset[k0]);
            const std::size_t i1 = corner0 + std::size_t(mCornerOffset[k1]);
            const bool in0 = mInside[i0] != 0;
            const std::ptrdiff_t step = mS.stride[e / 4] * (in0 ? 1 : -1);
            const std::size_t in = in0 ? i0 : i1, out = in0 ? i1 : i0;
            const double dIn = mS.values[in] - iso, dOut = mS.values[out] - iso;
            const double sOut = mS.values[std::ptrdiff_t(out) + step] - iso - dOut,
                         sIn = dIn - (mS.values[std::ptrdiff_t(in) - step] - iso);
            double best = dOut - dIn, u = -dIn / best;
            if (sOut > 1.001 * best && dOut / sOut <= 1.0) {
                best = sOut;
                u = 1.0 - dOut / sOut;
                normalAt = in0 ? 1 : 0;
            }
            if (sIn > 1.001 * best && -dIn / sIn <= 1.0) {
                u = -dIn / sIn;
                normalAt = in0 ? 0 : 1;
            }
            const double t = in0 ? u : 1.0 - u;
            const glm::dvec3 p0(k0 >> 2 & 1, k0 >> 1 & 1, k0 & 1);
            const glm::dvec3 p1(k1 >> 2 & 1, k1 >> 1 & 1, k1 & 1);
            points[count] = p0 + (p1 - p0) * t;
            mean += points[count];
            if (mP.planeGradient) {
                normals[count] = mP.planeGradient({cell[0], cell[1], cell[2]}, points[count]);
            } else if (normalAt != NO_SAMPLE) {
                normals[count] = enoGradient(normalAt == 0 ? i0 : i1);
            } else {
                normals[count] = enoGradient(i0) * (1.0 - t) + enoGradient(i1) * t;
            }
            const double len = glm::length(normals[count]);
            normals[count] = len > 1e-12 && std::isfinite(len) ? normals[count] / len : glm::dvec3(0.0);
            ++count;
        }
        glm::dvec3 p = count > 0 ? mean / double(count) : glm::dvec3(0.5);

        if (qef && count > 0) {
            // Minimise sum (n_i . (x - p_i))^2 about the mass point, ignoring
            // near-singular directions (there x stays at the mass point).
            double ata[3][3] = {}, atb[3] = {};
            for (int i = 0; i < count; ++i) {
                const glm::dvec3& n = normals[i];
                const double d = glm::dot(n, points[i] - p);
                for (int r = 0; r < 3; ++r) {
                    atb[r] += n[r] * d;
                    for (int c = 0; c < 3; ++c) ata[r][c] += n[r] * n[c];
                }
            }
            double lambda[3], v[3][3];
            symmetricEigen(ata, lambda, v);
            const double largest = std::max({std::abs(lambda[0]), std::abs(lambda[1]), std::abs(lambda[2])});
            glm::dvec3 x(0.0);
            for (int e = 0; e < 3; ++e) {
                if (largest <= 0.0 || std::abs(lambda[e]) < mP.singularThreshold * largest) continue;
                const double proj = (v[0][e] * atb[0] + v[1][e] * atb[1] + v[2][e] * atb[2]) / lambda[e];
                for (int r = 0; r < 3; ++r) x[r] += v[r][e] * proj;
            }
            p += x;
        }
        // Dual contouring keeps the vertex strictly inside its cell: the QEF
        // minimum often lies outside, and clamped onto a face, edge or corner
        // it could meet the clamped vertex of a neighbouring cell at the same
        // point, which a reader welding by position turns into a non-manifold
        // edge. Cells are disjoint inside, so vertices of distinct cells never
        // coincide (and each stays where every chunk computes it).
        const double lo = DUAL_CONTOURING_MARGIN;

        return finish(p, corner0, qef, lo);
    }

    /// Surface nets: the mean of the crossings (of sheet `sheet`), the cell
    /// centre if none.
    glm::dvec3 meanCrossing(const float f[8], int mask, int sheet) const
    {
        const double iso = mP.isovalue;
        int edges = 0; // the edges to average, bit e: CELL_EDGES[e]
        if (mP.sheets == DualSheets::Separate) {
            edges = mTable.edges[mask][sheet];
        } else {
            int signs = 0;
            for (int k = 0; k < 8; ++k) signs |= int(f[k] < mIso) << k;
            edges = mTable.crossed[signs];
        }
        // Visited in memory order, set bits only (bit n: mEdgeOrder[n]).
        unsigned order = unsigned(mMemoryOrderBits[0][edges & 63] | mMemoryOrderBits[1][edges >> 6]);
        glm::dvec3 sum(0.0);
        int count = 0;
        for (; order != 0; order &= order - 1) {
            const int e = mEdgeOrder[std::countr_zero(order)];
            const EdgeCorner& corner = EDGE_CORNERS[e];
            const double v0 = f[corner.k0], v1 = f[corner.k1];
            const double t = std::clamp((iso - v0) / (v1 - v0), 0.0, 1.0);
            // The crossing: corner k0, moved by t along the edge's axis.
            sum.x += corner.axis == 0 ? t : corner.at[0];
            sum.y += corner.axis == 1 ? t : corner.at[1];
            sum.z += corner.axis == 2 ? t : corner.at[2];
            ++count;
        }
        return count > 0 ? sum / double(count) : glm::dvec3(0.5);
    }

    /// Projection steps (when `project`), then the clamp into [lo, 1 − lo]
    /// and the rounding to the quantum.
    glm::dvec3 finish(glm::dvec3 p, std::size_t corner0, bool project, double lo) const
    {
        if (project && mP.projectionSteps > 0) p = projected(p, corner0);
        const double hi = 1.0 - lo;
        // Per component in registers (a vector stored by parts and loaded
        // whole stalls store forwarding).
        return {quantized(std::clamp(p.x, lo, hi)), quantized(std::clamp(p.y, lo, hi)),
                quantized(std::clamp(p.z, lo, hi))};
    }

    double quantized(double v) const
    {
        if (!(mQuantum > 0.0)) return v;
        const double x = v * mQuantum + 0.5;
        // floor() of a positive double below 2^52 is its truncation.
        const double r = x > 0.0 && x < 4503599627370496.0 ? double(std::int64_t(x)) : std::floor(x);
        return mQuantumInverse > 0.0 ? r * mQuantumInverse : r / mQuantum;
    }

    /// Newton steps along the trilinear gradient towards the isosurface.
    glm::dvec3 projected(glm::dvec3 p, std::size_t corner0) const
    {
        const double iso = mP.isovalue;
        for (int s = 0; s < mP.projectionSteps; ++s) {
            const double fp = trilinear(corner0, p) - iso;
            const glm::dvec3 g = centralGradient(corner0, p);
            const double g2 = glm::dot(g, g);
            if (!(g2 > 1e-12)) break;
            p -= g * (fp / g2);
            for (int a = 0; a < 3; ++a) p[a] = std::clamp(p[a], 0.0, 1.0);
        }
        return p;
    }

    // Trilinear interpolation at `p`, relative to sample `base`, p in
    // [-1, 2]^3 (a cell and one cell around it). Relative coordinates make
    // the result independent of where the cell sits in the samples.
    double trilinear(std::size_t base, const glm::dvec3& p) const
    {
        const int x = std::clamp(floorToInt<int>(p[0]), -1, 1);
        const int y = std::clamp(floorToInt<int>(p[1]), -1, 1);
        const int z = std::clamp(floorToInt<int>(p[2]), -1, 1);
        const double u = p[0] - x, v = p[1] - y, w = p[2] - z;
        return trilinearIn(std::ptrdiff_t(base) + x * mS.stride[0] + y * mS.stride[1] + z * mS.stride[2], u, v, w);
    }

    // trilinear() in the cell at sample `i` (its corner 0), weights u, v, w:
    // the same operations in the same order.
    double trilinearIn(std::ptrdiff_t i, double u, double v, double w) const
    {
        const std::ptrdiff_t sx = mS.stride[0], sy = mS.stride[1], sz = mS.stride[2];
        const float* d = mS.values;
        auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
        const double c00 = lerp(d[i], d[i + sz], w), c01 = lerp(d[i + sy], d[i + sy + sz], w);
        const double c10 = lerp(d[i + sx], d[i + sx + sz], w);
        const double c11 = lerp(d[i + sx + sy], d[i + sx + sy + sz], w);
        return lerp(lerp(c00, c01, v), lerp(c10, c11, v), u);
    }

    // Central differences one cell apart on the trilinear interpolant, p in
    // [0, 1]^3 relative to sample `base`. For p in [0, 1]^3 (every caller's
    // case) the cells of the six evaluations are known without floor(): the
    // same cells and weights as centralGradientAnywhere(), bit for bit.
    glm::dvec3 centralGradient(std::size_t base, const glm::dvec3& p) const
    {
        // Almost always p is in [0, 1)^3 (and not -0): the cells are the
        // vertex's own and its six face neighbours, the weights those below
        // with floor(p) = 0, floor(p + 1) = 1 and floor(p - 1) = -1.
        if (p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0 && p.z >= 0.0 && p.z < 1.0 && !std::signbit(p.x) &&
            !std::signbit(p.y) && !std::signbit(p.z)) {
            const std::ptrdiff_t b = std::ptrdiff_t(base);
            const std::ptrdiff_t sx = mS.stride[0], sy = mS.stride[1], sz = mS.stride[2];
            const double u = p.x, v = p.y, w = p.z;
            const double gx = trilinearIn(b + sx, (p.x + 1.0) - 1.0, v, w) - trilinearIn(b - sx, (p.x - 1.0) - -1.0, v, w);
            const double gy = trilinearIn(b + sy, u, (p.y + 1.0) - 1.0, w) - trilinearIn(b - sy, u, (p.y - 1.0) - -1.0, w);
            const double gz = trilinearIn(b + sz, u, v, (p.z + 1.0) - 1.0) - trilinearIn(b - sz, u, v, (p.z - 1.0) - -1.0);
            return {0.5 * gx, 0.5 * gy, 0.5 * gz};
        }
        return centralGradientUnitCell(base, p);
    }

    // centralGradient() for any p in [0, 1]^3 (else centralGradientAnywhere()).
    [[gnu::noinline]] glm::dvec3 centralGradientUnitCell(std::size_t base, const glm::dvec3& p) const
    {
        const bool inUnitCell = p.x >= 0.0 && p.x <= 1.0 && p.y >= 0.0 && p.y <= 1.0 && p.z >= 0.0 && p.z <= 1.0;
        // p + (1, 0, 0) turns a -0 of y or z into +0: leave that to the general path.
        if (!inUnitCell || std::signbit(p.x) || std::signbit(p.y) || std::signbit(p.z)) {
            return centralGradientAnywhere(base, p);
        }
        const std::ptrdiff_t sx = mS.stride[0], sy = mS.stride[1], sz = mS.stride[2];
        const std::ptrdiff_t b = std::ptrdiff_t(base);
        // Unshifted axes: floor(p) is 0, or 1 at p = 1.
        const int cx = p.x < 1.0 ? 0 : 1, cy = p.y < 1.0 ? 0 : 1, cz = p.z < 1.0 ? 0 : 1;
        const double u = p.x - cx, v = p.y - cy, w = p.z - cz;
        // Shifted by +1: floor(p + 1) clamps to 1; by -1: floor(p - 1) is -1, or 0 at p = 1.
        const double xp = p.x + 1.0, yp = p.y + 1.0, zp = p.z + 1.0;
        const double xm = p.x - 1.0, ym = p.y - 1.0, zm = p.z - 1.0;
        const int xmCell = xm < 0.0 ? -1 : 0, ymCell = ym < 0.0 ? -1 : 0, zmCell = zm < 0.0 ? -1 : 0;
        const double gx = trilinearIn(b + sx + cy * sy + cz * sz, xp - 1.0, v, w) -
                          trilinearIn(b + xmCell * sx + cy * sy + cz * sz, xm - xmCell, v, w);
        const double gy = trilinearIn(b + cx * sx + sy + cz * sz, u, yp - 1.0, w) -
                          trilinearIn(b + cx * sx + ymCell * sy + cz * sz, u, ym - ymCell, w);
        const double gz = trilinearIn(b + cx * sx + cy * sy + sz, u, v, zp - 1.0) -
                          trilinearIn(b + cx * sx + cy * sy + zmCell * sz, u, v, zm - zmCell);
        return {0.5 * gx, 0.5 * gy, 0.5 * gz};
    }

    glm::dvec3 centralGradientAnywhere(std::size_t base, const glm::dvec3& p) const
    {
        return {0.5 * (trilinear(base, p + glm::dvec3(1, 0, 0)) - trilinear(base, p - glm::dvec3(1, 0, 0))),
                0.5 * (trilinear(base, p + glm::dvec3(0, 1, 0)) - trilinear(base, p - glm::dvec3(0, 1, 0))),
                0.5 * (trilinear(base, p + glm::dvec3(0, 0, 1)) - trilinear(base, p - glm::dvec3(0, 0, 1)))};
    }

    // The exact gradient of the cell's trilinear interpolant at `local`,
    // corners summed in memory order.
    glm::dvec3 cellGradient(const float f[8], const glm::dvec3& local) const
    {
        glm::dvec3 g(0.0);
        for (int m = 0; m < 8; ++m) {
            const int k = mCornerOrder[m];
            const int ox = k >> 2 & 1, oy = k >> 1 & 1, oz = k & 1;
            const double wx = ox ? local.x : 1.0 - local.x;
            const double wy = oy ? local.y : 1.0 - local.y;
            const double wz = oz ? local.z : 1.0 - local.z;
            const double sx = ox ? 1.0 : -1.0, sy = oy ? 1.0 : -1.0, sz = oz ? 1.0 : -1.0;
            g.x += sx * wy * wz * f[k];
            g.y += sy * wx * wz * f[k];
            g.z += sz * wx * wy * f[k];
        }
        return g;
    }

    // Gradient at a sample, per axis: central differences where the field is
    // smooth (small centred second difference), else the one-sided
    // difference whose side is smoother (ENO: smaller one-sided second
    // difference), so a kink (a sharp edge of the surface) next to the
    // sample does not bend the estimate.
    glm::dvec3 enoGradient(std::size_t i) const
    {
        glm::dvec3 g;
        const float* d = mS.values;
        for (int a = 0; a < 3; ++a) {
            const std::size_t s = std::size_t(mS.stride[a]);
            const double m2 = d[i - 2 * s], m1 = d[i - s], c = d[i], p1 = d[i + s], p2 = d[i + 2 * s];
            const double back = c - m1, fore = p1 - c;
            const double back2 = std::abs(c - 2.0 * m1 + m2), fore2 = std::abs(p2 - 2.0 * p1 + c);
            if (std::abs(fore - back) < mP.smoothness) g[a] = 0.5 * (back + fore);
            else g[a] = back2 < fore2 ? back : fore;
        }
        return g;
    }

    const DualSamples& mS;
    const DualMeshSettings& mP;
    const ComponentTable& mTable;
    int mOuter[3] = {0, 1, 2};
    int mBit[3] = {2, 1, 0};
    int mCornerOrder[8];
    int mEdgeOrder[12];
    std::uint16_t mMemoryOrderBits[2][64]; // edge bits 0-5 and 6-11 (CELL_EDGES) to bits of mEdgeOrder
    std::ptrdiff_t mCornerOffset[8];
    struct OwnCorner // ownPolygon(): per axis, the four cells around an edge
    {
        int delta[3];        // the cell is the edge's lattice point minus this
        std::ptrdiff_t slot; // its offset in mCellSlot
        int edge;            // the edge in it (CELL_EDGES)
    };
    OwnCorner mOwnCorners[3][4];
    bool mAnyFiner = false, mAnyLevel = false;
    float mIso = 0.0f;
    double mQuantum = 0.0, mQuantumInverse = 0.0; // the inverse only when exact (a power of two)
    WalkerScratch* mScratch = nullptr; // where the buffers below go back to
    std::unique_ptr<std::uint8_t[]> mInside;
    std::size_t mInsideCapacity = 0;
    std::vector<std::uint32_t> mCellSlot;
    std::vector<std::array<std::uint32_t, 5>> mSlots; // 4 vertices, then the corner signs
    std::map<std::array<int, 4>, std::uint32_t> mOtherLevels;
    std::vector<glm::vec3> mChunkPosition; // ShorterDiagonal: per vertex, in own-level cells (float, as callers store them)
    DualMeshResult mOut;
};

} // namespace

DualMeshResult dualMesh(const DualSamples& samples, const DualMeshSettings& settings)
{
    return Walker(samples, settings, DualMeshResult()).run();
}

void dualMesh(const DualSamples& samples, const DualMeshSettings& settings, DualMeshResult& result)
{
    result = Walker(samples, settings, std::move(result)).run();
}

} // namespace strata::meshing
