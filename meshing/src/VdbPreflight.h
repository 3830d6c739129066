// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Checks the parts of a .vdb file that OpenVDB's reader trusts blindly
/// before it reads them: the header, the file's and each grid's metadata,
/// the grid descriptors, the transforms and the root nodes' tiles. Every
/// string length, count and offset there must fit in the file; otherwise
/// OpenVDB allocates whatever the bytes say (a corrupt 16 KiB file asked for
/// gigabytes). A root tile's active flag must be 0 or 1: OpenVDB reads it
/// into a bool (undefined behaviour otherwise). For the standard value trees
/// the nodes below the root are followed too, to every compressed block.

#include <cstdint>
#include <filesystem>
#include <optional>

namespace strata::meshing::detail {

/// The oldest .vdb format version read (OpenVDB 3.0, 2014: node mask
/// compression).
constexpr unsigned MIN_VDB_FILE_VERSION = 222;

/// Throws strata::Error (BadInput) "VDB file 'PATH' ..." naming the first
/// length, count or offset that does not fit in the file (with its byte
/// offset), an unsupported format version, or a metadata value whose size
/// does not match its type, and (where the file records where its grids
/// end) each grid as preflightVdbGrid() does.
void preflightVdbFile(const std::filesystem::path& path);

/// Checks grid `index` of a .vdb file of format version `fileVersion` from
/// its descriptor at byte `offset` (where OpenVDB's reader is about to read
/// it): the descriptor, the grid's metadata, its transform, the root node's
/// background, tile and child counts and tile records (whose active byte,
/// and a bool grid's values, OpenVDB reads straight into a bool), and for
/// the standard value trees (float, double, int32, int64, vec3s/d/i) every
/// node below: masks, compression metadata, and each compressed block's
/// byte count against the file and the node (OpenVDB allocates what a count
/// says). Throws strata::Error (BadInput) "VDB file 'PATH' ..." naming the
/// byte that does not fit. Returns the byte where the grid ends, or nothing
/// where the check stopped early (bool, mask and point trees below the root;
/// a map or grid type OpenVDB does not know).
std::optional<std::uint64_t> preflightVdbGrid(const std::filesystem::path& path, std::uint64_t offset,
                                              std::uint32_t fileVersion, std::int32_t index);

} // namespace strata::meshing::detail
