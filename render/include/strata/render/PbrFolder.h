// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// PBR texture folders as CC0 libraries ship them (ambientCG, Poly Haven,
/// cgbookcase, 3dtextures.me...): the maps of one material, told apart by
/// their file names, classified and packed into the renderers' maps (an sRGB
/// albedo, a MOHS mask, an OpenGL normal map).

#include <strata/render/Texture.h>

#include <filesystem>

namespace strata::render {

/// The map files of one PBR folder; an empty path is a map the folder lacks.
struct PbrFiles
{
    std::filesystem::path albedo;     ///< base colour (always set by findPbrFiles)
    std::filesystem::path normal;     ///< tangent-space normal map
    std::filesystem::path roughness;  ///< greyscale roughness (smoothness = 1 − roughness)
    std::filesystem::path smoothness; ///< greyscale gloss / smoothness (only when there is no roughness map)
    std::filesystem::path occlusion;  ///< greyscale ambient occlusion
    std::filesystem::path height;     ///< greyscale height / displacement / bump
    std::filesystem::path metallic;   ///< greyscale metalness
    std::filesystem::path arm;        ///< packed R occlusion, G roughness, B metallic (Poly Haven "arm", glTF "orm")
    bool normalDirectX = false;       ///< the normal map's green points down (DirectX −Y)
};

/// Classifies the image files (png, jpg, jpeg, tga, tif, tiff, exr, bmp,
/// webp, hdr) directly inside `folder` by their names: each stem is split
/// into lower-case tokens at '_', '-', '.', spaces, camelCase and
/// letter/digit boundaries, and the LAST token that names a map decides the
/// file's map, so "Metal032_2K_Color" is an albedo and "metal_plate_metal_2k"
/// a metallic map.
/// - albedo: color, colour, col, basecolor, albedo, diffuse, diff
/// - normal: normal, nor, nrm, norm (+ gl/opengl or dx/directx anywhere in
///   the name); a name that says neither is taken as `defaultNormalDirectX`
///   says. With both a GL and a DX map the one of the default convention wins.
/// - roughness: roughness, rough; smoothness: smoothness, smooth, gloss,
///   glossiness (dropped when a roughness map exists)
/// - occlusion: ao, occlusion, ambientocclusion; metallic: metallic,
///   metalness, metal; arm: arm, orm
/// - height: height, displacement, disp, displ, then bump (a height or
///   displacement map wins over a bump map)
/// - ignored: preview, sphere, cube, thumb, thumbnail, render, opacity, alpha,
///   transparency, mask, specular, spec, emission, emissive, translucency,
///   transmission, scattering, sss, cavity, curvature, id; names without
///   any of these tokens, hidden files, sub-folders and other extensions are
///   ignored as well.
/// Deterministic (file names are sorted). Throws strata::Error naming the
/// folder when it is missing or not a folder, when it has no albedo, and
/// when two files are candidates for one map and neither is preferred by
/// the rules above (the message names both files, e.g. two resolutions or
/// two formats of the same map).
PbrFiles findPbrFiles(const std::filesystem::path& folder, bool defaultNormalDirectX = false);

/// The maps of a PBR folder, ready for a Material.
struct PbrMaps
{
    TexturePtr albedo; ///< MapKind::Albedo, never null
    /// MapKind::Mask, MOHS: R metallic (0 without a map), G occlusion (1),
    /// B height (0.5), A smoothness = 1 − roughness, or the gloss map (0.5).
    /// Null when the folder has none of these maps.
    TexturePtr mask;
    TexturePtr normal; ///< MapKind::Normal, OpenGL convention; null without a normal map
};

/// Loads the maps findPbrFiles() finds in `folder`: each through
/// loadMapImage() (greyscale maps use their first channel; a normal map
/// needs 3 channels), DirectX normals flipped to OpenGL (flipGreen), the
/// single-channel maps and an ARM map packed into MOHS (packMohs; separate
/// maps take precedence over the channels of an ARM map).
/// `maxSize` (0 = keep, else a power of two): larger maps are halved with a
/// 2×2 box filter (in linear space for the albedo, renormalised for normals)
/// until both sides are at most `maxSize`, so a 4K set can be used at 1K.
/// The maps packed into the mask must have the same size after that.
/// O(pixels). Throws strata::Error (naming the folder or file) for the
/// errors of findPbrFiles() and loadMapImage(), a bad `maxSize`, a normal
/// map with fewer than 3 channels, and mask maps of different sizes (the
/// message names both files and their sizes).
PbrMaps loadPbrFolder(const std::filesystem::path& folder, const MipOptions& mips = {}, int maxSize = 0,
                      bool defaultNormalDirectX = false);

} // namespace strata::render
