// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Scene.h>

#include "DefaultScene.h"
#include <strata/scene/SceneMaterial.h>
#include "SceneTerrain.h"
#include "SceneReaders.h"

#include <strata/Error.h>
#include <strata/terrain/FractalNoise.h>

#include <toml++/toml.h>

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace strata::scene {

namespace {

constexpr double HUGE_LENGTH = 1e9; // metres: the largest coordinate a scene may use

/// Sets the scene's field, landform and rock sources and their rebuilders from the
/// node tree's builder (SceneTerrain.h).
void useTerrainTree(Scene& scene, const TerrainBuilder& build)
{
    scene.buildField = [build](std::uint64_t seed) { return build(seed).root; };
    const TerrainTree tree = build(scene.terrain.seed);
    scene.field = tree.root;
    scene.landformMasks = tree.landformMasks;
    scene.landformPasses = tree.passes;
    if (tree.landformMasks) {
        scene.buildLandformMasks = [build](std::uint64_t seed) { return build(seed).landformMasks; };
    }
    scene.georeference = tree.georeference;
    scene.rockMasks = tree.rockMasks;
    if (tree.rockMasks) scene.buildRockMasks = [build](std::uint64_t seed) { return build(seed).rockMasks; };
}

void readTerrain(TableReader& root, Scene& scene, const SceneLoadOptions& load)
{
    const toml::node* terrainNode = root.node("terrain");
    TableReader terrainTable = root.table("terrain");
    if (terrainTable.has("root") || terrainTable.has("nodes")) {
        // The node form (SceneTerrain.h).
        for (const char* shorthand : {"height", "caves"}) {
            if (terrainTable.has(shorthand)) {
                terrainTable.fail(nullptr, shorthand, "cannot be combined with terrain.root and [terrain.nodes]: "
                                                      "describe the heightfield and caves as nodes");
            }
        }
        useTerrainTree(scene, readTerrainNodes(terrainNode->as_table(), scene.source,
                                               std::filesystem::path(scene.source).parent_path(), scene.terrain.seed,
                                               &scene.inputFiles, load.maxMemoryBytes, load.progress,
                                               scene.noiseVersion));
        return;
    }
    if (!terrainTable.has("height") && !terrainTable.has("caves")) {
        // No terrain given: the default scene's node tree.
        terrainTable.finish();
        const toml::table defaults = toml::parse(defaultSceneText(), std::string_view("<default scene>"));
        useTerrainTree(scene, readTerrainNodes(defaults["terrain"].as_table(), "<default scene>", {},
                                               scene.terrain.seed, nullptr, 0, {}, scene.noiseVersion));
        return;
    }
    scene.terrain.noiseVersion = scene.noiseVersion;
    TableReader height = terrainTable.table("height");
    terrain::HeightfieldOptions& h = scene.terrain.height;
    h.baseHeight = height.number("base", h.baseHeight, -HUGE_LENGTH, HUGE_LENGTH);
    h.amplitude = height.number("amplitude", h.amplitude, 0.0, 1e6);
    h.wavelength = height.number("wavelength", h.wavelength, 1e-3, 1e7);
    h.fbm.octaves = int(height.integer("octaves", h.fbm.octaves, 1, 24));
    h.fbm.lacunarity = height.number("lacunarity", h.fbm.lacunarity, 1.0, 8.0);
    h.fbm.gain = height.number("gain", h.fbm.gain, 0.0, 1.0);
    height.finish();

    TableReader caves = terrainTable.table("caves");
    terrain::CaveOptions& c = scene.terrain.caves;
    c.enabled = caves.boolean("enabled", c.enabled);
    c.wavelength = caves.number("wavelength", c.wavelength, 1e-3, 1e7);
    c.radius = caves.number("radius", c.radius, 1e-4, 1e6);
    c.verticalSquash = caves.number("vertical_squash", c.verticalSquash, 0.1, 10.0);
    c.fbm.octaves = int(caves.integer("octaves", c.fbm.octaves, 1, 8));
    c.maxHeight = caves.number("max_height", c.maxHeight, -HUGE_LENGTH, 1e30);
    caves.finish();
    terrainTable.finish();
    // The shorthand: TerrainField, a heightfield minus spaghetti tunnels.
    const terrain::TerrainOptions options = scene.terrain;
    scene.buildField = [options](std::uint64_t seed) -> std::shared_ptr<const terrain::DensityField> {
        terrain::TerrainOptions o = options;
        o.seed = seed;
        return std::make_shared<terrain::TerrainField>(o);
    };
    try {
        scene.field = scene.buildField(scene.terrain.seed);
    } catch (const Error& e) {
        terrainTable.fail(nullptr, "height", std::string("or terrain.caves: ") + e.what());
    }
}

glm::vec3 directionFromAngles(double azimuthDegrees, double elevationDegrees)
{
    const double az = glm::radians(azimuthDegrees), el = glm::radians(elevationDegrees);
    return glm::vec3(glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)));
}

} // namespace

