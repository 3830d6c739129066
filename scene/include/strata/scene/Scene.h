#pragma once
/// \file
/// The scene file: everything `strata generate` needs, read from TOML.

#include <strata/scene/Quality.h>
#include <strata/scene/SceneMaterial.h>

#include <strata/render/Material.h>
#include <strata/render/SnapshotOptions.h>
#include <strata/terrain/SampleLevelSet.h>
#include <strata/terrain/TerrainField.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace strata::scene {

/// Where the camera looks from: an orbit around the terrain's bounds, or an
/// explicit position and target (world metres).
struct CameraSettings
{
    double azimuth = 30.0;   ///< degrees around +Y; 0 looks towards −Z
    double elevation = 35.0; ///< degrees above the horizon
    double zoom = 1.0;       ///< > 1 moves the orbit camera closer
    double fov = 35.0;       ///< vertical field of view, degrees
    std::optional<glm::dvec3> position;
    std::optional<glm::dvec3> target;
};

struct SnapshotSettings
{
    int width = 1280;
    int height = 720;
    int samples = 4; ///< MSAA samples
    float anisotropy = 1.0f; ///< 1 = trilinear; up to 16
    render::ShadowOptions shadows; ///< [snapshot] shadows, shadow_resolution, shadow_normal_bias, shadow_depth_bias
    render::TextureFilter filtering = render::TextureFilter::Trilinear; ///< [quality] filtering
};


struct Scene
{
    std::string source; ///< file path, or "<default scene>"
    std::string text;   ///< the TOML text it was parsed from (the bake hashes it)
    /// The files the terrain reads (heightmap images), sorted; the bake
    /// hashes their contents too.
    std::vector<std::filesystem::path> inputFiles;
    /// The seed (terrain.seed) and, for the [terrain.height]/[terrain.caves]
    /// shorthand, its options.
    terrain::TerrainOptions terrain;
    /// The terrain's root density field, built with terrain.seed (see
    /// SceneTerrain.h); never null after parseScene().
    std::shared_ptr<const terrain::DensityField> field;
    /// Rebuilds the root field for another seed (`--seed`).
    std::function<std::shared_ptr<const terrain::DensityField>(std::uint64_t)> buildField;
    terrain::Region region;
    double voxelSize = 0.5;
    int halfWidth = 3;
    bool renormalize = false; ///< [sampling] renormalize: reinitialise the band to a signed distance
    double adaptivity = 0.0;
    CameraSettings camera;
    SnapshotSettings snapshot;
    MaterialSettings material; ///< see SceneMaterial.h
    render::Lighting lighting;
    QualityTable quality; ///< [quality]: preset and knob overrides (Quality.h)
};

/// The scene compiled into the executable.
std::string_view defaultSceneText();

/// Parses TOML scene text. `source` names it in error messages. Throws
/// strata::Error "SOURCE:LINE: KEY = VALUE ..." on a syntax error, an unknown
/// key, a wrong type or an out-of-range value.
Scene parseScene(std::string_view text, const std::string& source);

/// Reads and parses a scene file. Throws strata::Error naming the file.
Scene loadScene(const std::filesystem::path& path);

/// The embedded default scene, parsed (source "<default scene>").
Scene defaultScene();

/// The scene's root density field for `seed` (the scene's own when empty or
/// equal; another seed rebuilds the node tree). Throws strata::Error
/// (BadInput) when the scene has no terrain.
std::shared_ptr<const terrain::DensityField> fieldForSeed(const Scene& scene, std::optional<std::uint64_t> seed);

} // namespace strata::scene
