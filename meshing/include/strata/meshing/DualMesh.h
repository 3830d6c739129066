// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The one dual mesher behind surfaceNets(), dualContouring() and the
/// streaming World's chunk meshes (strata::world): given the samples of one
/// chunk, it walks the sign-changing lattice edges, places one vertex per
/// cell (or per surface sheet of a cell) and emits the polygon around each
/// edge. Callers only gather samples and turn the result into their own
/// mesh type; the sample source is plain arrays and a callback, so this
/// header knows nothing of grids or density fields.
///
/// Chunk and cells. A chunk has `cells` cells per axis at its own level;
/// lattice point (i, j, k) is the minimum corner of cell (i, j, k), both
/// relative to the chunk's minimum. The chunk owns the lattice edges whose
/// lower end lies in [0, cells) and emits one polygon per owned edge whose
/// ends have different signs (inside: value < isovalue).
///
/// Octree seams. A chunk's seven lower neighbours may be one level coarser
/// or finer (`DualSamples::signature`). Cells on the chunk's lower side then
/// belong to the neighbour's level; an edge whose cells around it include a
/// finer one is replaced by the finer neighbour's edges along the shared
/// face (read through `DualSamples::fine`). The polygon around an edge is a
/// quad, or a triangle where two of its cells are the same coarse cell, so
/// the meshes of adjacent chunks of different levels close without cracks.
///
/// Vertex placement (DualPlacement):
/// - surface nets: the mean of the cell's edge crossings (linear
///   interpolation of the two samples), cell centre if none;
/// - dual contouring: the minimiser of the quadric error of the tangent
///   planes at the crossings, solved about the mean with near-singular
///   directions dropped, then clamped strictly inside its cell (a margin of
///   DUAL_CONTOURING_MARGIN cells), so vertices of distinct cells never
///   share a position and the mesh stays manifold when welded by position.
///
/// Reproducibility. Corners and crossings are visited in the memory order of
/// `DualSamples::values` (the axis with the smallest stride varies fastest)
/// and lattice points likewise, so the bytes of the output depend only on
/// the samples and their layout, never on threads.

#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace strata::meshing {

/// Levels of a chunk's seven lower neighbours relative to its own (−1 one
/// level finer, 0 same or absent, +1 one level coarser), indexed by a mask
/// whose bit a means "offset −1 along axis a"; entry 0 (the chunk itself)
/// is always 0.
using DualSignature = std::array<std::int8_t, 8>;

/// Where a cell's vertex goes (see the file comment).
enum class DualPlacement
{
    SurfaceNets,
    DualContouring,
};

/// How many vertices a cell the surface crosses gets.
enum class DualSheets
{
    One,      ///< one, from all its crossings (any level; the World's chunks)
    Separate, ///< one per surface sheet, as marching cubes separates them (ChunkMesh.h); own level only
};

/// Which gradient dualMesh() reports per vertex (DualMeshResult::gradients).
enum class DualGradient
{
    None,
    /// The exact gradient of the cell's trilinear interpolant at the vertex
    /// (any level).
    Cell,
    /// Central differences one cell apart on the trilinear interpolant of
    /// the own-level samples (smoother across cells; own level only).
    Central,
};

/// How a quad is cut into two triangles.
enum class DualQuadSplit
{
    /// Along the diagonal through the first cell (at −1, −1 across the edge)
    /// when the edge's lower end is inside, else the other diagonal.
    Fixed,
    /// Along the shorter diagonal (ties: through the first cell).
    ShorterDiagonal,
};

/// Dual contouring keeps its vertices at least this far (in cells) from
/// their cell's faces. Small enough to keep sharp features sharp (1/1024 of
/// a voxel), large enough to survive float positions (cells up to 2^13 from
/// the chunk origin), and a multiple of 1/65536, so DualMeshSettings::quantum
/// rounding keeps it.
constexpr double DUAL_CONTOURING_MARGIN = 1.0 / 1024.0;

