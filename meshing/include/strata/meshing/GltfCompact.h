// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Compact binary glTF: KHR_mesh_quantization (16-bit integer positions
/// dequantized by the node's scale and translation, octahedral normals) and
/// EXT_meshopt_compression (meshoptimizer's vertex and index codecs), the
/// form `strata bake` writes its tiles in by default. readGltf() and
/// parseGlb() read it back (decode, dequantize).

#include <strata/meshing/GltfIO.h>

#include <string>
#include <vector>

namespace strata::meshing {

/// Options for encodeCompactGlb().
struct CompactGlbOptions
{
    /// The position grid in metres (> 0). Every position p (relative to the
    /// origin) is stored as the integer n = floor(p / positionStep + 1/2)
    /// (halves rounded up, the same on either side of the origin), so the
    /// decoded point is origin + n·positionStep and its error is at most
    /// positionStep / 2 per axis. Meshes whose origins are multiples of
    /// `positionStep` share one world-aligned grid: a point two of them hold
    /// (a seam vertex) decodes to the same world point in both.
    /// A primitive spans at most 65535 steps per axis; where a mesh is wider
    /// the step is doubled until it fits (CompactGlbStats::positionStep says
    /// which was used); compactPositionStep() picks one that fits.
    double positionStep = 1.0 / 128.0;
    /// Bits per component of the octahedral normals (meshopt's OCTAHEDRAL
    /// filter), 2..16: up to 8 stores a normal in 4 bytes (glTF BYTE,
    /// normalized), more in 8 (SHORT). 8 bits: within 1° of the normal.
    int normalBits = 8;
    /// Reorder each primitive's triangles for the vertex cache and its
    /// vertices in first-use order (meshoptimizer), which the codecs
    /// compress better. The triangles and their windings stay the same.
    bool optimizeOrder = true;
};

/// What encodeCompactGlb() wrote.
struct CompactGlbStats
{
    double positionStep = 0.0;     ///< the step used (metres)
    double maxPositionError = 0.0; ///< largest |decoded − input| over all components (metres)
    double maxNormalAngle = 0.0;   ///< largest angle between a decoded and its input normal (radians)
};

/// The finest grid step unit·2^k (k any integer) over which `extent`
/// metres span at most 65535 steps: for a tile of a bake, `unit` the voxel
/// size and `extent` the tile's widest reach including skirts, so every
/// tile of the bake shares one world-aligned grid.
double compactPositionStep(double extent, double unit);

/// The bytes of a .glb with the same meshes, node, materials and primitives
/// as encodeGlb() (positions relative to `origin`, normals, _SURFACE and
/// _LANDFORM when present), compact: POSITION as VEC3 unsigned short (not
/// normalized) on options.positionStep's grid, the node's scale the step and
/// its translation `origin` plus the primitives' common grid offset; NORMAL
/// as octahedral-encoded normalized BYTE (or SHORT); _SURFACE and _LANDFORM
/// as float (lossless); indices uint16 where a primitive has at most 65535
/// vertices, else uint32. Every buffer view is compressed
/// (EXT_meshopt_compression: attributes mode for vertices, triangles mode
/// for indices) into the GLB's binary chunk; the views' own buffer is a
/// fallback buffer with no data, so both extensions are required: a client
/// that does not know them refuses the file rather than drawing garbage.
/// `stats` (may be null) receives the step used and the measured errors.
/// Throws strata::Error (BadInput) for a step that is not positive and
/// finite or a normalBits outside 2..16, (Internal) if an encoder fails.
std::string encodeCompactGlb(const std::vector<GlbPart>& parts, const glm::dvec3& origin, const std::string& name,
                             const CompactGlbOptions& options = {}, CompactGlbStats* stats = nullptr);

} // namespace strata::meshing
