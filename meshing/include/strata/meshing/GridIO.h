#pragma once
/// \file
/// OpenVDB .vdb files.

#include <openvdb/openvdb.h>

#include <filesystem>
#include <string>

namespace strata::meshing {

/// Writes `grid` (with its name and metadata) to a .vdb file atomically.
/// The file's UUID, random in OpenVDB, is derived from the file's content
/// instead, so the same grid always gives the same bytes.
/// Throws strata::Error naming the path.
void writeGrid(const openvdb::FloatGrid& grid, const std::filesystem::path& path);

/// The grids of a .vdb file and the file's format version, read in full.
struct VdbFile
{
    openvdb::GridPtrVecPtr grids; ///< never null; may be empty
    std::string version;          ///< "FILE/LIBRARY", e.g. "224/10.0"
};

/// Reads every grid of a .vdb file (`strata info` prints them). The file is
/// read sequentially, and a file that ends before its last grid does (a
/// truncated or corrupt one) is refused. Throws strata::Error (BadInput)
/// naming the path: missing, a folder, not an OpenVDB file, truncated.
VdbFile readVdbFile(const std::filesystem::path& path);

/// Reads the first float grid of a .vdb file (through readVdbFile()) and checks it is a usable level
/// set: the file exists and parses, holds a grid, the grid is a FloatGrid of
/// class level set with a uniform linear transform, and it has active voxels.
/// Each failure throws strata::Error saying which check failed and naming
/// the path.
openvdb::FloatGrid::Ptr readLevelSet(const std::filesystem::path& path);

} // namespace strata::meshing