/// The samples of one chunk: plain arrays and a callback, filled by the
/// caller before dualMesh() runs.
struct DualSamples
{
    /// Cells per axis at the chunk's own level (each in [1, 1024]).
    std::array<int, 3> cells{32, 32, 32};
    /// Own-level samples: lattice point p (relative to the chunk minimum) is
    /// `values[sum over a of (p[a] + apron) * stride[a]]`, for p[a] in
    /// [−apron, size[a] − apron). Plain meshing reads [−1, cells]; the cells
    /// of coarser neighbours reach down to −2; dual contouring, Separate
    /// sheets, projection and Central gradients read two more points on each
    /// side ([−3, cells + 2]). Not owned.
    const float* values = nullptr;
    std::array<std::ptrdiff_t, 3> stride{1, 1, 1}; ///< positive and distinct
    std::array<int, 3> size{35, 35, 35};           ///< points per axis in `values`
    int apron = 2;                                 ///< points below lattice point 0
    /// Levels of the lower neighbours (see DualSignature); all 0 for a lone
    /// chunk. Coarser neighbours' cells are read from `values` at every
    /// second point.
    DualSignature signature{};
    /// A sample of the level one finer than the chunk's, at fine lattice
    /// point (x, y, z) relative to the chunk minimum (two fine points per
    /// cell), x, y, z in [−2, 2·cells]. Called only when a signature entry
    /// is −1; then it must be set. Called from the dualMesh() thread only.
    std::function<float(int x, int y, int z)> fine;
};

struct DualMeshSettings
{
    double isovalue = 0.0; ///< in sample units; inside is `value < isovalue`
    DualPlacement placement = DualPlacement::SurfaceNets;
    DualSheets sheets = DualSheets::One;
    DualQuadSplit split = DualQuadSplit::Fixed;
    /// What DualMeshResult::gradients holds (sample units per cell).
    DualGradient gradients = DualGradient::None;
    /// Dual contouring: eigenvalues of the QEF matrix below this fraction of
    /// the largest are ignored. In (0, 1).
    double singularThreshold = 0.1;
    /// Dual contouring without `planeGradient`: second differences of the
    /// samples below this are smooth (sample units); larger ones mark a kink,
    /// and the plane gradient there is taken from the smoother side.
    double smoothness = 0.0;
    /// Dual contouring: the gradient (sample units per cell, any length) at
    /// a crossing, given its cell (relative to the chunk) and position inside
    /// it; when empty it is estimated from the samples.
    std::function<glm::dvec3(const std::array<int, 3>& cell, const glm::dvec3& local)> planeGradient;
    /// Newton steps along the trilinear gradient towards the isosurface
    /// after placement (own-level cells only; the vertex stays in its cell).
    int projectionSteps = 0;
    /// When > 0, positions inside a cell are rounded to multiples of
    /// 1/quantum (positions then add exactly to cell indices in float).
    double quantum = 0.0;
};

/// One vertex: the cell it belongs to (where in it: DualMeshResult::positions).
struct DualVertex
{
    std::int8_t level = 0;           ///< the cell's level relative to the chunk: −1, 0 or +1
    std::uint8_t sheet = 0;          ///< which surface sheet of the cell (0 with DualSheets::One)
    std::array<int, 3> cell{0, 0, 0}; ///< relative to the chunk minimum, in cells of its level
};

/// Structure of arrays, one entry per vertex in each per-vertex array, each
/// written once as the vertex is created (callers move them out, no copy).
struct DualMeshResult
{
    std::vector<DualVertex> vertices; ///< in order of first use
    /// Per vertex, `(cell + local) · 2^level` in double: its position in
    /// own-level cells relative to the chunk minimum, where `local` (each in
    /// [0, 1]) is its place inside its cell. `float(positions[i])` is the
    /// single rounding a float mesh stores.
    std::vector<glm::dvec3> positions;
    /// Per vertex, as DualMeshSettings::gradients asks (empty with None).
    std::vector<glm::dvec3> gradients;
    /// Triangles, counter-clockwise seen from outside (value >= isovalue).
    std::vector<std::uint32_t> indices;
};

/// Meshes one chunk from its samples (see the file comment). A pure function
/// of its arguments. Preconditions (asserted): `values` set, the aprons
/// above, `fine` set when the signature has a −1, Separate sheets and dual
/// contouring only with an all-zero signature. O(cells³).
DualMeshResult dualMesh(const DualSamples& samples, const DualMeshSettings& settings);

/// dualMesh() into `result`, whose vectors are cleared and refilled, keeping
/// their capacity: a caller that meshes chunk after chunk with one result
/// (per thread) allocates nothing once the buffers have grown.
void dualMesh(const DualSamples& samples, const DualMeshSettings& settings, DualMeshResult& result);

} // namespace strata::meshing
