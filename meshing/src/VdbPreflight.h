#pragma once
/// \file
/// Checks the parts of a .vdb file that OpenVDB's reader trusts blindly
/// before it reads them: the header, the file's and each grid's metadata,
/// the grid descriptors and the transform's type name. Every string length,
/// count and offset there must fit in the file; otherwise OpenVDB allocates
/// whatever the bytes say (a corrupt 16 KiB file asked for gigabytes).

#include <filesystem>

namespace strata::meshing::detail {

/// The oldest .vdb format version read (OpenVDB 3.0, 2014: node mask
/// compression).
constexpr unsigned MIN_VDB_FILE_VERSION = 222;

/// Throws strata::Error (BadInput) "VDB file 'PATH' ..." naming the first
/// length, count or offset that does not fit in the file (with its byte
/// offset), an unsupported format version, or a metadata value whose size
/// does not match its type. The grids' trees are not checked here.
void preflightVdbFile(const std::filesystem::path& path);

} // namespace strata::meshing::detail
