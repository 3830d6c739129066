#pragma once
/// \file
/// The triplanar material, its feature set, and the lighting of a snapshot.
/// The math is in shaders/TriplanarShading.h and TriplanarMaterial.h,
/// shared by the GL and the CPU renderer.

#include <strata/render/Atmosphere.h>
#include <strata/render/Texture.h>

#include <glm/vec3.hpp>

#include <cstdint>
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
inline constexpr std::uint32_t ALL = 1023u;
} // namespace feature

/// "mask+height+normal+top" style names of the bits, for logs and reports.
std::string featureNames(std::uint32_t features);

/// A triplanar material. Every map is optional (null): the material's
/// feature set (materialFeatures) enables exactly what is present and
/// in use. Textures repeat every 1/mapScale metres in each projection.
struct Material
{
    float mapScale = 0.125f;        ///< texture repeats per metre, > 0
    float blendOffset = 0.25f;      ///< 0..0.5: subtracted from |n|
    float blendExponent = 4.0f;     ///< 1..64: sharpness of the blend
    /// 3: triplanar; 2: biplanar (Quilez): the projection of the smallest
    /// normal component is never sampled (the blend offset is raised to it
    /// per fragment), fewer fetches for a harder blend near the diagonals.
    int projections = 3;
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
};

/// The feature set `material` compiles to: a bit per present map (top
/// maps when topAlbedo, topMask or topNormal is set), HEIGHT_BLEND when a
/// MOHS mask is present and heightStrength > 0, MODS for that layout, the
/// normal blend bits when a normal map is present.
std::uint32_t materialFeatures(const Material& material);

/// The feature set that bits `features` can really compile to: MODS and
/// HEIGHT_BLEND are dropped without MASK_MAP (and HEIGHT_BLEND with MODS),
/// UDN and RNM without a normal or detail-normal map, UDN when RNM is set.
/// Idempotent; materialFeatures() results are already normalised.
std::uint32_t normalizeFeatures(std::uint32_t features);

/// normalizeFeatures(materialFeatures(material) & mask): what a renderer
/// compiles for `material` with the features outside `mask` switched off.
std::uint32_t effectiveFeatures(const Material& material, std::uint32_t mask);

/// Every distinct normalised feature set (320), in increasing order: the
/// program variants a renderer may have to compile.
std::vector<std::uint32_t> allFeatureSets();

/// Throws strata::Error "material: KEY = VALUE outside RANGE" for a
/// parameter out of range or a texture without levels.
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
