// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: EXT_meshopt_compression decoded out of a .glb before tinygltf
// (which does not know the extension) parses it.

#include <string>
#include <string_view>

namespace strata::meshing::detail {

/// Whether the GLB's JSON chunk names EXT_meshopt_compression (a cheap
/// scan; the container must already be checked).
bool usesMeshoptCompression(std::string_view glb);

/// The same .glb with every EXT_meshopt_compression buffer view decoded
/// (meshoptimizer's attribute, triangle and index sequence codecs and its
/// octahedral, quaternion and exponential filters) into the binary chunk,
/// the fallback buffers dropped and the extension removed, so the accessors
/// read plain (possibly KHR_mesh_quantization) data. Throws strata::Error
/// (BadInput) naming `name` and the buffer view for anything malformed: a
/// mode, filter or stride the extension does not allow, compressed bytes
/// outside the binary chunk, a decoded size larger than its view, a codec
/// error.
std::string decodeMeshoptGlb(std::string_view glb, const std::string& name);

} // namespace strata::meshing::detail
