// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/SampleLevelSet.h>

#include <strata/Error.h>
#include <strata/Format.h>

#include <openvdb/tools/LevelSetTracker.h>
#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

namespace strata::terrain {

namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using Tree = openvdb::FloatTree;
using Leaf = Tree::LeafNodeType;

constexpr int LEAF_DIM = int(Leaf::DIM); // 8: the tiles we evaluate
/// Top-level pruning blocks, subdivided down to tiles: the size of a
/// level-1 internal node, so a block found all inside is one tile.
constexpr int BLOCK_DIM = int(Tree::RootNodeType::ChildNodeType::ChildNodeType::DIM); // 128
/// Pruning levels inside an evaluated tile: 4³ sub-blocks. Going on to 2³
/// evaluated 30 % fewer points but made 5 times as many bounds() calls, and
/// with block evaluation (a 4³ block in SIMD lanes costs less than bounding
/// its eight 2³ parts) it took 1.3 times longer on the default scene and
/// twice as long on TerrainField (terrain_bench, PruningKeeps... below).
constexpr int SUB_DIMS[] = {4};
constexpr int MAX_HALF_WIDTH = 64;
/// Index coordinates stay well inside int32 (OpenVDB's Coord).
constexpr double MAX_INDEX = 1073741824.0; // 2^30
/// At most this many voxels in the region (2^40), which bounds the coarse
/// pass to 2^19 blocks.
constexpr double MAX_VOXELS = 1099511627776.0;
/// Relative slack on the pruning test: fields are evaluated through float
/// noise, so their interval bounds hold only up to rounding.
constexpr double PRUNE_SLACK = 1e-4;

std::string show(double value) { return formatExact(value); }

void validate(const SampleOptions& o)
{
    if (!(std::isfinite(o.voxelSize) && o.voxelSize > 0.0)) {
        throw Error(ErrorKind::BadInput, "sampling: voxel_size = " + show(o.voxelSize) + " must be a finite number > 0");
    }
    if (o.halfWidth < 3 || o.halfWidth > MAX_HALF_WIDTH) {
        throw Error(ErrorKind::BadInput, "sampling: half_width = " + std::to_string(o.halfWidth) + " is out of range 3.." +
                    std::to_string(MAX_HALF_WIDTH));
    }
    if (o.renormalizeIterations < 1 || o.renormalizeIterations > 64) {
        throw Error(ErrorKind::BadInput, "sampling: renormalize_iterations = " + std::to_string(o.renormalizeIterations) +
                    " is out of range 1..64");
    }
    const char* axes = "xyz";
    for (int a = 0; a < 3; ++a) {
        const double lo = o.region.min[a], hi = o.region.max[a];
        const std::string key = std::string(".") + axes[a];
        if (!std::isfinite(lo) || !std::isfinite(hi)) {
            throw Error(ErrorKind::BadInput, "sampling: region min" + key + " = " + show(lo) + ", max" + key + " = " + show(hi) +
                        " must be finite numbers");
        }
        if (!(hi > lo)) {
            throw Error(ErrorKind::BadInput, "sampling: region is empty: max" + key + " = " + show(hi) + " is not greater than min" +
                        key + " = " + show(lo));
        }
    }
}

/// The voxels whose centre i·voxelSize lies in [min, max), per axis.
CoordBBox indexBox(const Region& region, double voxelSize)
{
    Coord lo, hi;
    const char* axes = "xyz";
    for (int a = 0; a < 3; ++a) {
        const double first = std::ceil(region.min[a] / voxelSize), last = std::floor(region.max[a] / voxelSize);
        if (!(std::abs(first) < MAX_INDEX && std::abs(last) < MAX_INDEX)) {
            throw Error(ErrorKind::BadInput, std::string("sampling: region ") + axes[a] + " range [" + show(region.min[a]) + ", " +
                        show(region.max[a]) + ") is too far out for voxel_size = " + show(voxelSize) +
                        " (more than 2^30 voxels from the origin)");
        }
        // Fix the rounding of the divisions with the exact test on i·voxelSize.
        std::int64_t i = std::int64_t(first), j = std::int64_t(last);
        while (double(i - 1) * voxelSize >= region.min[a]) --i;
        while (double(i) * voxelSize < region.min[a]) ++i;
        while (double(j) * voxelSize >= region.max[a]) --j;
        while (double(j + 1) * voxelSize < region.max[a]) ++j;
        if (j < i) {
            throw Error(ErrorKind::BadInput, std::string("sampling: region ") + axes[a] + " range [" + show(region.min[a]) + ", " +
                        show(region.max[a]) + ") holds no voxel centre at voxel_size = " + show(voxelSize));
        }
        lo[a] = openvdb::Int32(i);
        hi[a] = openvdb::Int32(j);
    }
    const double voxels = double(hi.x() - lo.x() + 1) * double(hi.y() - lo.y() + 1) * double(hi.z() - lo.z() + 1);
    if (voxels > MAX_VOXELS) {
        throw Error(ErrorKind::BadInput, "sampling: region holds " + show(voxels) + " voxels at voxel_size = " + show(voxelSize) +
                    ", more than the limit of 2^40: sample it in chunks or use larger voxels");
    }
    return CoordBBox(lo, hi);
}

/// Bytes of one leaf node: the node (masks, origin, buffer header) and its
/// separately allocated values; leaves are the bulk of a level set.
constexpr std::uint64_t LEAF_BYTES = sizeof(Leaf) + Leaf::SIZE * sizeof(Leaf::ValueType);

std::string showBytes(std::uint64_t bytes)
{
    std::ostringstream out;
    out.precision(3);
    if (bytes >= (1ull << 30)) out << double(bytes) / double(1ull << 30) << " GiB";
    else out << double(bytes) / double(1ull << 20) << " MiB";
    return out.str();
}

/// Upper estimate of the grid's memory: every candidate tile a leaf, plus
/// the internal nodes above them (counted per distinct 128³ and 4096³ node).
std::uint64_t estimateBytes(const std::vector<Coord>& tiles)
{
    using Internal1 = Tree::RootNodeType::ChildNodeType::ChildNodeType;
    using Internal2 = Tree::RootNodeType::ChildNodeType;
    std::uint64_t n1 = 0, n2 = 0;
    Coord last1(std::numeric_limits<int>::min()), last2(std::numeric_limits<int>::min());
    std::vector<Coord> keys1, keys2;
    keys1.reserve(tiles.size());
    for (const Coord& t : tiles) {
        keys1.push_back(Coord(t.x() & ~(int(Internal1::DIM) - 1), t.y() & ~(int(Internal1::DIM) - 1),
                              t.z() & ~(int(Internal1::DIM) - 1)));
        keys2.push_back(Coord(t.x() & ~(int(Internal2::DIM) - 1), t.y() & ~(int(Internal2::DIM) - 1),
                              t.z() & ~(int(Internal2::DIM) - 1)));
    }
    std::sort(keys1.begin(), keys1.end());
    std::sort(keys2.begin(), keys2.end());
    for (const Coord& k : keys1) n1 += (k != last1), last1 = k;
    for (const Coord& k : keys2) n2 += (k != last2), last2 = k;
    return std::uint64_t(tiles.size()) * LEAF_BYTES + n1 * sizeof(Internal1) + n2 * sizeof(Internal2);
}

/// Rounds down to a multiple of `dim` (a power of two), also for negatives.
Coord alignDown(const Coord& c, int dim)
{
    return Coord(c.x() & ~(dim - 1), c.y() & ~(dim - 1), c.z() & ~(dim - 1));
}

/// The field as sampled: the user's field, intersected with the region box
/// when the level set is to be closed.
class Sampler
{
public:
    Sampler(const DensityField& field, const SampleOptions& options, const CoordBBox& box)
        : mField(field), mVoxelSize(options.voxelSize), mClosed(options.closed)
    {
        // The box surface runs half a voxel inside the outermost voxel
        // centres, so the cap's zero crossing lies between sampled voxels.
        const glm::dvec3 lo = world(box.min()) + 0.5 * mVoxelSize;
        const glm::dvec3 hi = world(box.max()) - 0.5 * mVoxelSize;
        mBoxCentre = 0.5 * (lo + hi);
        mBoxHalf = 0.5 * (hi - lo);
    }

