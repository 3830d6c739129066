// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "DualMesher.h"

#include <strata/Error.h>
#include <strata/IntegerMath.h>
#include <strata/meshing/DualMesh.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

namespace strata::meshing {

using openvdb::Coord;

namespace {

constexpr std::uint32_t UNSET = 0xffffffffu;
constexpr int APRON = 3;             // block samples below the first owned cell (DualMesh stencils)
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
// two more layers on each side for the stencils of DualMesh.cpp.
struct Block
{
    Coord min;   // index coordinates of sample (0,0,0)
    int n[3];    // samples per axis
    float* values = nullptr; // n[0] * n[1] * n[2], every one written by fillBlock()

    std::size_t at(int x, int y, int z) const { return (std::size_t(x) * n[1] + y) * n[2] + z; }
    std::size_t stride(int axis) const { return axis == 0 ? std::size_t(n[1]) * n[2] : axis == 1 ? n[2] : 1; }
};

void fillBlock(const openvdb::FloatGrid& grid, Block& block)
{
    float* values = block.values;
    openvdb::FloatGrid::ConstAccessor accessor = grid.getConstAccessor();
    const Coord lo = block.min, hi = block.min + Coord(block.n[0] - 1, block.n[1] - 1, block.n[2] - 1);
    // Leaf by leaf: copy runs along z from the leaf buffer, or fill with the tile value.
    for (int lx = lo.x() & ~7; lx <= hi.x(); lx += 8) {
        for (int ly = lo.y() & ~7; ly <= hi.y(); ly += 8) {
            for (int lz = lo.z() & ~7; lz <= hi.z(); lz += 8) {
                const Coord origin(lx, ly, lz);
                const openvdb::FloatTree::LeafNodeType* leaf = accessor.probeConstLeaf(origin);
                const float* buffer = nullptr; // null: every sample is `tile`
                float tile = 0.0f;
                if (leaf) {
                    // getValue() reads 0 from an empty buffer; load a delayed one first.
                    if (leaf->buffer().isOutOfCore()) (void)leaf->getValue(openvdb::Index(0));
                    if (!leaf->buffer().empty()) buffer = leaf->buffer().data();
                } else {
                    tile = accessor.getValue(origin);
                }
                const int x0 = std::max(lx, lo.x()), x1 = std::min(lx + 7, hi.x());
                const int y0 = std::max(ly, lo.y()), y1 = std::min(ly + 7, hi.y());
                const int z0 = std::max(lz, lo.z()), z1 = std::min(lz + 7, hi.z());
                const std::size_t run = std::size_t(z1 - z0 + 1);
                for (int x = x0; x <= x1; ++x) {
                    for (int y = y0; y <= y1; ++y) {
                        float* to = values + block.at(x - lo.x(), y - lo.y(), z0 - lo.z());
                        if (buffer) {
                            const float* from = buffer + (((x & 7) << 6) | ((y & 7) << 3) | (z0 & 7));
                            std::memcpy(to, from, run * sizeof(float));
                        } else {
                            std::fill(to, to + run, tile);
                        }
                    }
                }
            }
        }
    }
}

// GridChunkMesher::mesh()'s buffers, kept per thread from one chunk to the
// next (as dualMesh() keeps its own): allocated and freed per chunk, they
// made the allocator return pages to the system and fault them in again.
// Buffers above KEEP_BYTES are freed after use.
struct MesherScratch
{
    static constexpr std::size_t KEEP_BYTES = std::size_t(16) << 20;
    std::unique_ptr<float[]> values;
    std::size_t capacity = 0;
    DualMeshResult result;
    bool busy = false; // in use further up this thread's stack (a gradient callback that meshes)

