// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The scene file: everything `strata generate` needs, read from TOML.

#include <strata/scene/Georeference.h>
#include <strata/scene/Quality.h>
#include <strata/scene/SceneMaterial.h>

#include <strata/render/Material.h>
#include <strata/render/SnapshotOptions.h>
#include <strata/terrain/LandformMasks.h>
#include <strata/terrain/RockMasks.h>
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

/// An erode node's global pass as loading the scene ran it (once per
/// process for the same input: later loads find it cached).
struct LandformPass
{
    std::string node;            ///< the node's name
    std::size_t cells = 0;       ///< grid corners
    std::uint64_t peakBytes = 0; ///< the pass's working memory, estimated
    double seconds = 0.0;        ///< wall time of the evolution when it ran
    bool cached = false;         ///< this load found it already computed
    int steps = 0;               ///< implicit time steps
};

/// What loading a scene may use.
struct SceneLoadOptions
{
    /// Bytes (0: no budget): an erode node whose pass would need more is
    /// refused before it runs, naming its cell_size (--max-memory).
    std::uint64_t maxMemoryBytes = 0;
    /// The erode nodes' passes report their progress in [0, 1] here (one
    /// pass after the other); returning false stops the load (strata::Error,
    /// Interrupted: Ctrl-C in the CLI, KeyboardInterrupt in Python). Called
    /// while loading only, from the loading thread; a later rebuild for
    /// another seed (Scene::buildField) runs without it. May be empty.
    std::function<bool(double)> progress;
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
    /// `noise_version`: 1 (the default, so scenes written before version 2
    /// keep their bits) or 2 (terrain::FractalOptions::version).
    int noiseVersion = 1;
    /// The terrain's root density field, built with terrain.seed (see
    /// SceneTerrain.h); never null after parseScene().
    std::shared_ptr<const terrain::DensityField> field;
    /// Rebuilds the root field for another seed (`--seed`).
    std::function<std::shared_ptr<const terrain::DensityField>(std::uint64_t)> buildField;
    /// The terrain tree's landform source, built with terrain.seed: the node
    /// that knows its landform masks (an `erode` node; `[terrain] masks =
    /// "NAME"` picks one of several), which layer rules' flow, wear,
    /// deposition and water bands and the landform debug views read. Null
    /// when the tree has none.
    std::shared_ptr<const terrain::LandformMasks> landformMasks;
    /// The erode nodes' global passes run while loading (for scene.seed).
    std::vector<LandformPass> landformPasses;
    /// Rebuilds it for another seed, from the same tree as buildField (the
    /// tree is built once for both); empty when the tree has none.
    std::function<std::shared_ptr<const terrain::LandformMasks>(std::uint64_t)> buildLandformMasks;
    /// The terrain tree's rock source, built with terrain.seed: the node
    /// that knows its rock masks (a `beds` node; `[terrain] rock = "NAME"`
    /// picks one of several), which layer rules' hardness and bed bands and
    /// the rock debug views read. Null when the tree has none.
    std::shared_ptr<const terrain::RockMasks> rockMasks;
    /// Rebuilds it for another seed (the beds' folds are seeded), from the
    /// same tree as buildField; empty when the tree has none.
    std::function<std::shared_ptr<const terrain::RockMasks>(std::uint64_t)> buildRockMasks;
    /// Where the scene's origin lies on the Earth, from a georeferenced DEM
    /// (a dem_heightfield node's file with a CRS); the bake's tileset is
    /// placed there unless --georeference says otherwise. Empty otherwise.
    std::optional<Georeference> georeference;
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
Scene parseScene(std::string_view text, const std::string& source, const SceneLoadOptions& options = {});

/// Reads and parses a scene file. Throws strata::Error naming the file.
Scene loadScene(const std::filesystem::path& path, const SceneLoadOptions& options = {});

/// The embedded default scene, parsed (source "<default scene>").
Scene defaultScene();

/// The scene's root density field for `seed` (the scene's own when empty or
/// equal; another seed rebuilds the node tree). Throws strata::Error
/// (BadInput) when the scene has no terrain.
std::shared_ptr<const terrain::DensityField> fieldForSeed(const Scene& scene, std::optional<std::uint64_t> seed);

/// The scene's landform source for `seed`, as fieldForSeed() the field
/// (another seed rebuilds it with the tree); null when the tree has none.
std::shared_ptr<const terrain::LandformMasks> landformMasksForSeed(const Scene& scene,
                                                                   std::optional<std::uint64_t> seed);

/// The scene's rock source for `seed`, as landformMasksForSeed(); null when
/// the tree has none.
std::shared_ptr<const terrain::RockMasks> rockMasksForSeed(const Scene& scene, std::optional<std::uint64_t> seed);

} // namespace strata::scene