    glm::dvec3 world(const Coord& ijk) const
    {
        return glm::dvec3(double(ijk.x()) * mVoxelSize, double(ijk.y()) * mVoxelSize, double(ijk.z()) * mVoxelSize);
    }

    double operator()(const glm::dvec3& p) const
    {
        const double d = mField.density(p);
        return mClosed ? std::max(d, box(p)) : d;
    }

    /// operator() at every point of the block (DensityField::densities).
    void operator()(const PointBlock& points, double* out) const
    {
        mField.densities(points, out);
        if (!mClosed || points.count == 0) return;
        // Where the region's box term is at most every density of the block
        // (the block lies deep enough inside the region) max leaves each
        // value as it is: the box term is 1-Lipschitz, so box(c) + radius
        // bounds it over the block's box (plus a margin far above the
        // rounding of box(), centre() and radius() at these coordinates, so
        // that the bound holds for the computed box(p) as well).
        const glm::dvec3 c = points.box.centre();
        const double radius = points.box.radius();
        const glm::dvec3 extent = glm::abs(c) + glm::abs(mBoxCentre) + mBoxHalf;
        const double scale = extent.x + extent.y + extent.z + radius;
        const double boxMost = box(c) + radius + 1e-12 * scale;
        double least = out[0];
        for (std::size_t i = 1; i < points.count; ++i) least = std::min(least, out[i]);
        if (boxMost <= least) return;
        for (std::size_t i = 0; i < points.count; ++i)
            out[i] = std::max(out[i], box({points.x[i], points.y[i], points.z[i]}));
    }

