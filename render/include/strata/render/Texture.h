// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Texture maps as the renderers sample them: RGBA8 mip chains built once,
/// with the colour space and mip rule of the map's kind, and the CPU
/// sampler that filters them exactly as OpenGL does (REPEAT wrap, bilinear,
/// trilinear with the level of detail from UV derivatives, sRGB decoded
/// before filtering).

#include <strata/render/Image.h>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace strata::render {

/// What a map holds; decides its colour space and how its mips are built.
enum class MapKind
{
    Albedo,       ///< sRGB colour (alpha linear)
    Mask,         ///< linear MOHS or MODS
    Normal,       ///< linear tangent-space normal, OpenGL (+Y) convention; renormalised per mip
    Detail,       ///< linear, 0.5 neutral; fades to grey over the mip range
    DetailNormal, ///< linear normal; renormalised and faded to flat over the mip range
    Emission,     ///< sRGB colour
};

/// True for the kinds stored as sRGB (albedo, emission).
bool isSrgb(MapKind kind);

/// Options of the mip chain.
struct MipOptions
{
    /// Detail maps: mip level where fading to neutral starts and where it is
    /// complete (complex-maps §3.4). 0 <= start <= end.
    float detailFadeStart = 1.0f;
    float detailFadeEnd = 6.0f;
};

/// An immutable RGBA8 mip chain. Level 0 is the image; each level halves
/// (rounding down, at least 1). Rows run bottom to top as in OpenGL, so
/// texel (i, j) of level 0 is image pixel (i, height − 1 − j): the image's
/// top is at v = 1.
struct Texture
{
    struct Level
    {
        int width = 0;
        int height = 0;
        std::vector<std::uint8_t> texels; ///< width·height·4, rows bottom to top
    };
    MapKind kind = MapKind::Albedo;
    bool srgb = true;
    std::vector<Level> levels;

    int width() const { return levels.empty() ? 0 : levels[0].width; }
    int height() const { return levels.empty() ? 0 : levels[0].height; }
};

using TexturePtr = std::shared_ptr<const Texture>;

/// Builds the mip chain of `image` for maps of `kind`: box-filtered in
/// linear space (sRGB decoded, averaged, encoded), normals decoded,
/// averaged and renormalised, detail maps faded to 0.5 (normals to flat)
/// between options.detailFadeStart and detailFadeEnd. O(pixels).
/// Throws strata::Error for an empty or inconsistent image.
TexturePtr makeTexture(const Image& image, MapKind kind, const MipOptions& options = {});

/// A one-texel texture of the given RGBA8 value (for absent maps).
TexturePtr makeConstantTexture(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a, MapKind kind);

/// One channel of a remapped map: which source channel (0..3 = R, G, B, A;
/// 4 = constant 0; 5 = constant 1), optionally inverted (1 − x).
struct ChannelSource
{
    int channel = 0;
    bool invert = false;
};

/// Channel remapping of a loaded image, e.g. "a" (height from alpha),
/// "1-r" (smoothness = 1 − roughness). Identity by default.
struct ChannelMapping
{
    ChannelSource channels[4] = {{0, false}, {1, false}, {2, false}, {3, false}};
};

/// Parses one channel expression: "r", "g", "b", "a", "0", "1", or "1-X".
/// Throws strata::Error naming `what` otherwise.
ChannelSource parseChannelSource(const std::string& text, const std::string& what);

/// Applies `mapping` to an RGBA8 image (per channel, in the stored encoding).
Image remapChannels(const Image& image, const ChannelMapping& mapping);

/// Flips the green channel (DirectX −Y normal maps to OpenGL +Y).
void flipGreen(Image& image);

/// The largest map side, in pixels: 8192 (the RGBA8 mip chain of an
/// 8192² map takes 358 MB). Larger maps are refused before decoding.
inline constexpr int MAX_MAP_SIZE = 8192;

