#include "Scene.h"

#include "DefaultScene.h"

#include <strata/Error.h>

#include <toml++/toml.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

namespace strata::app {

namespace {

std::string formatNumber(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

/// Reads one TOML table, checking types and ranges, and remembers which keys
/// it consumed so that `finish()` can reject unknown ones (typos).
class TableReader
{
public:
    TableReader(const toml::table* table, std::string prefix, const std::string& source)
        : mTable(table), mPrefix(std::move(prefix)), mSource(source)
    {
    }

    double number(const std::string& key, double fallback, double min, double max)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        std::optional<double> value = node->value<double>(); // also accepts integers
        if (!value || node->is_boolean()) fail(node, key, "must be a number");
        checkRange(node, key, *value, min, max);
        return *value;
    }

    std::int64_t integer(const std::string& key, std::int64_t fallback, std::int64_t min, std::int64_t max)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        if (!node->is_integer()) fail(node, key, "must be an integer");
        const std::int64_t value = *node->value<std::int64_t>();
        if (value < min || value > max) {
            fail(node, key, "= " + std::to_string(value) + " is out of range [" + std::to_string(min) + ", " +
                                std::to_string(max) + "]");
        }
        return value;
    }

    bool boolean(const std::string& key, bool fallback)
    {
        const toml::node* node = find(key);
        if (!node) return fallback;
        if (!node->is_boolean()) fail(node, key, "must be true or false");
        return *node->value<bool>();
    }

    std::optional<glm::dvec3> vec3(const std::string& key, double limit)
    {
        const toml::node* node = find(key);
        if (!node) return std::nullopt;
        const toml::array* array = node->as_array();
        if (!array || array->size() != 3) fail(node, key, "must be an array of three numbers [x, y, z]");
        glm::dvec3 v;
        for (int i = 0; i < 3; ++i) {
            const toml::node& element = *array->get(std::size_t(i));
            std::optional<double> value = element.value<double>();
            if (!value || element.is_boolean()) fail(node, key, "must be an array of three numbers [x, y, z]");
            checkRange(&element, key + "[" + std::to_string(i) + "]", *value, -limit, limit);
            v[i] = *value;
        }
        return v;
    }

    /// A sub-table; absent tables read as empty.
    TableReader table(const std::string& key)
    {
        const toml::node* node = find(key);
        if (node && !node->is_table()) fail(node, key, "must be a table");
        return TableReader(node ? node->as_table() : nullptr, qualified(key), mSource);
    }

    /// Throws on the first key that no reader asked for.
    void finish() const
    {
        if (!mTable) return;
        for (const auto& [key, node] : *mTable) {
            if (!mUsed.count(std::string(key.str()))) {
                throw Error(location(&node) + "unknown key '" + qualified(std::string(key.str())) + "'");
            }
        }
    }

    /// Throws "SOURCE:LINE: KEY WHAT"; the line is the node's, or the key's
    /// own when `node` is null.
    [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& what) const
    {
        if (!node && mTable) node = mTable->get(key);
        throw Error(location(node) + qualified(key) + " " + what);
    }

private:
    const toml::node* find(const std::string& key)
    {
        mUsed.insert(key);
        return mTable ? mTable->get(key) : nullptr;
    }

    void checkRange(const toml::node* node, const std::string& key, double value, double min, double max) const
    {
        if (!std::isfinite(value)) fail(node, key, "= " + formatNumber(value) + " must be finite");
        if (value < min || value > max) {
            fail(node, key, "= " + formatNumber(value) + " is out of range [" + formatNumber(min) + ", " +
                                formatNumber(max) + "]");
        }
    }

    std::string qualified(const std::string& key) const { return mPrefix.empty() ? key : mPrefix + "." + key; }

    std::string location(const toml::node* node) const
    {
        std::string where = mSource;
        if (node && node->source().begin.line > 0) where += ":" + std::to_string(node->source().begin.line);
        return where + ": ";
    }

    const toml::table* mTable;
    std::string mPrefix;
    const std::string& mSource;
    std::set<std::string> mUsed;
};

constexpr double HUGE_LENGTH = 1e9; // metres: the largest coordinate a scene may use

void readTerrain(TableReader& root, Scene& scene)
{
    TableReader terrainTable = root.table("terrain");
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
}

glm::vec3 directionFromAngles(double azimuthDegrees, double elevationDegrees)
{
    const double az = glm::radians(azimuthDegrees), el = glm::radians(elevationDegrees);
    return glm::vec3(glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el)));
}

} // namespace

std::string_view defaultSceneText() { return DEFAULT_SCENE_TOML; }

Scene parseScene(std::string_view text, const std::string& source)
{
    toml::table document;
    try {
        document = toml::parse(text, source);
    } catch (const toml::parse_error& e) {
        throw Error(source + ":" + std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
    }

    Scene scene;
    scene.source = source;
    TableReader root(&document, "", source);
    scene.terrain.seed = std::uint64_t(root.integer("seed", 1, 0, std::numeric_limits<std::int64_t>::max()));

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
    sampling.finish();

    readTerrain(root, scene);

    TableReader mesh = root.table("mesh");
    scene.adaptivity = mesh.number("adaptivity", scene.adaptivity, 0.0, 1.0);
    mesh.finish();

    TableReader material = root.table("material");
    MaterialSettings& m = scene.material;
    m.mapScale = float(material.number("map_scale", m.mapScale, 1e-6, 1e6));
    m.blendOffset = float(material.number("blend_offset", m.blendOffset, 0.0, 0.5));
    m.blendExponent = float(material.number("blend_exponent", m.blendExponent, 1.0, 8.0));
    m.textureSize = int(material.integer("texture_size", m.textureSize, 16, 4096));
    if ((m.textureSize & (m.textureSize - 1)) != 0) {
        material.fail(nullptr, "texture_size", "= " + std::to_string(m.textureSize) + " must be a power of two");
    }
    m.textureSeed = std::uint32_t(material.integer("texture_seed", m.textureSeed, 0, 0xffffffffll));
    material.finish();

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
    light.finish();

    TableReader snapshot = root.table("snapshot");
    scene.snapshot.width = int(snapshot.integer("width", scene.snapshot.width, 1, 16384));
    scene.snapshot.height = int(snapshot.integer("height", scene.snapshot.height, 1, 16384));
    scene.snapshot.samples = int(snapshot.integer("samples", scene.snapshot.samples, 1, 16));
    scene.snapshot.anisotropy = float(snapshot.number("anisotropy", scene.snapshot.anisotropy, 1.0, 16.0));
    snapshot.finish();

    root.finish();
    return scene;
}

Scene loadScene(const std::filesystem::path& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        throw Error("cannot open scene file '" + path.string() + "'");
    }
    std::ostringstream text;
    text << in.rdbuf();
    return parseScene(text.str(), path.string());
}

} // namespace strata::app
