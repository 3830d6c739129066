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
};

/// Builds the material: built-in sets, then the files (loaded through
/// OpenImageIO with the colour space of each map, channel remapping and
/// normal convention), mip chains. Throws strata::Error naming the
/// material, the map and the file when a file cannot be read or has too
/// few channels.
render::Material buildMaterial(const MaterialSettings& settings);

} // namespace strata::scene
