// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: EXT_meshopt_compression decoded out of a .glb before tinygltf
// (which does not know the extension) parses it.

#include <cstdint>
#include <string>
#include <vector>
#include <string_view>

namespace strata::meshing::detail {

/// Whether the GLB's JSON chunk names EXT_meshopt_compression (a cheap
/// scan; the container must already be checked).
bool usesMeshoptCompression(std::string_view glb);

/// One EXT_meshopt_compression buffer view, checked.
struct MeshoptJob
{
    std::size_t at = 0;                               ///< its offset in the decoded buffer
    std::size_t sourceOffset = 0, sourceLength = 0;   ///< its compressed bytes in the binary chunk
    std::uint64_t count = 0, stride = 0;
    std::string mode, filter;                         ///< as the extension names them
    std::string where;                                ///< "buffer view N's EXT_meshopt_compression"
};

/// A .glb rewritten for tinygltf, and what is left to decode.
struct MeshoptGlb
{
    /// The .glb with the extension removed: compressed views now read
    /// buffer 1 (the decoded buffer, which the parsed model lacks until
    /// decodeMeshoptViews() fills it), fallback buffers dropped, the
    /// binary chunk (the compressed bytes) unchanged.
    std::string glb;
    std::vector<MeshoptJob> jobs;
    std::size_t decodedBytes = 0; ///< the decoded buffer's size
};

/// Checks and rewrites a .glb that uses EXT_meshopt_compression (nothing is
/// decoded yet). Throws strata::Error (BadInput) naming `name` and the
/// buffer view for anything malformed: a mode, filter or stride the
/// extension does not allow, compressed bytes outside the binary chunk, a
/// decoded size larger than its view or than any codec yields, data in
/// other buffers (not supported).
MeshoptGlb decodeMeshoptGlb(std::string_view glb, const std::string& name);

/// Decodes every job (meshoptimizer's attribute, triangle and index
/// sequence codecs, its octahedral, quaternion and exponential filters)
/// from `bin` (the parsed binary chunk) into `decoded` (resized to
/// glb.decodedBytes). Throws strata::Error (BadInput) for a codec error.
void decodeMeshoptViews(const MeshoptGlb& glb, const std::vector<unsigned char>& bin, std::vector<unsigned char>& decoded,
                        const std::string& name);

} // namespace strata::meshing::detail