    float* samples(std::size_t count)
    {
        if (count > capacity) {
            values.reset(new float[count]);
            capacity = count;
        }
        return values.get();
    }
};

// This thread's scratch, or a fresh one when it is in use.
class ScratchLease
{
public:
    ScratchLease()
    {
        thread_local MesherScratch scratch;
        if (scratch.busy) {
            mLocal = std::make_unique<MesherScratch>();
            mScratch = mLocal.get();
        } else {
            mScratch = &scratch;
        }
        mScratch->busy = true;
    }
    ~ScratchLease()
    {
        mScratch->busy = false;
        if (mLocal) return;
        if (mScratch->capacity * sizeof(float) > MesherScratch::KEEP_BYTES) {
            mScratch->values.reset();
            mScratch->capacity = 0;
        }
        DualMeshResult& r = mScratch->result;
        const std::size_t bytes = r.vertices.capacity() * sizeof(DualVertex) + r.positions.capacity() * sizeof(glm::dvec3) +
                                  r.gradients.capacity() * sizeof(glm::dvec3) + r.indices.capacity() * sizeof(std::uint32_t);
        if (bytes > MesherScratch::KEEP_BYTES) r = DualMeshResult();
    }
    ScratchLease(const ScratchLease&) = delete;
    ScratchLease& operator=(const ScratchLease&) = delete;
    MesherScratch* operator->() const { return mScratch; }

private:
    MesherScratch* mScratch = nullptr;
    std::unique_ptr<MesherScratch> mLocal;
};

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

// Meshes the chunks of one grid: gathers each chunk's samples into a Block
// and hands them to dualMesh(); turns its vertices into index-space
// positions and per-vertex normals.
class GridChunkMesher
{
public:
    GridChunkMesher(const openvdb::FloatGrid& grid, const detail::DualSettings& settings)
        : mGrid(grid), mSettings(settings), mFrame(grid.transform())
    {
    }