    /// An interval of operator() over the box (DensityField::bounds; the
    /// region box term is 1-Lipschitz, and max is non-decreasing in both
    /// arguments, so max of the ends bounds max of the values).
    Interval bounds(const WorldBox& b) const
    {
        const Interval d = mField.bounds(b);
        if (!mClosed) return d;
        const double c = box(b.centre()), r = b.radius();
        return {std::max(d.lo, c - r), std::max(d.hi, c + r)};
    }

private:
    /// Exact signed distance to the region box: positive outside.
    double box(const glm::dvec3& p) const
    {
        const glm::dvec3 q = glm::abs(p - mBoxCentre) - mBoxHalf;
        return glm::length(glm::max(q, 0.0)) + std::min(std::max(q.x, std::max(q.y, q.z)), 0.0);
    }

    const DensityField& mField;
    double mVoxelSize;
    bool mClosed;
    glm::dvec3 mBoxCentre{0.0}, mBoxHalf{0.0};
};

/// An aligned cube of voxels (part of it may lie outside the index box)
/// whose in-box voxels all have |density| >= background and the same sign.
struct Uniform
{
    Coord origin;
    int dim;
    bool inside;
};

/// What the coarse pass found in one 128³ block.
struct BlockResult
{
    std::vector<Coord> tiles;      ///< 8³ tiles that may hold the surface
    std::vector<char> tileInBand;  ///< per tile: its bound put it all within the band
    std::vector<Uniform> uniforms; ///< cubes pruned away
    std::uint64_t bounds = 0;      ///< bounds() calls
};

/// What evaluating one 8³ tile gave.
struct TileResult
{
    std::unique_ptr<Leaf> leaf; ///< null when the tile holds no active voxel
    bool inside = false;        ///< the tile's sign when it has no leaf
    std::uint64_t evaluated = 0; ///< density() calls
    std::uint64_t bounds = 0;    ///< bounds() calls
};

class LevelSetSampler
{
public:
    LevelSetSampler(const Sampler& field, const CoordBBox& box, double background, bool closed)
        : mField(field), mBox(box), mBackground(background), mClosed(closed)
    {
    }

    /// What an interval bound says about the voxels of a cube.
    enum class Verdict
    {
        OUTSIDE, ///< every voxel has density >= background: all inactive air
        INSIDE,  ///< every voxel has density <= −background: all inactive rock
        IN_BAND, ///< every voxel has |density| < background: all active, no use bounding parts
        MIXED,   ///< undecided: split it or evaluate its voxels
    };