std::string_view defaultSceneText() { return DEFAULT_SCENE_TOML; }

Scene parseScene(std::string_view text, const std::string& source, const SceneLoadOptions& options)
{
    toml::table document;
    try {
        document = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        throw Error(ErrorKind::BadInput, source + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
    }

    Scene scene;
    scene.source = source;
    scene.text = std::string(text);
    TableReader root(&document, "", source);
    scene.terrain.seed = std::uint64_t(root.integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));
    scene.noiseVersion = int(root.integer("noise_version", 1, terrain::NOISE_VERSION_MIN, terrain::NOISE_VERSION_MAX));

    TableReader region = root.table("region");
    const std::optional<glm::dvec3> lo = region.vec3("min", HUGE_LENGTH);
    const std::optional<glm::dvec3> hi = region.vec3("max", HUGE_LENGTH);
    scene.region.min = lo.value_or(glm::dvec3(-96.0, -44.0, -96.0));
    scene.region.max = hi.value_or(glm::dvec3(96.0, 44.0, 96.0));
    for (int i = 0; i < 3; ++i) {
        if (!(scene.region.min[i] < scene.region.max[i])) {
            region.fail(nullptr, "max", "must be greater than region.min on every axis (axis " +
                                            std::string(1, "xyz"[i]) + ": " + formatNumber(scene.region.min[i]) +
                                            " >= " + formatNumber(scene.region.max[i]) + ")");
        }
    }
    region.finish();

    TableReader sampling = root.table("sampling");
    scene.voxelSize = sampling.number("voxel_size", scene.voxelSize, 1e-4, 1e4);
    scene.halfWidth = int(sampling.integer("half_width", scene.halfWidth, 3, 32));
    scene.renormalize = sampling.boolean("renormalize", scene.renormalize);
    sampling.finish();

    readTerrain(root, scene, options);

    TableReader mesh = root.table("mesh");
    scene.adaptivity = mesh.number("adaptivity", scene.adaptivity, 0.0, 1.0);
    mesh.finish();

    readMaterial(root, scene.material, std::filesystem::path(source).parent_path(), scene.landformMasks != nullptr,
                 scene.rockMasks != nullptr);

    TableReader camera = root.table("camera");
    CameraSettings& c = scene.camera;
    c.azimuth = camera.number("azimuth", c.azimuth, -360.0, 360.0);
    c.elevation = camera.number("elevation", c.elevation, -89.0, 89.0);
    c.zoom = camera.number("zoom", c.zoom, 0.05, 100.0);
    c.fov = camera.number("fov", c.fov, 1.0, 170.0);
    c.position = camera.vec3("position", HUGE_LENGTH);
    c.target = camera.vec3("target", HUGE_LENGTH);
    if (c.position.has_value() != c.target.has_value()) {
        camera.fail(nullptr, c.position ? "target" : "position", "is required when camera." +
                                                    std::string(c.position ? "position" : "target") + " is given");
    }
    if (c.position && glm::length(*c.position - *c.target) <= 0.0) {
        camera.fail(nullptr, "target", "must differ from camera.position");
    }
    camera.finish();

    TableReader light = root.table("light");
    const double sunAzimuth = light.number("sun_azimuth", 60.0, -360.0, 360.0);
    const double sunElevation = light.number("sun_elevation", 40.0, -90.0, 90.0);
    scene.lighting.sunDirection = directionFromAngles(sunAzimuth, sunElevation);
    if (const std::optional<glm::dvec3> color = light.vec3("sun_color", 1e3)) {
        scene.lighting.sunColor = glm::vec3(*color);
        if (glm::any(glm::lessThan(*color, glm::dvec3(0.0)))) light.fail(nullptr, "sun_color", light.shown("sun_color") + "must not be negative");
    }
    scene.lighting.exposure = float(light.number("exposure", scene.lighting.exposure, 1e-3, 1e3));
    // [[light.extra]]: up to three more directional lights (fill, rim).
    if (const toml::node* extra = light.node("extra")) {
        const toml::array* lights = extra->as_array();
        if (!lights || !lights->is_array_of_tables() || lights->size() > 3) {
            light.fail(extra, "extra", TableReader::shown(extra) + "must be an array of at most 3 tables ([[light.extra]])");
        }
        for (std::size_t i = 0; i < lights->size(); ++i) {
            TableReader one(lights->get(i)->as_table(), "light.extra[" + std::to_string(i) + "]", source);
            render::DirectionalLightSource extraLight;
            extraLight.direction = directionFromAngles(one.number("azimuth", 0.0, -360.0, 360.0),
                                                       one.number("elevation", 45.0, -90.0, 90.0));
            extraLight.color = glm::vec3(one.vec3("color", 1e3).value_or(glm::dvec3(0.5)));
            if (glm::any(glm::lessThan(extraLight.color, glm::vec3(0.0f)))) {
                one.fail(nullptr, "color", one.shown("color") + "must not be negative");
            }
            one.finish();
            scene.lighting.extraLights.push_back(extraLight);
        }
    }
    light.finish();

    // [atmosphere]: the sky and aerial perspective, on unless disabled.
    TableReader sky = root.table("atmosphere");
    render::Atmosphere& atmosphere = scene.lighting.atmosphere;
    atmosphere.enabled = sky.boolean("enabled", true);
    for (const auto& [key, color] : {std::pair{"zenith_color", &atmosphere.zenithColor},
                                     std::pair{"horizon_color", &atmosphere.horizonColor}}) {
        if (const std::optional<glm::dvec3> value = sky.vec3(key, 1e3)) {
            if (glm::any(glm::lessThan(*value, glm::dvec3(0.0)))) sky.fail(nullptr, key, sky.shown(key) + "must not be negative");
            *color = glm::vec3(*value);
        }
    }
    atmosphere.fogDensity = float(sky.number("fog_density", atmosphere.fogDensity, 0.0, 1.0));
    atmosphere.fogFalloff = float(sky.number("fog_falloff", atmosphere.fogFalloff, 0.0, 1.0));
    atmosphere.fogBaseHeight = sky.number("fog_base_height", atmosphere.fogBaseHeight, -1e9, 1e9);
    atmosphere.sunGlow = float(sky.number("sun_glow", atmosphere.sunGlow, 0.0, 100.0));
    atmosphere.sunDiscRadius = float(sky.number("sun_disc_radius", atmosphere.sunDiscRadius, 0.0, 20.0));
    sky.finish();

    TableReader snapshot = root.table("snapshot");
    scene.snapshot.width = int(snapshot.integer("width", scene.snapshot.width, 1, 16384));
    scene.snapshot.height = int(snapshot.integer("height", scene.snapshot.height, 1, 16384));
    scene.snapshot.samples = int(snapshot.integer("samples", scene.snapshot.samples, 1, 16));
    scene.snapshot.anisotropy = float(snapshot.number("anisotropy", scene.snapshot.anisotropy, 1.0, 16.0));
    render::ShadowOptions& shadows = scene.snapshot.shadows;
    shadows.enabled = snapshot.boolean("shadows", shadows.enabled);
    shadows.resolution = int(snapshot.integer("shadow_resolution", shadows.resolution, 16, 16384));
    shadows.normalBias = float(snapshot.number("shadow_normal_bias", shadows.normalBias, 0.0, 16.0));
    shadows.depthBias = float(snapshot.number("shadow_depth_bias", shadows.depthBias, 0.0, 16.0));
    snapshot.finish();

    scene.quality = readQuality(root);

    root.finish();
    return scene;
}

