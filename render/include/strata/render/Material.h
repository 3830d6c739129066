// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The triplanar material, its feature set, and the lighting of a snapshot.
/// The math is in shaders/TriplanarShading.h and TriplanarMaterial.h,
/// shared by the GL and the CPU renderer.

#include <strata/render/Atmosphere.h>
#include <strata/render/Texture.h>

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace strata::render {

/// How a projection's mapped normal is blended with the surface normal.
enum class NormalBlend
{
    Whiteout, ///< (m.xy + s.xy, m.z·s.z), triplanar-mapping §3.3 (default)
    Udn,      ///< (m.xy + s.xy, s.z)
    Rnm,      ///< reoriented normal mapping
};

/// Layout of the mask map.
enum class MaskLayout
{
    Mohs, ///< Metallic, Occlusion, Height, Smoothness (height blending possible)
    Mods, ///< Metallic, Occlusion, Detail mask, Smoothness
};

/// Feature bits; the same values as FEATURE_* in shaders/TriplanarMaterial.h.
namespace feature {
inline constexpr std::uint32_t MASK_MAP = 1u;
inline constexpr std::uint32_t MODS = 2u;
inline constexpr std::uint32_t HEIGHT_BLEND = 4u;
inline constexpr std::uint32_t NORMAL_MAP = 8u;
inline constexpr std::uint32_t TOP_MAPS = 16u;
inline constexpr std::uint32_t DETAIL = 32u;
inline constexpr std::uint32_t DETAIL_NORMAL = 64u;
inline constexpr std::uint32_t EMISSION = 128u;
inline constexpr std::uint32_t NORMAL_UDN = 256u;
inline constexpr std::uint32_t NORMAL_RNM = 512u;
/// The material has layers (Material::layers): the program evaluates them
/// all (TerrainLayers.h), its other bits being the union of theirs.
inline constexpr std::uint32_t LAYERS = 1024u;
inline constexpr std::uint32_t ANTI_TILING = 2048u;
inline constexpr std::uint32_t ALL = 4095u;
} // namespace feature

/// "mask+height+normal+top" style names of the bits, for logs and reports.
std::string featureNames(std::uint32_t features);

/// A soft band of a layer rule: weight 1 inside [min, max], smooth ramps
/// `softness` wide outside each bound, 0 beyond. Off: weight 1
/// everywhere. Unbounded sides are ±infinity.
struct LayerBand
{
    bool enabled = false;
    float min = -std::numeric_limits<float>::infinity();
    float max = std::numeric_limits<float>::infinity();
    float softness = 0.0f; ///< >= 0, in the band's unit
};

/// Where a layer shows (shaders/TerrainLayers.h): its coverage is opacity
/// times every enabled criterion.
struct LayerRule
{
    LayerBand altitude; ///< world height (Y), metres
    LayerBand slope;    ///< degrees from horizontal of the interpolated normal: 0 flat, 90 a wall, 180 a ceiling
    LayerBand cavity;   ///< the mesh's per-vertex cavity (MeshView::surface x), 0..1
    LayerBand cover;    ///< the mesh's per-vertex cover (MeshView::surface y): 1 under rock, 0 open sky
    LayerBand flow;     ///< the mesh's per-vertex flow (MeshView::landform x): log10 of the drainage area in m²
    LayerBand wear;     ///< the mesh's per-vertex wear (MeshView::landform y): metres eroded
    LayerBand deposition; ///< the mesh's per-vertex deposition (MeshView::landform z): metres of sediment
    LayerBand water;      ///< the mesh's per-vertex water (MeshView::landform w): 0 dry .. 1 river or lake
    LayerBand hardness;   ///< the mesh's per-vertex rock hardness (MeshView::rock x): 0 soft .. 1 hard
    LayerBand bed;        ///< the mesh's per-vertex bed (MeshView::rock y): the index in the beds' sequence
    /// Noise mask: three octaves of value noise in [0, 1] with features
    /// about 1/noiseFrequency metres wide; the layer shows where it exceeds
    /// noiseThreshold (ramp noiseSoftness wide). Off when noiseFrequency is 0.
    float noiseFrequency = 0.0f;
    float noiseThreshold = 0.5f;
    float noiseSoftness = 0.1f;
    std::uint32_t noiseSeed = 0;
    float opacity = 1.0f; ///< 0..1, multiplies the coverage
};

/// Whether `rule` reads the landform masks (an enabled flow, wear,
/// deposition or water band): the mesh then needs MeshView::landform.
bool usesLandform(const LayerRule& rule);

/// Whether `rule` reads the rock masks (an enabled hardness or bed band):
/// the mesh then needs MeshView::rock.
bool usesRock(const LayerRule& rule);

struct MaterialLayer;

/// A triplanar material. Every map is optional (null): the material's
/// feature set (materialFeatures) enables exactly what is present and
/// in use. Textures repeat every 1/mapScale metres in each projection.
///
/// With `layers`, this material is the base (layer 0, everywhere) and the
/// layers are painted over it in order by their rules, combined by the
/// N-layer height blend (shaders/TerrainLayers.h): at most
/// MAX_MATERIAL_LAYERS in all. The maps of one slot (albedo, mask...) are
/// one texture array on the GPU, so they must share a size or be mip
/// levels of one another (a larger map then starts at its level of the
/// smallest map's size; checkMaterial() rejects other sizes).
struct Material
{
    float mapScale = 0.125f;        ///< texture repeats per metre, > 0
    float blendOffset = 0.25f;      ///< 0..0.5: subtracted from |n|
    float blendExponent = 4.0f;     ///< 1..64: sharpness of the blend
    /// 3: triplanar; 2: biplanar (Quilez): the projection of the smallest
    /// normal component is never sampled (the blend offset is raised to it
    /// per fragment), fewer fetches for a harder blend near the diagonals.
    int projections = 3;
    /// Anti-tiling: the albedo, mask and normal maps are fetched by
    /// stochastic tiling (three taps at random offsets per texture repeat,
    /// shaders/TriplanarShading.h), so repeats do not show; three times
    /// their fetches.
    bool antiTiling = false;
    float antiTilingSharpness = 4.0f; ///< 1..16: larger keeps more contrast, smaller blends more
    float heightStrength = 0.5f;    ///< 0..0.99: height blending (MOHS layout, mask map present)
    glm::vec3 albedoTint{1.0f};     ///< linear, multiplies albedo
    float metallic = 0.0f;          ///< 0..1; multiplies mask R (the value itself without a mask map; 1 with one)
    float smoothness = 0.5f;        ///< 0..1; multiplies mask A (the value itself without a mask map; 1 with one)
    float occlusionStrength = 1.0f; ///< 0..1
    float normalStrength = 1.0f;    ///< 0..4, scales normal-map XY
    NormalBlend normalBlend = NormalBlend::Whiteout;
    MaskLayout maskLayout = MaskLayout::Mohs;
    float detailScale = 4.0f;          ///< detail repeats per base repeat, > 0
    float detailAlbedo = 1.0f;         ///< 0..1
    float detailSmoothness = 1.0f;     ///< 0..1
    float detailNormalStrength = 0.5f; ///< 0..1
    glm::vec3 emissionColor{1.0f};     ///< HDR linear, multiplies the emission map
    float fresnelStrength = 1.0f;      ///< 0..1

    TexturePtr albedo;       ///< sRGB; null: plain light grey
    TexturePtr mask;         ///< MOHS or MODS
    TexturePtr normal;       ///< tangent-space, OpenGL convention
    TexturePtr topAlbedo;    ///< Y projection where n.y > 0 (enables the top maps)
    TexturePtr topMask;      ///< top maps: null uses `mask`
    TexturePtr topNormal;    ///< top maps: null uses `normal`
    TexturePtr detail;       ///< R albedo, B smoothness, 0.5 neutral
    TexturePtr detailNormal; ///< tangent-space detail normals
    TexturePtr emission;     ///< sRGB

    std::vector<MaterialLayer> layers; ///< painted over this material, bottom to top (not nested)
    /// > 0: how far below the highest (height + coverage) a layer still
    /// shows; small values give sharp, height-driven edges, large ones a
    /// plain cross-fade by coverage.
    float layerBlendDepth = 0.2f;
};

/// The most layers a material has, the base included.
inline constexpr int MAX_MATERIAL_LAYERS = 8;

/// One layer of a layered material.
struct MaterialLayer
{
    std::string name; ///< for errors and reports
    Material material; ///< its maps and parameters (its own `layers` must be empty)
    LayerRule rule;
};

/// The feature set `material` compiles to: a bit per present map (top
/// maps when topAlbedo, topMask or topNormal is set), HEIGHT_BLEND when a
/// MOHS mask is present and heightStrength > 0, MODS for that layout, the
/// normal blend bits when a normal map is present. With layers: LAYERS and
/// the union of every layer's set (normalised).
std::uint32_t materialFeatures(const Material& material);

/// The feature set of layer `index` alone (0: the base), without LAYERS,
/// with the features outside `mask` switched off and normalised.
std::uint32_t layerFeatures(const Material& material, int index, std::uint32_t mask = feature::ALL);

/// The feature set that bits `features` can really compile to: MODS and
/// HEIGHT_BLEND are dropped without MASK_MAP, UDN and RNM without a normal
/// or detail-normal map; without LAYERS also HEIGHT_BLEND with MODS and
/// UDN when RNM is set (a layered program serves layers of every kind).
/// Idempotent; materialFeatures() results are already normalised.
std::uint32_t normalizeFeatures(std::uint32_t features);

/// normalizeFeatures(materialFeatures(material) & mask): what a renderer
/// compiles for `material` with the features outside `mask` switched off
/// (the base's own set when `mask` switches LAYERS off).
std::uint32_t effectiveFeatures(const Material& material, std::uint32_t mask);

/// Every distinct normalised feature set (1680: 320 single-material and
/// 520 layered, each with and without anti-tiling), in increasing order:
/// the program variants a renderer may have to compile (a layered program
/// also for each layer count).
std::vector<std::uint32_t> allFeatureSets();

/// Throws strata::Error "material: KEY = VALUE outside RANGE" for a
/// parameter out of range or a texture without levels; for layers
/// "material layer 'NAME': ...", also for too many or nested layers and
/// bands with min > max, negative softness or NaN bounds.
void checkMaterial(const Material& material);

/// One directional light.
struct DirectionalLightSource
{
    glm::vec3 direction{0.0f, 1.0f, 0.0f}; ///< towards the light, normalised by the renderer
    glm::vec3 color{1.0f};                 ///< linear radiance
};

struct Lighting
{
    glm::vec3 sunDirection{0.45f, 0.8f, 0.35f};      ///< towards the sun, normalised by the renderer
    glm::vec3 sunColor{2.6f, 2.45f, 2.2f};           ///< linear radiance
    std::vector<DirectionalLightSource> extraLights; ///< up to 3 more directional lights
    glm::vec3 skyAmbient{0.38f, 0.45f, 0.6f};        ///< linear, from above
    glm::vec3 groundAmbient{0.16f, 0.14f, 0.12f};    ///< linear, from below
    glm::vec3 skyColor{0.55f, 0.7f, 0.9f};           ///< background, linear (display value), when the atmosphere is off
    float exposure = 1.0f;                           ///< multiplies radiance before the ACES tone map
    Atmosphere atmosphere;                           ///< sky and fog; off by default
};


} // namespace strata::render