    /// Bounds the field over the box spanned by the voxel centres of the
    /// aligned cube `cube` (DensityField::bounds). OUTSIDE or INSIDE when the
    /// interval lies entirely at or beyond ±background: every one of those
    /// voxels would be stored as an inactive ±background anyway, with that
    /// sign, so none needs evaluating. IN_BAND when it lies strictly within:
    /// every voxel must be evaluated, so bounding its parts would only cost.
    /// A relative slack of PRUNE_SLACK keeps rounding from deciding. The
    /// whole cube (not its part inside the region) is bounded, so the verdict
    /// depends only on the cube: two regions that share voxels treat them
    /// alike. `evaluations` counts the call (see SampleStats on its cost).
    Verdict classify(const CoordBBox& cube, std::uint64_t& evaluations) const
    {
        ++evaluations;
        const Interval d = mField.bounds({mField.world(cube.min()), mField.world(cube.max())});
        const double outer = mBackground * (1.0 + PRUNE_SLACK), inner = mBackground * (1.0 - PRUNE_SLACK);
        if (d.lo > outer) return Verdict::OUTSIDE;
        if (d.hi < -outer) return Verdict::INSIDE;
        if (d.lo > -inner && d.hi < inner) return Verdict::IN_BAND;
        return Verdict::MIXED;
    }

    /// Coarse pass: subdivides an aligned cube down to 8³ tiles, dropping
    /// every cube whose interval bound puts it all outside the band.
    /// Stops adding tiles once `tileCount` passes `tileLimit`.
    void visit(const Coord& origin, int dim, BlockResult& out, std::atomic<std::uint64_t>& tileCount,
               std::uint64_t tileLimit) const
    {
        const CoordBBox cube(origin, origin.offsetBy(dim - 1));
        CoordBBox clip = cube;
        clip.intersect(mBox);
        if (clip.empty()) return;
        if (tileCount.load(std::memory_order_relaxed) > tileLimit) return;
        const Verdict verdict = classify(cube, out.bounds);
        if (verdict == Verdict::OUTSIDE || verdict == Verdict::INSIDE) {
            out.uniforms.push_back({origin, dim, verdict == Verdict::INSIDE});
        } else if (dim == LEAF_DIM) {
            out.tiles.push_back(origin);
            out.tileInBand.push_back(verdict == Verdict::IN_BAND);
            tileCount.fetch_add(1, std::memory_order_relaxed);
        } else {
            const int half = dim / 2;
            for (int x = 0; x < 2; ++x)
                for (int y = 0; y < 2; ++y)
                    for (int z = 0; z < 2; ++z)
                        visit(origin.offsetBy(x * half, y * half, z * half), half, out, tileCount, tileLimit);
        }
    }

    /// The values of one tile as they are filled in.
    struct Fill
    {
        float values[Leaf::SIZE];
        Leaf::NodeMaskType active;
        bool anyInside = false, anyOutside = false;
    };

    /// Evaluates the voxels of `cube` inside `clip` as one block.
    void evaluateVoxels(const CoordBBox& cube, const CoordBBox& clip, Fill& fill, TileResult& result) const
    {
        CoordBBox sub = cube;
        sub.intersect(clip);
        if (sub.empty()) return;
        double x[Leaf::SIZE], y[Leaf::SIZE], z[Leaf::SIZE], values[Leaf::SIZE];
        openvdb::Index offsets[Leaf::SIZE];
        std::size_t n = 0;
        for (int i = sub.min().x(); i <= sub.max().x(); ++i)
            for (int j = sub.min().y(); j <= sub.max().y(); ++j)
                for (int k = sub.min().z(); k <= sub.max().z(); ++k, ++n) {
                    const Coord ijk(i, j, k);
                    const glm::dvec3 p = mField.world(ijk);
                    x[n] = p.x;
                    y[n] = p.y;
                    z[n] = p.z;
                    offsets[n] = Leaf::coordToOffset(ijk);
                }
        mField(PointBlock{x, y, z, n, {mField.world(sub.min()), mField.world(sub.max())}}, values);
        result.evaluated += n;
        for (std::size_t i = 0; i < n; ++i) {
            const double d = values[i];
            const openvdb::Index offset = offsets[i];
            if (std::abs(d) < mBackground) {
                fill.values[offset] = float(d);
                fill.active.setOn(offset);
            } else {
                fill.values[offset] = float(d < 0.0 ? -mBackground : mBackground);
            }
            (d < 0.0 ? fill.anyInside : fill.anyOutside) = true;
        }
    }

