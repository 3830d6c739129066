// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The CPU reference renderer: rasterizes a mesh as OpenGL does and shades
/// it with the same shared shading header (shaders/TriplanarMaterial.h) and
/// a sampler conformant with GL's (Texture.h).

#include <strata/render/Image.h>
#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace strata::render {

/// What one CPU render did: material map fetches (SAMPLE_MAP calls of the
/// shared shading header; each is one bilinear or trilinear lookup) against
/// those of a naive triplanar shader that samples all three projections of
/// every map it reads (three taps each with anti-tiling), of every layer,
/// at every shaded pixel. The header skips a projection whose blend weight
/// is zero, so fetches <= naiveFetches; the difference is the saving.
/// Shadow-map lookups are not counted.
struct CpuRenderStats
{
    std::uint64_t shadedPixels = 0;   ///< visible pixels shaded (sky pixels are not)
    std::uint64_t textureFetches = 0; ///< map fetches done
    std::uint64_t naiveFetches = 0;   ///< 3 × maps read (× 3 taps with anti-tiling) per layer, summed over shaded pixels
};

/// Renders `mesh` on the CPU: RGBA8, sRGB-encoded, rows top to bottom, the
/// background lighting.skyColor (the sky of lighting.atmosphere when it is on), alpha 255 — the same image as
/// renderSnapshot() up to rasterization and filtering precision.
///
/// Details:
///  - clipping against the near and far planes (and a guard band);
///    perspective-correct interpolation; a float depth buffer with GL_LESS;
///    GL's top-left fill rule on vertices snapped to 1/256 pixel;
///    back faces (clockwise on screen) culled;
///  - options.samples coverage samples per pixel (1, 2, 4, 8 or 16; other
///    counts take the next lower), at GL's standard positions
///    (cpuSamplePositions()), each with its own depth; a pixel's fragment
///    is shaded once per triangle covering any of its samples, at the pixel
///    centre as GL does, stored as 8-bit sRGB at the samples it covers, and
///    the pixel resolved to the rounded mean of those bytes (llvmpipe's
///    resolve); anisotropy is ignored;
///  - fragments are shaded in 2×2 quads: UV derivatives are the differences
///    to the quad neighbour in x and in y of the same triangle's attributes
///    (helper pixels extrapolate, as on a GPU), so the mip level is GL's;
///  - visibility is resolved first (one triangle per pixel), then each
///    visible pixel is shaded once;
///  - sun shadows (options.shadows, on by default): the mesh is first
///    rasterized by the same rasterizer, without culling, into a depth map
///    seen from the sun (orthographic, fitted to the mesh bounds), then each
///    pixel looks it up with shaders/Shadow.h's normal-offset bias (along the
///    interpolated normal) and 4×4 PCF, exactly as the GL renderer does;
///    the result scales the sun's light only;
///  - options.debugView and options.featureMask are honoured as on GL (a
///    debug view is unlit and unshadowed);
///  - the image is split into 32×32 tiles processed in parallel with TBB;
///    each tile depends on nothing but the input, so the bytes are identical
///    for any thread count;
///  - throws strata::Error for invalid options or mesh indices out of range.
/// Complexity O(triangles + pixels · maps + shadow resolution²).
///
/// `stats`, when not null, receives the fetch counters (the same on any
/// thread count).
Image renderSnapshotCpu(const MeshView& mesh, const SnapshotOptions& options, CpuRenderStats* stats = nullptr);

/// Where renderSnapshotCpu() puts the coverage samples of a pixel for
/// `samples`: positions in [0, 1]² in GL window coordinates (origin at the
/// pixel's bottom-left corner, y up), as glGetMultisamplefv reports GL's.
std::vector<glm::vec2> cpuSamplePositions(int samples);

} // namespace strata::render