/// Bytes the texels of `texture`'s mip chain take (0 for null).
std::uint64_t textureBytes(const TexturePtr& texture);

/// Loads a map through OpenImageIO (PNG, TGA, JPEG, EXR, TIFF...), keeping
/// alpha unassociated (oiio:UnassociatedAlpha = 1); linear maps keep their
/// stored values, sRGB maps are sRGB-encoded. `minChannels` is the number
/// of channels the map needs (a height from alpha needs 4). Throws
/// strata::Error "material M, map K: FILE: why" when the file is missing,
/// unreadable, larger than MAX_MAP_SIZE on a side (checked from the header,
/// before any pixel is decoded) or has too few channels.
Image loadMapImage(const std::filesystem::path& path, MapKind kind, int minChannels, const std::string& what);

/// Packs a MOHS map from separate single-channel images (their R channel;
/// null means the default: metallic 0, occlusion 1, height 0.5, smoothness
/// 0.5). All given images must have the same size. Throws strata::Error.
Image packMohs(const Image* metallic, const Image* occlusion, const Image* height, const Image* smoothness);

// ---------------------------------------------------------------------------
// The CPU sampler.

/// sRGB byte to linear float, exactly as the GL sRGB decode table.
float srgbByteToLinear(std::uint8_t value);

/// GL_LINEAR sampling of one level with GL_REPEAT wrap: texel centres at
/// (i + ½)/w; values decoded (sRGB → linear) before filtering.
glm::vec4 sampleBilinear(const Texture& texture, int level, glm::vec2 uv);

/// How the CPU sampler takes the log2 of the level of detail.
enum class LodLog2
{
    /// log2 as the GL specification defines λ (default): the reference.
    Exact,
    /// Mesa llvmpipe's approximation (lp_build_fast_log2): log2(m·2^e) ≈
    /// e + m − 1 for m in [1, 2), exact at powers of two, linear between, at
    /// most 0.086 below the true value. The GL spec allows it; matching the
    /// CI's driver makes the trilinear blend the same on both renderers.
    Llvmpipe,
};

/// GL's level of detail λ = log2(ρ), ρ = max(|∂uv/∂x|, |∂uv/∂y|) in texels
/// of level 0 (no clamping), computed as ½·log2(ρ²) with `log2`; −1000 for
/// zero or non-finite derivatives.
float textureLod(const Texture& texture, glm::vec2 dUVdx, glm::vec2 dUVdy, LodLog2 log2 = LodLog2::Exact);

/// GL_LINEAR_MIPMAP_LINEAR (minification) / GL_LINEAR (magnification,
/// λ <= 0) sampling with λ from textureLod(), clamped to the last level.
glm::vec4 sampleTrilinear(const Texture& texture, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy,
                          LodLog2 log2 = LodLog2::Exact);

/// How the renderers filter minified maps (SnapshotOptions::filtering).
enum class TextureFilter
{
    Trilinear, ///< GL_LINEAR_MIPMAP_LINEAR: two mip levels blended (default)
    Bilinear,  ///< GL_LINEAR_MIPMAP_NEAREST: the nearest mip level only (half the texel reads, visible mip seams)
};

/// GL_LINEAR_MIPMAP_NEAREST (minification) / GL_LINEAR (magnification,
/// λ <= 0): bilinear in level d = ⌈λ + ½⌉ − 1 (GL's nearest-level rule),
/// clamped to the last level, with λ from textureLod().
glm::vec4 sampleBilinearNearestMip(const Texture& texture, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy,
                                   LodLog2 log2 = LodLog2::Exact);

/// sampleTrilinear() or sampleBilinearNearestMip() by `filter`.
glm::vec4 sampleFiltered(const Texture& texture, TextureFilter filter, glm::vec2 uv, glm::vec2 dUVdx, glm::vec2 dUVdy,
                         LodLog2 log2 = LodLog2::Exact);

} // namespace strata::render