    /// Fills the part inside `clip` of the aligned cube at `origin` of size
    /// `parent` (the tile, or a sub-block of it), whose own bound was MIXED:
    /// each of its SUB_DIMS[level]³ parts is filled whole when its bound
    /// decides it, evaluated voxel by voxel when IN_BAND or at the last
    /// level, else split further.
    void refine(const Coord& origin, int level, const CoordBBox& clip, Fill& fill, TileResult& result) const
    {
        constexpr int LEVELS = int(sizeof(SUB_DIMS) / sizeof(SUB_DIMS[0]));
        const int dim = SUB_DIMS[level];
        const int parent = level == 0 ? LEAF_DIM : SUB_DIMS[level - 1];
        for (int sx = 0; sx < parent; sx += dim)
            for (int sy = 0; sy < parent; sy += dim)
                for (int sz = 0; sz < parent; sz += dim) {
                    const Coord subOrigin = origin.offsetBy(sx, sy, sz);
                    const CoordBBox subCube(subOrigin, subOrigin.offsetBy(dim - 1));
                    CoordBBox sub = subCube;
                    sub.intersect(clip);
                    if (sub.empty()) continue;
                    const Verdict verdict = classify(subCube, result.bounds);
                    if (verdict == Verdict::MIXED && level + 1 < LEVELS) {
                        refine(subOrigin, level + 1, clip, fill, result);
                    } else if (verdict == Verdict::MIXED || verdict == Verdict::IN_BAND) {
                        evaluateVoxels(subCube, clip, fill, result);
                    } else {
                        const bool inside = verdict == Verdict::INSIDE;
                        const float value = float(inside ? -mBackground : mBackground);
                        for (int x = sub.min().x(); x <= sub.max().x(); ++x)
                            for (int y = sub.min().y(); y <= sub.max().y(); ++y)
                                for (int z = sub.min().z(); z <= sub.max().z(); ++z)
                                    fill.values[Leaf::coordToOffset(Coord(x, y, z))] = value;
                        (inside ? fill.anyInside : fill.anyOutside) = true;
                    }
                }
    }

    /// Fine pass: evaluates one 8³ tile, pruning 4³ sub-blocks
    /// by their interval bounds first (unless the tile's own bound put it all
    /// in the band: `inBand`). Active voxels hold |d| < background; the
    /// others hold ±background with the sign of d (of the interval when
    /// pruned).
    TileResult evaluate(const Coord& origin, bool inBand) const
    {
        TileResult result;
        CoordBBox clip(origin, origin.offsetBy(LEAF_DIM - 1));
        clip.intersect(mBox);

        Fill fill;
        if (inBand) evaluateVoxels(CoordBBox(origin, origin.offsetBy(LEAF_DIM - 1)), clip, fill, result);
        else refine(origin, 0, clip, fill, result);

        float* values = fill.values;
        Leaf::NodeMaskType& active = fill.active;
        const bool anyInside = fill.anyInside, anyOutside = fill.anyOutside;
        const float inside = float(-mBackground), outside = float(mBackground);

        if (clip != CoordBBox(origin, origin.offsetBy(LEAF_DIM - 1))) {
            // Voxels outside the region: air when the level set is closed,
            // else the sign of the nearest voxel inside (no crossing at the
            // region boundary).
            for (int x = 0; x < LEAF_DIM; ++x)
                for (int y = 0; y < LEAF_DIM; ++y)
                    for (int z = 0; z < LEAF_DIM; ++z) {
                        const Coord ijk = origin.offsetBy(x, y, z);
                        if (clip.isInside(ijk)) continue;
                        const Coord nearest = Coord::maxComponent(clip.min(), Coord::minComponent(clip.max(), ijk));
                        values[Leaf::coordToOffset(ijk)] =
                            mClosed ? outside : (values[Leaf::coordToOffset(nearest)] < 0.0f ? inside : outside);
                    }
        }

        // A tile with no active voxel is all one sign (the field cannot
        // change sign between neighbours without passing |d| < background),
        // unless it is very steep: then keep it as a leaf.
        if (active.isOff() && !(anyInside && anyOutside)) {
            result.inside = anyInside;
            return result;
        }
        result.leaf = std::make_unique<Leaf>(origin, outside, false);
        for (openvdb::Index i = 0; i < Leaf::SIZE; ++i) result.leaf->setValueOnly(i, values[i]);
        result.leaf->setValueMask(active);
        return result;
    }

private:
    const Sampler& mField;
    CoordBBox mBox;
    double mBackground;
    bool mClosed;
};

void reportProgress(const SampleOptions& options, double fraction)
{
    if (options.progress && !options.progress(fraction)) throw Error(ErrorKind::Interrupted, "sampling interrupted");
}

} // namespace

