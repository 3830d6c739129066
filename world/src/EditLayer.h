// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the sparse edit grid (edited densities at voxel resolution) and
// the read-only snapshots chunk tasks sample from.

#include <strata/world/WorldTypes.h>

#include "Lattice.h"

#include <openvdb/openvdb.h>

#include <filesystem>
#include <mutex>
#include <shared_mutex>
#include <vector>

namespace strata::world::detail {

// Unregistered accessors: every accessor lives inside one lock scope (or on
// a private snapshot), so the tree never changes under one, and none touches
// the tree's registry (a TBB container) from several threads.
using ConstTreeAccessor = openvdb::tree::ValueAccessor<const openvdb::FloatTree, false>;
using TreeAccessor = openvdb::tree::ValueAccessor<openvdb::FloatTree, false>;

/// A private copy of the edit leaves overlapping a box: read by one task only.
class EditSnapshot
{
public:
    EditSnapshot();
    ~EditSnapshot();
    EditSnapshot(const EditSnapshot&) = delete;
    EditSnapshot& operator=(const EditSnapshot&) = delete;
    bool empty() const { return mLeafBoxes.empty(); }
    /// Does any copied leaf overlap `box` (voxel coordinates)?
    bool overlaps(const openvdb::CoordBBox& box) const;
    /// The edited value of a lattice point, if it has one.
    bool lookup(const openvdb::Coord& c, float& value) const;

private:
    friend class EditLayer;
    openvdb::FloatTree::Ptr mTree;
    std::unique_ptr<ConstTreeAccessor> mAccessor;
    std::vector<openvdb::CoordBBox> mLeafBoxes;
};

class EditLayer
{
public:
    explicit EditLayer(double voxelSize);

    /// Applies an edit; returns the lattice points whose value changed.
    /// Serialised with other edits; readers are blocked only while the
    /// changes are written.
    std::vector<openvdb::Coord> apply(const Edit& edit, const terrain::DensityField& field, int band);

    /// Copies the leaves overlapping `box` (shared lock).
    std::unique_ptr<EditSnapshot> snapshot(const openvdb::CoordBBox& box) const;

    /// Effective values (edit or procedural) of `count` lattice points.
    void samples(const terrain::DensityField& field, const openvdb::Coord* points, int count, float* values) const;
    /// Does any edit lie in `box`?
    bool anyIn(const openvdb::CoordBBox& box) const;

    void save(const std::filesystem::path& path) const;
    /// Replaces the grid; returns the lattice points whose value differs.
    std::vector<openvdb::Coord> load(const std::filesystem::path& path);

    std::size_t activeVoxels() const;
    std::size_t memoryBytes() const;

private:
    double mVoxelSize;
    openvdb::FloatGrid::Ptr mGrid;
    /// mGrid's leaves, counted on the editing thread when it changes: the
    /// chunk tasks' snapshot() must not call Tree::leafCount(), a TBB
    /// reduction nested in the task (its join is invisible to
    /// ThreadSanitizer, which then reported the task's later stack use).
    std::size_t mLeafCount = 0;
    mutable std::shared_mutex mLock; ///< guards mGrid's contents and mLeafCount
    std::mutex mWriteMutex;          ///< serialises edits and loads
};

} // namespace strata::world::detail