    ChunkData mesh(const Coord& min, const Coord& dim) const;

private:
    const openvdb::FloatGrid& mGrid;
    const detail::DualSettings& mSettings;
    Frame mFrame;
};

ChunkData GridChunkMesher::mesh(const Coord& min, const Coord& dim) const
{
    ChunkData out;
    out.min = min;
    out.dim = dim;

    const ScratchLease scratch;
    Block block;
    block.min = min - Coord(APRON);
    for (int a = 0; a < 3; ++a) block.n[a] = dim[a] + 2 * APRON;
    block.values = scratch->samples(std::size_t(block.n[0]) * block.n[1] * block.n[2]);
    fillBlock(mGrid, block);

    DualSamples samples;
    samples.values = block.values;
    samples.apron = APRON;
    for (int a = 0; a < 3; ++a) {
        samples.cells[a] = dim[a];
        samples.size[a] = block.n[a];
        samples.stride[a] = std::ptrdiff_t(block.stride(a));
    }
    const ChunkMeshOptions& options = mSettings.options;
    DualMeshSettings settings;
    settings.isovalue = options.isovalue;
    settings.sheets = DualSheets::Separate;
    settings.split = DualQuadSplit::ShorterDiagonal;
    settings.projectionSteps = options.projectionSteps;
    settings.quantum = QUANTUM;
    const NormalMethod normalMethod = options.normals;
    if (normalMethod == NormalMethod::Grid) settings.gradients = DualGradient::Central;
    if (mSettings.method == detail::DualMethod::DualContouring) {
        settings.placement = DualPlacement::DualContouring;
        settings.singularThreshold = mSettings.singularThreshold;
        settings.smoothness = 0.1 * mGrid.voxelSize()[0]; // second differences of a smooth field (world units)
        if (options.gradient) {
            settings.planeGradient = [&](const std::array<int, 3>& cell, const glm::dvec3& local) {
                const openvdb::Vec3d ijk = openvdb::Vec3d(min.x() + cell[0], min.y() + cell[1], min.z() + cell[2]) +
                                           openvdb::Vec3d(local.x, local.y, local.z);
                const openvdb::Vec3d g = mFrame.indexGradient(options.gradient(mFrame.world(ijk)));
                return glm::dvec3(g[0], g[1], g[2]);
            };
        }
    }
    DualMeshResult& result = scratch->result;
    dualMesh(samples, settings, result);

    const bool perVertexNormals = normalMethod == NormalMethod::Grid || normalMethod == NormalMethod::Gradient;
    out.local.reserve(result.vertices.size());
    out.cells.reserve(result.vertices.size());
    out.components.reserve(result.vertices.size());
    if (perVertexNormals) out.normals.reserve(result.vertices.size());
    for (std::size_t i = 0; i < result.vertices.size(); ++i) {
        const DualVertex& v = result.vertices[i];
        const glm::dvec3& q = result.positions[i];
        out.local.emplace_back(float(q.x), float(q.y), float(q.z));
        const Coord cell = min + Coord(v.cell[0], v.cell[1], v.cell[2]);
        out.cells.push_back(cell);
        out.components.push_back(v.sheet);
        if (perVertexNormals) {
            glm::dvec3 g;
            if (normalMethod == NormalMethod::Gradient) {
                // Inside the cell; exact, as the offset is a multiple of 1/QUANTUM.
                const glm::dvec3 p = q - glm::dvec3(v.cell[0], v.cell[1], v.cell[2]);
                g = options.gradient(mFrame.world(openvdb::Vec3d(cell.x(), cell.y(), cell.z()) +
                                                  openvdb::Vec3d(p.x, p.y, p.z)));
            } else {
                const glm::dvec3& d = result.gradients[i];
                g = mFrame.worldGradient(openvdb::Vec3d(d.x, d.y, d.z));
            }
            const glm::vec3 n(g);
            const float len2 = glm::dot(n, n);
            // Zero marks a vanished gradient; assembly replaces it.
            out.normals.push_back(len2 > MIN_LENGTH2 && std::isfinite(len2) ? n / std::sqrt(len2) : glm::vec3(0.0f));
        }
    }
    out.indices = std::move(result.indices);
    return out;
}

std::vector<Coord> chunksOf(const openvdb::FloatGrid& grid, int chunkSize)
{
    std::vector<Coord> chunks;
    // The corner of the chunk that holds voxel coordinate v.
    auto chunkCorner = [chunkSize](int v) { return int(floorDiv(v, chunkSize) * chunkSize); };
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const Coord origin = leaf->origin();
        // Cells touching this leaf lie in [origin - 1, origin + 7].
        for (int k = 0; k < 8; ++k) {
            const Coord c(origin.x() - (k >> 2 & 1), origin.y() - (k >> 1 & 1), origin.z() - (k & 1));
            chunks.emplace_back(chunkCorner(c.x()), chunkCorner(c.y()), chunkCorner(c.z()));
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
        throw Error(ErrorKind::BadInput, "meshing: isovalue = " + std::to_string(o.isovalue) + " must be finite");
    }
    if (o.chunkSize != 0 && (o.chunkSize < 8 || o.chunkSize > 512 || o.chunkSize % 8 != 0)) {
        throw Error(ErrorKind::BadInput, "meshing: chunk size " + std::to_string(o.chunkSize) +
                    " must be 0 (one chunk) or a multiple of 8 in [8, 512]");
    }
    if (!std::isfinite(o.origin.x) || !std::isfinite(o.origin.y) || !std::isfinite(o.origin.z)) {
        throw Error(ErrorKind::BadInput, "meshing: origin must be finite");
    }
    if (o.normals == NormalMethod::Gradient && !o.gradient) {
        throw Error(ErrorKind::BadInput, "meshing: normals = gradient needs a gradient function");
    }
    if (o.projectionSteps < 0 || o.projectionSteps > 16) {
        throw Error(ErrorKind::BadInput, "meshing: projection steps " + std::to_string(o.projectionSteps) + " must be in [0, 16]");
    }
    if (!(settings.singularThreshold > 0.0 && settings.singularThreshold < 1.0)) {
        throw Error(ErrorKind::BadInput, "meshing: QEF singular threshold " + std::to_string(settings.singularThreshold) +
                    " must be in (0, 1)");
    }
}

static void requireLinear(const openvdb::FloatGrid& grid)
{
    if (!grid.transform().isLinear()) {
        throw Error(ErrorKind::BadInput, "meshing: grid '" + grid.getName() + "' needs a linear transform (got '" +
                    grid.transform().mapType() + "')");
    }
}

ChunkMesh meshChunk(const openvdb::FloatGrid& grid, const Coord& chunkMin, const DualSettings& settings)
{
    requireLinear(grid);
    const int n = settings.options.chunkSize == 0 ? 32 : settings.options.chunkSize;
    for (int a = 0; a < 3; ++a) {
        if (chunkMin[a] % n != 0) {
            throw Error(ErrorKind::BadInput, "meshing: chunk minimum (" + std::to_string(chunkMin.x()) + ", " +
                        std::to_string(chunkMin.y()) + ", " + std::to_string(chunkMin.z()) +
                        ") is not a multiple of the chunk size " + std::to_string(n));
        }
    }
    const Frame frame(grid.transform());
    ChunkData data = GridChunkMesher(grid, settings).mesh(chunkMin, Coord(n));
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
    const GridChunkMesher mesher(grid, settings);
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
        throw Error(ErrorKind::BadInput, "meshing: chunk size " + std::to_string(chunkSize) + " must be a multiple of 8 in [8, 512]");
    }
    return chunksOf(grid, chunkSize);
}

} // namespace strata::meshing