Scene loadScene(const std::filesystem::path& path, const SceneLoadOptions& options)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error(ErrorKind::BadInput, "cannot open scene file '" + path.string() + "'");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path.string(), options);
}

Scene defaultScene() { return parseScene(defaultSceneText(), "<default scene>"); }

std::shared_ptr<const terrain::DensityField> fieldForSeed(const Scene& scene, std::optional<std::uint64_t> seed)
{
    std::shared_ptr<const terrain::DensityField> field =
        seed && *seed != scene.terrain.seed && scene.buildField ? scene.buildField(*seed) : scene.field;
    if (!field) throw Error(ErrorKind::BadInput, scene.source + ": the scene has no terrain", {scene.source});
    return field;
}

std::shared_ptr<const terrain::LandformMasks> landformMasksForSeed(const Scene& scene,
                                                                   std::optional<std::uint64_t> seed)
{
    return seed && *seed != scene.terrain.seed && scene.buildLandformMasks ? scene.buildLandformMasks(*seed)
                                                                           : scene.landformMasks;
}

std::shared_ptr<const terrain::RockMasks> rockMasksForSeed(const Scene& scene, std::optional<std::uint64_t> seed)
{
    return seed && *seed != scene.terrain.seed && scene.buildRockMasks ? scene.buildRockMasks(*seed) : scene.rockMasks;
}

} // namespace strata::scene
