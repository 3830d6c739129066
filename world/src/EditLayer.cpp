// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "EditLayer.h"
#include <strata/detail/TsanHandOver.h>

#include <strata/Error.h>
#include <strata/IntegerMath.h>
#include <strata/meshing/GridIO.h>
#include <strata/terrain/Csg.h>

#include <openvdb/io/File.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

namespace strata::world::detail {

using strata::detail::tsanHandOff;
using strata::detail::tsanTakeOver;

using openvdb::Coord;
using openvdb::CoordBBox;

namespace {

/// Tree::leafCount() without TBB: a walk on this thread.
std::size_t countLeaves(const openvdb::FloatTree& tree)
{
    std::size_t count = 0;
    for (auto it = tree.cbeginLeaf(); it; ++it) ++count;
    return count;
}

} // namespace

EditSnapshot::EditSnapshot()
    : mTree(new openvdb::FloatTree(0.0f))
{
}

EditSnapshot::~EditSnapshot()
{
    // A snapshot holds a chunk's few leaves and dies inside a chunk task.
    // Tree's own destructor frees nodes with a tbb::parallel_for, which
    // there only spreads a handful of deletes over workers that are busy
    // with other chunks, and leaves a TBB join node on this worker's stack
    // written by another thread through libtbb's (uninstrumented)
    // synchronisation: ThreadSanitizer then reports the next task's stack
    // variables at that address (a CI run failed so). Freed here, in order.
    mAccessor.reset();
    if (!mTree) return;
    using Leaf = openvdb::FloatTree::LeafNodeType;
    using Lower = openvdb::FloatTree::RootNodeType::ChildNodeType::ChildNodeType;
    using Upper = openvdb::FloatTree::RootNodeType::ChildNodeType;
    std::vector<Leaf*> leaves;
    mTree->stealNodes(leaves);
    for (Leaf* leaf : leaves) delete leaf;
    std::vector<Lower*> lower;
    mTree->stealNodes(lower);
    for (Lower* node : lower) delete node;
    std::vector<Upper*> upper;
    mTree->stealNodes(upper);
    for (Upper* node : upper) delete node;
}

bool EditSnapshot::overlaps(const CoordBBox& box) const
{
    for (const CoordBBox& leaf : mLeafBoxes)
        if (leaf.hasOverlap(box)) return true;
    return false;
}

bool EditSnapshot::lookup(const Coord& c, float& value) const
{
    if (mLeafBoxes.empty()) return false;
    return mAccessor->probeValue(c, value);
}

EditLayer::EditLayer(double voxelSize)
    : mVoxelSize(voxelSize)
    , mGrid(openvdb::FloatGrid::create(0.0f))
{
    mGrid->setName("edits");
    mGrid->setTransform(openvdb::math::Transform::createLinearTransform(voxelSize));
}

std::vector<Coord> EditLayer::apply(const Edit& edit, const terrain::DensityField& field, int band)
{
    const EditShape& shape = edit.shape;
    const double k = edit.smoothRadius;
    const double bandWidth = band * mVoxelSize;
    const float bandValue = float(bandWidth);
    glm::dvec3 lo, hi;
    shape.bounds(lo, hi);
    lo -= bandWidth + k;
    hi += bandWidth + k;
    const Coord cmin(ceilToInt<int>(lo.x / mVoxelSize), ceilToInt<int>(lo.y / mVoxelSize),
                     ceilToInt<int>(lo.z / mVoxelSize));
    const Coord cmax(floorToInt<int>(hi.x / mVoxelSize), floorToInt<int>(hi.y / mVoxelSize),
                     floorToInt<int>(hi.z / mVoxelSize));
    const bool dig = edit.mode == EditMode::DIG;

    std::lock_guard<std::mutex> writer(mWriteMutex);
    // Only this thread writes the grid (mWriteMutex), so reading it here
    // without the shared lock races with nothing.
    using Change = std::pair<Coord, float>;
    const int slices = std::max(0, cmax.z() - cmin.z() + 1);
    std::vector<std::vector<Change>> perSlice(slices);
    const openvdb::FloatTree& tree = mGrid->tree();
    {
        // The bodies read the grid without mLock, and that is safe: the only
        // writers (apply() and load()) hold mWriteMutex, which this thread
        // holds until after the writes below, so nothing writes the grid
        // while the bodies run; concurrent snapshot()/samples() only read.
        // The bodies' reads happen before the writes below because
        // parallel_for returns only after every body has ended (TBB's
        // fork-join). A shared lock per body added nothing but cost; the
        // annotations tell ThreadSanitizer, which cannot see TBB's
        // synchronisation, about those two edges (no-ops in other builds).
        tsanHandOff(&perSlice);
        tbb::parallel_for(tbb::blocked_range<int>(0, slices), [&](const tbb::blocked_range<int>& r) {
            tsanTakeOver(&perSlice);
            ConstTreeAccessor acc(tree);
            for (int s = r.begin(); s != r.end(); ++s) {
                const int z = cmin.z() + s;
                std::vector<Change>& out = perSlice[s];
                for (int y = cmin.y(); y <= cmax.y(); ++y) {
                    for (int x = cmin.x(); x <= cmax.x(); ++x) {
                        const glm::dvec3 p(double(x) * mVoxelSize, double(y) * mVoxelSize, double(z) * mVoxelSize);
                        const double sd = shape.distance(p);
                        if (sd >= bandWidth + k) continue;
                        const Coord c(x, y, z);
                        float current;
                        const bool edited = acc.probeValue(c, current);
                        float next;
                        if (sd <= -bandWidth) {
                            // Deep inside: the result is beyond the band whatever
                            // the value was, so it is stored clamped.
                            next = dig ? bandValue : -bandValue;
                            if (edited && current == next) continue;
                        } else {
                            if (!edited) current = baseSample(field, x, y, z, mVoxelSize);
                            const double v = dig ? terrain::smoothMax(current, -sd, k) : terrain::smoothMin(current, sd, k);
                            next = float(v);
                            // A fill makes the closed shape rock: a point on its
                            // surface must not stay at 0 (air).
                            if (!dig && sd <= 0.0 && !(next < 0.0f)) next = -std::numeric_limits<float>::min();
                            if (next == current) continue;
                            next = std::clamp(next, -bandValue, bandValue);
                            if (edited && next == current) continue;
                        }
                        out.emplace_back(c, next);
                    }
                }
            }
            tsanHandOff(&tree); // this body's reads and its slices, for after the join
        });
        tsanTakeOver(&tree);
    }

    std::vector<Coord> changed;
    {
        std::unique_lock<std::shared_mutex> lock(mLock);
        std::size_t total = 0;
        for (const auto& s : perSlice) total += s.size();
        changed.reserve(total);
        TreeAccessor acc(mGrid->tree());
        for (const auto& s : perSlice) {
            for (const Change& ch : s) {
                acc.setValueOn(ch.first, ch.second);
                changed.push_back(ch.first);
            }
        }
        mLeafCount = countLeaves(mGrid->tree());
    }
    return changed;
}

std::unique_ptr<EditSnapshot> EditLayer::snapshot(const CoordBBox& box) const
{
    auto snap = std::make_unique<EditSnapshot>();
    {
        std::shared_lock<std::shared_mutex> lock(mLock);
        const openvdb::FloatTree& tree = mGrid->tree();
        const std::size_t leafCount = mLeafCount;
        const Coord lo = box.min() & ~(openvdb::FloatTree::LeafNodeType::DIM - 1);
        const Coord hi = box.max();
        const std::int64_t dim = openvdb::FloatTree::LeafNodeType::DIM;
        const std::int64_t probes = ((hi.x() - lo.x()) / dim + 1) * ((hi.y() - lo.y()) / dim + 1) *
                                    ((hi.z() - lo.z()) / dim + 1);
        auto take = [&](const openvdb::FloatTree::LeafNodeType& leaf) {
            snap->mTree->addLeaf(new openvdb::FloatTree::LeafNodeType(leaf));
            snap->mLeafBoxes.push_back(leaf.getNodeBoundingBox());
        };
        if (leafCount == 0) {
        } else if (std::uint64_t(probes) < leafCount) {
            ConstTreeAccessor acc(tree);
            for (int z = lo.z(); z <= hi.z(); z += int(dim))
                for (int y = lo.y(); y <= hi.y(); y += int(dim))
                    for (int x = lo.x(); x <= hi.x(); x += int(dim))
                        if (const auto* leaf = acc.probeConstLeaf(Coord(x, y, z))) take(*leaf);
        } else {
            for (auto it = tree.cbeginLeaf(); it; ++it)
                if (it->getNodeBoundingBox().hasOverlap(box)) take(*it);
        }
    }
    snap->mAccessor = std::make_unique<ConstTreeAccessor>(*snap->mTree);
    return snap;
}

void EditLayer::samples(const terrain::DensityField& field, const Coord* points, int count, float* values) const
{
    std::vector<char> edited(std::size_t(count), 0);
    {
        std::shared_lock<std::shared_mutex> lock(mLock);
        ConstTreeAccessor acc(mGrid->tree());
        for (int i = 0; i < count; ++i) edited[i] = acc.probeValue(points[i], values[i]);
    }
    for (int i = 0; i < count; ++i)
        if (!edited[i]) values[i] = baseSample(field, points[i].x(), points[i].y(), points[i].z(), mVoxelSize);
}

bool EditLayer::anyIn(const CoordBBox& box) const
{
    std::shared_lock<std::shared_mutex> lock(mLock);
    const openvdb::FloatTree& tree = mGrid->tree();
    if (mLeafCount == 0) return false;
    ConstTreeAccessor acc(tree);
    const int dim = openvdb::FloatTree::LeafNodeType::DIM;
    const Coord lo = box.min() & ~(dim - 1);
    for (int z = lo.z(); z <= box.max().z(); z += dim)
        for (int y = lo.y(); y <= box.max().y(); y += dim)
            for (int x = lo.x(); x <= box.max().x(); x += dim)
                if (const auto* leaf = acc.probeConstLeaf(Coord(x, y, z))) {
                    for (auto it = leaf->cbeginValueOn(); it; ++it)
                        if (box.isInside(it.getCoord())) return true;
                }
    return false;
}

void EditLayer::save(const std::filesystem::path& path) const
{
    openvdb::FloatGrid::Ptr copy;
    {
        std::shared_lock<std::shared_mutex> lock(mLock);
        copy = mGrid->deepCopy();
    }
    copy->setName("edits");
    copy->setGridClass(openvdb::GRID_UNKNOWN);
    copy->insertMeta("strata_world_edits", openvdb::BoolMetadata(true));
    meshing::writeGrid(*copy, path);
}

std::vector<Coord> EditLayer::load(const std::filesystem::path& path)
{
    openvdb::initialize();
    const std::string where = "edit file '" + path.string() + "'";
    if (!std::filesystem::exists(path)) throw Error(ErrorKind::BadInput, where + " does not exist");
    openvdb::FloatGrid::Ptr grid;
    try {
        openvdb::io::File file(path.string());
        file.open();
        if (!file.hasGrid("edits")) {
            file.close();
            throw Error(ErrorKind::BadInput, where + " holds no grid named \"edits\"");
        }
        openvdb::GridBase::Ptr base = file.readGrid("edits");
        file.close();
        grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) throw Error(ErrorKind::BadInput, where + ": grid \"edits\" is a " + base->type() + ", not a float grid");
    } catch (const openvdb::Exception& e) {
        throw Error(ErrorKind::BadInput, where + " cannot be read: " + e.what());
    }
    const openvdb::Vec3d vs = grid->voxelSize();
    if (!grid->transform().isLinear() || std::abs(vs.x() - mVoxelSize) > 1e-9 * mVoxelSize ||
        std::abs(vs.y() - mVoxelSize) > 1e-9 * mVoxelSize || std::abs(vs.z() - mVoxelSize) > 1e-9 * mVoxelSize) {
        throw Error(ErrorKind::BadInput, where + ": voxel size " + std::to_string(vs.x()) + " differs from the world's voxelSize = " +
                    std::to_string(mVoxelSize));
    }
    grid->setTransform(openvdb::math::Transform::createLinearTransform(mVoxelSize));

