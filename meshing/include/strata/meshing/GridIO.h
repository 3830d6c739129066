#pragma once
/// \file
/// OpenVDB .vdb files.

#include <openvdb/openvdb.h>

#include <filesystem>

namespace strata::meshing {

/// Writes `grid` (with its name and metadata) to a .vdb file atomically.
/// The file's UUID, random in OpenVDB, is derived from the file's content
/// instead, so the same grid always gives the same bytes.
/// Throws strata::Error naming the path.
void writeGrid(const openvdb::FloatGrid& grid, const std::filesystem::path& path);

/// Reads the first float grid of a .vdb file and checks it is a usable level
/// set: the file exists and parses, holds a grid, the grid is a FloatGrid of
/// class level set with a uniform linear transform, and it has active voxels.
/// Each failure throws strata::Error saying which check failed and naming
/// the path.
openvdb::FloatGrid::Ptr readLevelSet(const std::filesystem::path& path);

} // namespace strata::meshing
