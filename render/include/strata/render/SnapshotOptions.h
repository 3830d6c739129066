// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// What a snapshot renders, shared by the GL and the CPU renderer.

#include <strata/render/Camera.h>
#include <strata/render/Material.h>
#include <strata/render/Texture.h>

namespace strata::render {

/// Shadows from the sun (Lighting::sunDirection), the same algorithm on the
/// GL and the CPU renderer (shaders/Shadow.h): an orthographic shadow map
/// fitted to the mesh bounds, looked up with a normal-offset bias along the
/// interpolated surface normal and a fixed 4×4-texel PCF kernel.
struct ShadowOptions
{
    bool enabled = true;
    int resolution = 2048;   ///< shadow-map texels per side, 16..16384 (memory: 4 bytes per texel)
    /// Lookup offset along the interpolated normal, in texels × sin(normal,
    /// sun), 0..16; >= 2 (the PCF kernel's reach) avoids acne at any angle.
    float normalBias = 2.5f;
    float depthBias = 1.0f;  ///< lookup offset towards the sun, in texels, 0..16
};

/// What the renderer shows: the lit material, or one of the debug views
/// (the same values as DEBUG_VIEW_* in shaders/TriplanarMaterial.h). The data
/// views store value v as the byte round(255·v).
enum class DebugView
{
    Shaded = 0,           ///< the lit, tone-mapped material
    TriplanarWeights = 1, ///< blend weights X, Y, Z as red, green, blue
    WorldNormals = 2,     ///< the mapped world normal as n·½ + ½
    Metallic = 3,         ///< grey
    Occlusion = 4,        ///< grey, after occlusionStrength
    Height = 5,           ///< mask B (height; the detail mask with MODS), grey
    Smoothness = 6,       ///< grey, after detail
    Albedo = 7,           ///< albedo with tint and detail, unlit
    Layers = 8,           ///< terrain layers' weights: base dark grey, then red, green, blue, yellow, cyan, magenta, white
    // The mesh's landform masks (MeshView::landform; 0 without), each on a colour ramp:
    Flow = 9,        ///< log10 drainage area 0..7: dark navy, blue, pale blue
    Wear = 10,       ///< metres eroded 0..20: dark brown, orange, pale
    Deposition = 11, ///< metres of sediment 0..20: dark olive, ochre, sand
    Water = 12,      ///< 0 dry .. 1 river or lake: dark grey, teal, cyan
    // The mesh's rock masks (MeshView::rock; 0 without):
    Hardness = 13, ///< 0 soft .. 1 hard: plum, rose, cream
    Bed = 14,      ///< the bed's index, one colour each (neighbouring beds differ)
};
inline constexpr int DEBUG_VIEW_COUNT = 15;

/// Whether `view` shows the mesh's landform masks (Flow .. Water).
inline bool isLandformView(DebugView view) { return view >= DebugView::Flow && view <= DebugView::Water; }
/// Whether `view` shows the mesh's rock masks (Hardness, Bed).
inline bool isRockView(DebugView view) { return view == DebugView::Hardness || view == DebugView::Bed; }

/// "shaded", "weights", "normals", "metallic", "occlusion", "height",
/// "smoothness", "albedo", "layers", "flow", "wear", "deposition", "water",
/// "hardness", "bed".
const char* debugViewName(DebugView view);

struct SnapshotOptions
{
    int width = 1280; ///< pixels, 1..16384
    int height = 720; ///< pixels, 1..16384
    int samples = 4;  ///< MSAA samples per pixel (1 = off), on GL and on the CPU renderer
    /// GL: maximum anisotropic filtering (1 = plain trilinear, up to 16;
    /// clamped to what the driver offers). Trilinear is what the CPU
    /// reference sampler does; anisotropy sharpens grazing views but costs
    /// about 6× the render time on Mesa llvmpipe (measured: 0.64 s → 4.4 s
    /// at 1280×720). Ignored by the CPU renderer.
    float anisotropy = 1.0f;
    /// Minification filter of the maps, the same on both renderers
    /// (Texture.h): trilinear (default) or bilinear in the nearest mip level.
    TextureFilter filtering = TextureFilter::Trilinear;
    /// CPU renderer: the log2 of its level of detail, exact as the GL
    /// specification defines it (default) or llvmpipe's approximation (to
    /// hold the CPU to llvmpipe bit for bit). GL ignores it.
    LodLog2 cpuLodLog2 = LodLog2::Exact;
    Camera camera;
    Lighting lighting;
    Material material;
    DebugView debugView = DebugView::Shaded; ///< a debug view instead of the lit material
    /// ANDed with the material's feature set (materialFeatures()): a bit
    /// cleared here switches that feature off (see effectiveFeatures()).
    std::uint32_t featureMask = feature::ALL;
    ShadowOptions shadows;
};

/// Throws strata::Error "snapshot: ..." for invalid options (size, samples,
/// material ranges, camera planes, shadow resolution and biases).
void checkSnapshotOptions(const SnapshotOptions& options);

} // namespace strata::render
