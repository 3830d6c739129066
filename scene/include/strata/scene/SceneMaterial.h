// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The material part of the scene file: the [material] table (and named
/// [materials.NAME] tables that [material] can `use`), read into
/// MaterialSettings, and MaterialSettings turned into a render::Material
/// with its textures (built-in sets or image files).

#include <strata/render/Material.h>
#include <strata/render/Texture.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {


/// One map of the material from a file (overrides the built-in set's map).
struct MapFileSettings
{
    std::filesystem::path file;      ///< resolved against the scene file's folder
    render::ChannelMapping channels; ///< channel remapping ("channels = ['r','g','b','1-a']")
    bool directX = false;            ///< normal maps: DirectX (−Y) convention
    int minChannels = 1;             ///< channels the file must have (4 when alpha is read)
    /// MOHS packing: separate images per channel (metallic, occlusion,
    /// height, smoothness), each with the channel to read.
    std::array<std::filesystem::path, 4> packFiles;
    std::array<render::ChannelSource, 4> packChannels{};
    std::string where; ///< "FILE:LINE: material.maps.KEY", for errors
};

/// The nine map slots in the order of MaterialMapSlot names below.
inline constexpr const char* MATERIAL_MAP_KEYS[9] = {"albedo",     "mask",   "normal",        "top_albedo", "top_mask",
                                                     "top_normal", "detail", "detail_normal", "emission"};

struct LayerSettings;

struct MaterialSettings
{
    std::string name = "material"; ///< for error messages
    std::string where;             ///< "FILE:LINE" of the table
    /// Everything but the maps. Metallic and smoothness multiply the mask
    /// maps, which the built-in sets have, so both default to 1 here.
    render::Material parameters = [] {
        render::Material m;
        m.metallic = 1.0f;
        m.smoothness = 1.0f;
        return m;
    }();
    int textureSize = 512; ///< built-in sets: power of two, 16..4096
    std::uint32_t textureSeed = 7;
    std::string side = "rock";     ///< built-in set of albedo/mask/normal ("none": no maps)
    std::string top = "grass";     ///< built-in set of the top maps ("none")
    std::string detail = "none";   ///< built-in set of the detail map ("none")
    std::string emission = "none"; ///< built-in set of the emission map ("none")
    bool maskMaps = true;          ///< use the built-in sets' MOHS maps
    bool normalMaps = true;        ///< use the built-in sets' normal maps
    bool detailNormals = false;    ///< use the detail set's normal map as detail normals
    float detailFadeStart = 1.0f;  ///< mip levels where detail maps start/finish fading
    float detailFadeEnd = 6.0f;
    std::array<std::optional<MapFileSettings>, 9> files; ///< per slot, MATERIAL_MAP_KEYS order
    /// `pbr = "FOLDER"`: the side maps (albedo, MOHS mask, normal) from a
    /// PBR texture folder (render::loadPbrFolder), instead of `side`'s set.
    std::filesystem::path pbr;
    int pbrMaxSize = 1024;        ///< `pbr_max_size`: maps are halved down to it (power of two)
    bool pbrDirectX = false;      ///< `pbr_convention = "directx"`: unmarked normal maps are DirectX
    std::string pbrWhere;         ///< "FILE:LINE: material.pbr", for errors
    /// [[layer]] tables: painted over this material by their rules (the
    /// base's only; render::Material::layers).
    std::vector<LayerSettings> layers;
};

/// One [[layer]] table: a material of its own (every [material] key but
/// `layer_blend_depth`, defaults side = "rock", top = "none") and its
/// placement rule.
struct LayerSettings
{
    MaterialSettings material;
    render::LayerRule rule;
    std::string where; ///< "FILE:LINE: layer[N]"
};

/// The rule keys of a [[layer]] table, for documentation and tools.
inline constexpr const char* LAYER_RULE_KEYS[] = {
    "altitude_min",   "altitude_max",    "altitude_softness",   "slope_min",  "slope_max", "slope_softness",
    "cavity_min",     "cavity_max",      "cavity_softness",     "cover_min",  "cover_max", "cover_softness",
    "flow_min",       "flow_max",        "flow_softness",       "wear_min",   "wear_max",  "wear_softness",
    "deposition_min", "deposition_max",  "deposition_softness", "water_min",  "water_max", "water_softness",
    "hardness_min",   "hardness_max",    "hardness_softness",   "bed_min",    "bed_max",   "bed_softness",
    "noise_scale",    "noise_threshold", "noise_softness",      "noise_seed", "opacity"};

/// Builds the material: built-in sets, then the files (loaded through
/// OpenImageIO with the colour space of each map, channel remapping and
/// normal convention), mip chains. Throws strata::Error naming the
/// material, the map and the file when a file cannot be read or has too
/// few channels.
render::Material buildMaterial(const MaterialSettings& settings);

} // namespace strata::scene