    std::lock_guard<std::mutex> writer(mWriteMutex);
    std::vector<Coord> changed;
    {
        ConstTreeAccessor oldAcc(mGrid->tree()), newAcc(grid->tree());
        float a, b;
        for (auto it = mGrid->tree().cbeginValueOn(); it; ++it) {
            // Tiles never occur (edits set single voxels), but be safe.
            const openvdb::CoordBBox box = it.getBoundingBox();
            for (auto c = box.begin(); c; ++c) {
                a = oldAcc.getValue(*c);
                if (!newAcc.probeValue(*c, b) || a != b) changed.push_back(*c);
            }
        }
        for (auto it = grid->tree().cbeginValueOn(); it; ++it) {
            const openvdb::CoordBBox box = it.getBoundingBox();
            for (auto c = box.begin(); c; ++c) {
                if (!oldAcc.probeValue(*c, a)) changed.push_back(*c);
            }
        }
    }
    const std::size_t leaves = countLeaves(grid->tree());
    {
        std::unique_lock<std::shared_mutex> lock(mLock);
        mGrid = grid;
        mLeafCount = leaves;
    }
    return changed;
}

// Counted by walking the leaves on this thread: OpenVDB's counters run on
// TBB, whose synchronisation ThreadSanitizer cannot see. Edits set single
// voxels, so the tree holds no active tiles.
std::size_t EditLayer::activeVoxels() const
{
    std::shared_lock<std::shared_mutex> lock(mLock);
    std::size_t count = 0;
    for (auto it = mGrid->tree().cbeginLeaf(); it; ++it) count += std::size_t(it->onVoxelCount());
    return count;
}

std::size_t EditLayer::memoryBytes() const
{
    std::shared_lock<std::shared_mutex> lock(mLock);
    std::size_t bytes = sizeof(openvdb::FloatTree);
    for (auto it = mGrid->tree().cbeginLeaf(); it; ++it) bytes += std::size_t(it->memUsage());
    return bytes;
}

} // namespace strata::world::detail
