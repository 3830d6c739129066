// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// OpenVDB .vdb files.

#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>
#include <vector>

namespace strata::meshing {

/// Writes `grid` (with its name and metadata) to a .vdb file atomically.
/// The file's UUID, random in OpenVDB, is derived from the file's content
/// instead, so the same grid always gives the same bytes.
/// Throws strata::Error naming the path.
void writeGrid(const openvdb::FloatGrid& grid, const std::filesystem::path& path);

/// A grid of a .vdb file that readVdbFile() skipped.
struct UnreadGrid
{
    std::string name;
    std::string type; ///< OpenVDB's grid type, e.g. "Tree_bool_5_4_3"
};

/// The grids of a .vdb file and the file's format version.
struct VdbFile
{
    openvdb::GridPtrVecPtr grids; ///< never null; may be empty
    std::vector<UnreadGrid> unread; ///< grids skipped, in file order (see readVdbFile())
    std::string version;          ///< "FILE/LIBRARY", e.g. "224/10.0"
};

/// Reads every grid of a .vdb file (`strata info` prints them) whose bytes
/// can be checked before OpenVDB reads them: float, double, integer and
/// vector grids in full. Bool, mask and point grids (and grids whose
/// transform OpenVDB does not know) are skipped, unread, through the file's
/// grid offsets and listed in `unread`: their nodes hold bools that OpenVDB
/// reads without checking, and no Strata command uses them. The file is
/// read sequentially, and a file that ends before its last grid does (a
/// truncated or corrupt one) is refused. Throws strata::Error (BadInput)
/// naming the path: missing, a folder, not an OpenVDB file, truncated, a
/// grid to skip in a file without grid offsets.
VdbFile readVdbFile(const std::filesystem::path& path);

/// Reads the first float grid of a .vdb file (through readVdbFile()) and checks it is a usable level
/// set: the file exists and parses, holds a grid, the grid is a FloatGrid of
/// class level set with a uniform linear transform, and it has active voxels.
/// Each failure throws strata::Error saying which check failed and naming
/// the path.
openvdb::FloatGrid::Ptr readLevelSet(const std::filesystem::path& path);

} // namespace strata::meshing