openvdb::FloatGrid::Ptr sampleLevelSet(const DensityField& field, const SampleOptions& options, SampleStats* stats)
{
    validate(options);
    openvdb::initialize();

    const double background = double(options.halfWidth) * options.voxelSize;
    const CoordBBox box = indexBox(options.region, options.voxelSize);
    const Sampler sampler(field, options, box);
    const LevelSetSampler levelSet(sampler, box, background, options.closed);
    reportProgress(options, 0.0);

    // Coarse pass over 128³ blocks, in parallel; each block's lists come out
    // in a fixed order, and blocks are concatenated in index order.
    std::vector<Coord> blocks;
    const Coord blockMin = alignDown(box.min(), BLOCK_DIM), blockMax = alignDown(box.max(), BLOCK_DIM);
    for (int x = blockMin.x(); x <= blockMax.x(); x += BLOCK_DIM)
        for (int y = blockMin.y(); y <= blockMax.y(); y += BLOCK_DIM)
            for (int z = blockMin.z(); z <= blockMax.z(); z += BLOCK_DIM) blocks.emplace_back(x, y, z);
    std::vector<BlockResult> blockResults(blocks.size());
    // With a memory budget, stop collecting tiles well past it (the tile list
    // of a huge region could itself exhaust memory).
    std::atomic<std::uint64_t> tileCount{0};
    const std::uint64_t tileLimit = options.maxMemoryBytes > 0
                                        ? 4 * (options.maxMemoryBytes / LEAF_BYTES + 1)
                                        : std::numeric_limits<std::uint64_t>::max();
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks.size()), [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
            levelSet.visit(blocks[i], BLOCK_DIM, blockResults[i], tileCount, tileLimit);
        }
    });

    std::vector<Coord> tiles;
    std::vector<char> tileInBand;
    std::vector<Uniform> uniforms;
    std::uint64_t evaluated = 0, bounded = 0;
    for (const BlockResult& b : blockResults) {
        tiles.insert(tiles.end(), b.tiles.begin(), b.tiles.end());
        tileInBand.insert(tileInBand.end(), b.tileInBand.begin(), b.tileInBand.end());
        uniforms.insert(uniforms.end(), b.uniforms.begin(), b.uniforms.end());
        bounded += b.bounds;
    }
    blockResults.clear();
    const std::uint64_t estimate = estimateBytes(tiles);
    if (stats) stats->estimatedBytes = estimate;
    if (options.maxMemoryBytes > 0 && (estimate > options.maxMemoryBytes || tileCount.load() > tileLimit)) {
        throw Error(ErrorKind::BadInput, "sampling: the grid would need " + std::string(tileCount.load() > tileLimit ? "more than " : "about ") +
                    showBytes(estimate) + ", more than the memory budget of " + showBytes(options.maxMemoryBytes) +
                    ": use a coarser voxel_size (doubling it needs about 4x less) or a smaller region, or raise "
                    "--max-memory");
    }
    constexpr double COARSE_SHARE = 0.05; // of the progress bar
    reportProgress(options, COARSE_SHARE);

    // Fine pass over the surviving tiles, in parallel, in chunks so that
    // progress is reported (and interruption honoured) from this thread.
    std::vector<TileResult> results(tiles.size());
    const std::size_t chunk = std::max<std::size_t>(256, tiles.size() / 64);
    for (std::size_t begin = 0; begin < tiles.size(); begin += chunk) {
        const std::size_t end = std::min(tiles.size(), begin + chunk);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(begin, end), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) results[i] = levelSet.evaluate(tiles[i], tileInBand[i] != 0);
        });
        reportProgress(options, COARSE_SHARE + (1.0 - 2.0 * COARSE_SHARE) * double(end) / double(tiles.size()));
    }

    // Assemble serially, leaves sorted by origin: the tree is the same
    // whatever the thread count.
    std::vector<std::size_t> order(tiles.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return tiles[a] < tiles[b]; });

    auto tree = std::make_shared<Tree>(float(background));
    for (std::size_t i : order) {
        evaluated += results[i].evaluated;
        bounded += results[i].bounds;
        if (results[i].leaf) {
            tree->addLeaf(results[i].leaf.release());
        } else {
            uniforms.push_back({tiles[i], LEAF_DIM, results[i].inside});
        }
    }
    results.clear();

    // Sign the interior explicitly. Every tile of the region is a leaf or
    // lies in a uniform cube whose sign is known, so inside tiles become
    // -background tiles and everything else stays background (air). This is
    // what signedFloodFill would infer by scanlines, but stays right where
    // the region boundary cuts the narrow band open, which the scanline
    // inference does not.
    {
        openvdb::tree::ValueAccessor<Tree> acc(*tree);
        for (const Uniform& u : uniforms) {
            if (!u.inside) continue;
            CoordBBox clip(u.origin, u.origin.offsetBy(u.dim - 1));
            if (u.dim == BLOCK_DIM && box.isInside(clip)) {
                acc.addTile(2, u.origin, float(-background), false); // a whole level-1 node
                continue;
            }
            clip.intersect(box);
            const Coord first = alignDown(clip.min(), LEAF_DIM), last = alignDown(clip.max(), LEAF_DIM);
            for (int x = first.x(); x <= last.x(); x += LEAF_DIM)
                for (int y = first.y(); y <= last.y(); y += LEAF_DIM)
                    for (int z = first.z(); z <= last.z(); z += LEAF_DIM)
                        acc.addTile(1, Coord(x, y, z), float(-background), false);
        }
    }
    // Merge uniform tiles into coarser ones (deterministic).
    openvdb::tools::prune(*tree);

    auto grid = openvdb::FloatGrid::create(tree);
    grid->setTransform(openvdb::math::Transform::createLinearTransform(options.voxelSize));
    grid->setGridClass(openvdb::GRID_LEVEL_SET);
    grid->setName("surface");
    if (stats) stats->activeVoxelsBeforeRenormalize = grid->activeVoxelCount();

    if (options.renormalize) {
        // Reinitialise the band to a signed distance: upwind first-order
        // Eikonal iterations (OpenVDB's LevelSetTracker), then drop voxels
        // that end up beyond the half width. Each iteration reads only the
        // previous one's buffer, so the result is the same on any thread count.
        openvdb::tools::LevelSetTracker<openvdb::FloatGrid> tracker(*grid);
        tracker.setSpatialScheme(openvdb::math::FIRST_BIAS);
        tracker.setTemporalScheme(openvdb::math::TVD_RK1);
        tracker.setNormCount(options.renormalizeIterations);
        tracker.normalize();
        tracker.prune();
        // Values clamped to ±background outside the band keep their sign.
        openvdb::tools::prune(grid->tree());
    }

    if (stats) {
        const Coord tileMin = alignDown(box.min(), LEAF_DIM), tileMax = alignDown(box.max(), LEAF_DIM);
        std::uint64_t visited = 1;
        for (int a = 0; a < 3; ++a) visited *= std::uint64_t((tileMax[a] - tileMin[a]) / LEAF_DIM + 1);
        stats->evaluatedPoints = evaluated + bounded;
        stats->boundEvaluations = bounded;
        stats->activeVoxels = grid->activeVoxelCount();
        stats->tilesVisited = visited;
        stats->tilesSkipped = visited - tiles.size();
    }
    reportProgress(options, 1.0);
    return grid;
}

} // namespace strata::terrain
