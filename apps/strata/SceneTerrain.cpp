#include "SceneTerrain.h"

#include <strata/Error.h>
#include <strata/terrain/Caves.h>
#include <strata/terrain/Csg.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/Noise.h>
#include <strata/terrain/Primitives.h>
#include <strata/terrain/Transforms.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <set>

namespace strata::app {

namespace {

using namespace strata::terrain;

constexpr double HUGE_LENGTH = 1e9; // metres: the largest coordinate a scene may use
constexpr double MAX_LENGTH = 1e7;  // metres: the largest size (wavelength, radius...)

/// FNV-1a of a node's name: its default seed stream.
std::uint64_t nameStream(const std::string& name)
{
    std::uint64_t h = 0xcbf29ce484222325ULL;
    for (unsigned char c : name) {
        h ^= c;
        h *= 0x100000001b3ULL;
    }
    return h;
}

std::string joinTypes()
{
    std::string out;
    for (const std::string& t : terrainNodeTypes()) out += (out.empty() ? "" : ", ") + t;
    return out;
}

/// Images read once per scene, shared by every build (seed override).
struct ImageCache
{
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const HeightImage>> images;
};

std::shared_ptr<const HeightImage> readHeightImage(const std::filesystem::path& path, TableReader& t,
                                                   ImageCache& cache)
{
    std::lock_guard<std::mutex> lock(cache.mutex);
    auto found = cache.images.find(path.string());
    if (found != cache.images.end()) return found->second;
    const std::string shown = "= '" + path.string() + "'";
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) t.fail(nullptr, "file", shown + ": no such file");
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path.string(), &config);
    if (!in) t.fail(nullptr, "file", shown + " cannot be read as an image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    auto image = std::make_shared<HeightImage>();
    image->width = spec.width;
    image->height = spec.height;
    if (spec.width < 2 || spec.height < 2 || spec.nchannels < 1 ||
        double(spec.width) * double(spec.height) > double(1 << 28)) {
        t.fail(nullptr, "file", shown + " is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                                    " pixels: heightmaps need 2x2 to 16384x16384");
    }
    image->values.resize(std::size_t(spec.width) * std::size_t(spec.height));
    // Channel 0 as float: 8- and 16-bit integers come normalised to [0, 1].
    if (!in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, image->values.data())) {
        t.fail(nullptr, "file", shown + " cannot be read: " + in->geterror());
    }
    in->close();
    cache.images.emplace(path.string(), image);
    return image;
}

class NodeBuilder
{
public:
    NodeBuilder(const toml::table* nodes, const std::string& source, const std::filesystem::path& baseDirectory,
                std::uint64_t seed, ImageCache& images)
        : mNodes(nodes), mSource(source), mBase(baseDirectory), mSeed(seed), mImages(images)
    {
    }

    /// Builds node `name`; `referrer` and `key` say where the name was given.
    DensityFieldPtr build(const std::string& name, TableReader& referrer, const std::string& key)
    {
        auto found = mBuilt.find(name);
        if (found != mBuilt.end()) return found->second;
        const toml::node* node = mNodes ? mNodes->get(name) : nullptr;
        if (!node) {
            referrer.fail(nullptr, key, "= '" + name + "' names no node: add a [terrain.nodes." + name + "] table");
        }
        if (!node->is_table()) {
            throw Error(mSource + ":" + std::to_string(node->source().begin.line) + ": terrain.nodes." + name +
                        " must be a table");
        }
        if (mVisiting.count(name)) {
            referrer.fail(nullptr, key, "= '" + name + "' makes a cycle: a node cannot contain itself");
        }
        mVisiting.insert(name);
        TableReader t(node->as_table(), "terrain.nodes." + name, mSource);
        DensityFieldPtr field;
        try {
            field = make(name, t);
        } catch (const Error& e) {
            const std::string what = e.what();
            if (what.rfind(mSource, 0) == 0) throw; // already says where
            // Errors of the terrain library start with the key ("radius = -1
            // must be ..."): add the file, line and node.
            const std::string key = what.substr(0, what.find(' '));
            if (!key.empty() && t.has(key)) throw Error(t.where(key) + what.substr(key.size()));
            const std::string at = t.where("type");
            throw Error(at.substr(0, at.size() - 5) + ": " + what);
        }
        t.finish();
        mVisiting.erase(name);
        mBuilt.emplace(name, field);
        return field;
    }

    bool isBuilt(const std::string& name) const { return mBuilt.count(name) > 0; }

private:
    std::uint64_t seedOf(const std::string& name, TableReader& t)
    {
        const std::int64_t stream =
            t.integer("seed", std::int64_t(nameStream(name) >> 1), 0, std::numeric_limits<std::int64_t>::max());
        return deriveSeed(mSeed, std::uint64_t(stream));
    }

    FractalOptions fractal(TableReader& t, FractalOptions o)
    {
        const std::string noise = t.string("noise", "");
        if (!noise.empty() && !parseNoiseType(noise, o.noise)) {
            t.fail(nullptr, "noise", "= '" + noise + "' is not a noise type (gradient, simplex, value, cellular_f1, "
                                     "cellular_f2)");
        }
        const std::string kind = t.string("fractal", "");
        if (!kind.empty() && !parseFractalType(kind, o.fractal)) {
            t.fail(nullptr, "fractal", "= '" + kind + "' is not a fractal type (fbm, ridged, billow)");
        }
        o.octaves = int(t.integer("octaves", o.octaves, 1, 24));
        o.lacunarity = t.number("lacunarity", o.lacunarity, 1.0, 8.0);
        o.gain = t.number("gain", o.gain, 0.0, 1.0);
        return o;
    }

    DensityFieldPtr child(TableReader& t)
    {
        if (!t.has("child")) t.fail(nullptr, "child", "is required (the name of the node to transform)");
        return build(t.string("child", ""), t, "child");
    }

    std::vector<DensityFieldPtr> children(TableReader& t)
    {
        const toml::node* node = t.node("children");
        const toml::array* array = node ? node->as_array() : nullptr;
        if (!array || array->size() < 2) {
            t.fail(node, "children", "must be an array of at least two node names, e.g. [\"land\", \"caves\"]");
        }
        std::vector<DensityFieldPtr> out;
        for (std::size_t i = 0; i < array->size(); ++i) {
            const toml::node& element = *array->get(i);
            if (!element.is_string()) t.fail(&element, "children", "must hold node names (strings)");
            out.push_back(build(*element.value<std::string>(), t, "children"));
        }
        return out;
    }

    glm::dvec2 vec2(TableReader& t, const std::string& key, glm::dvec2 fallback)
    {
        const toml::node* node = t.node(key);
        if (!node) return fallback;
        const toml::array* array = node->as_array();
        if (!array || array->size() != 2) t.fail(node, key, "must be an array of two numbers [x, z]");
        glm::dvec2 v;
        for (int i = 0; i < 2; ++i) {
            const toml::node& element = *array->get(std::size_t(i));
            const std::optional<double> value = element.value<double>();
            if (!value || element.is_boolean() || !std::isfinite(*value) || std::abs(*value) > HUGE_LENGTH) {
                t.fail(node, key, "must be an array of two finite numbers [x, z] within ±1e9");
            }
            v[i] = *value;
        }
        return v;
    }

    DensityFieldPtr make(const std::string& name, TableReader& t)
    {
        if (!t.has("type")) t.fail(nullptr, "type", "is required (one of " + joinTypes() + ")");
        const std::string type = t.string("type", "");
        if (type == "heightfield") {
            NoiseHeightfieldOptions o;
            o.base = t.number("base", o.base, -HUGE_LENGTH, HUGE_LENGTH);
            o.amplitude = t.number("amplitude", o.amplitude, 0.0, 1e6);
            o.wavelength = t.number("wavelength", o.wavelength, 1e-3, MAX_LENGTH);
            o.noise = fractal(t, o.noise);
            return std::make_shared<NoiseHeightfield>(seedOf(name, t), o);
        }
        if (type == "image_heightfield") {
            if (!t.has("file")) t.fail(nullptr, "file", "is required (a PNG, EXR, TIFF... height image)");
            std::filesystem::path file = t.string("file", "");
            if (file.is_relative()) file = mBase / file;
            ImageHeightfieldOptions o;
            o.min = vec2(t, "min", o.min);
            o.max = vec2(t, "max", o.max);
            for (int a = 0; a < 2; ++a) {
                if (!(o.max[a] > o.min[a])) {
                    t.fail(nullptr, "max", "must be greater than min on both axes (" + formatNumber(o.min[a]) +
                                               " >= " + formatNumber(o.max[a]) + ")");
                }
            }
            o.base = t.number("base", o.base, -HUGE_LENGTH, HUGE_LENGTH);
            o.heightScale = t.number("height_scale", o.heightScale, -1e6, 1e6);
            const std::shared_ptr<const HeightImage> image = readHeightImage(file, t, mImages);
            return std::make_shared<ImageHeightfield>(*image, o);
        }
        if (type == "worms") {
            WormOptions o;
            o.cellSize = t.number("cell_size", o.cellSize, 1.0, 1e5);
            o.wormsPerCell = t.number("worms_per_cell", o.wormsPerCell, 0.0, 16.0);
            o.minY = t.number("min_y", o.minY, -HUGE_LENGTH, HUGE_LENGTH);
            o.maxY = t.number("max_y", o.maxY, -HUGE_LENGTH, HUGE_LENGTH);
            if (o.maxY < o.minY) t.fail(nullptr, "max_y", "= " + formatNumber(o.maxY) + " is below min_y = " + formatNumber(o.minY));
            o.segments = int(t.integer("segments", o.segments, 1, 256));
            o.segmentLength = t.number("segment_length", o.segmentLength, 1e-3, 1e4);
            o.radius = t.number("radius", o.radius, 1e-3, 1e4);
            o.radiusVariation = t.number("radius_variation", o.radiusVariation, 0.0, 0.9);
            o.turn = t.number("turn", o.turn, 0.0, 10.0);
            o.maxPitch = t.number("max_pitch", o.maxPitch, 0.0, 1.4);
            return std::make_shared<WormCaves>(seedOf(name, t), o);
        }
        if (type == "cheese") {
            CheeseOptions o;
            o.wavelength = t.number("wavelength", o.wavelength, 1e-3, MAX_LENGTH);
            o.threshold = t.number("threshold", o.threshold, -2.0, 2.0);
            o.verticalSquash = t.number("vertical_squash", o.verticalSquash, 0.1, 10.0);
            o.invert = t.boolean("invert", o.invert);
            o.maxHeight = t.number("max_height", o.maxHeight, -HUGE_LENGTH, 1e30);
            o.noise = fractal(t, o.noise);
            return std::make_shared<CheeseCaves>(seedOf(name, t), o);
        }
        if (type == "spaghetti") {
            SpaghettiOptions o;
            o.wavelength = t.number("wavelength", o.wavelength, 1e-3, MAX_LENGTH);
            o.radius = t.number("radius", o.radius, 1e-4, 1e6);
            o.verticalSquash = t.number("vertical_squash", o.verticalSquash, 0.1, 10.0);
            o.maxHeight = t.number("max_height", o.maxHeight, -HUGE_LENGTH, 1e30);
            o.noise = fractal(t, o.noise);
            return std::make_shared<SpaghettiCaves>(seedOf(name, t), o);
        }
        if (type == "warp") {
            WarpOptions o;
            o.amplitude = t.number("amplitude", o.amplitude, 0.0, 1e6);
            o.wavelength = t.number("wavelength", o.wavelength, 1e-3, MAX_LENGTH);
            o.vertical = t.number("vertical", o.vertical, 0.0, 10.0);
            o.noise = fractal(t, o.noise);
            const std::uint64_t seed = seedOf(name, t);
            return std::make_shared<WarpField>(child(t), seed, o);
        }
        if (type == "terrace") {
            const double step = t.number("step", 4.0, 1e-3, 1e6);
            const double sharpness = t.number("sharpness", 3.0, 1.0, 64.0);
            return std::make_shared<TerraceField>(child(t), step, sharpness);
        }
        if (type == "translate") {
            const glm::dvec3 offset = t.vec3("offset", HUGE_LENGTH).value_or(glm::dvec3(0.0));
            return std::make_shared<TranslateField>(child(t), offset);
        }
        if (type == "union" || type == "subtract" || type == "intersect") {
            const double smooth = t.number("smooth", 0.0, 0.0, 1e4);
            const CsgOperation op = type == "union"      ? CsgOperation::UNION
                                    : type == "subtract" ? CsgOperation::SUBTRACT
                                                         : CsgOperation::INTERSECT;
            return std::make_shared<CsgField>(op, children(t), smooth);
        }
        if (type == "sphere") {
            const glm::dvec3 center = t.vec3("center", HUGE_LENGTH).value_or(glm::dvec3(0.0));
            const double radius = t.number("radius", 10.0, 1e-4, MAX_LENGTH);
            return std::make_shared<SphereField>(center, radius);
        }
        if (type == "box") {
            const glm::dvec3 center = t.vec3("center", HUGE_LENGTH).value_or(glm::dvec3(0.0));
            const glm::dvec3 size = t.vec3("size", MAX_LENGTH).value_or(glm::dvec3(10.0));
            for (int a = 0; a < 3; ++a) {
                if (!(size[a] > 0.0)) t.fail(nullptr, "size", "must be positive on every axis");
            }
            const double limit = 0.5 * std::min({size.x, size.y, size.z});
            const double rounding = t.number("rounding", 0.0, 0.0, limit);
            return std::make_shared<BoxField>(center, 0.5 * size, rounding);
        }
        if (type == "capsule") {
            const glm::dvec3 a = t.vec3("a", HUGE_LENGTH).value_or(glm::dvec3(0.0, -5.0, 0.0));
            const glm::dvec3 b = t.vec3("b", HUGE_LENGTH).value_or(glm::dvec3(0.0, 5.0, 0.0));
            const double radius = t.number("radius", 3.0, 1e-4, MAX_LENGTH);
            return std::make_shared<CapsuleField>(a, b, radius);
        }
        if (type == "plane") {
            const glm::dvec3 normal = t.vec3("normal", 1.0).value_or(glm::dvec3(0.0, 1.0, 0.0));
            if (!(glm::dvec3(normal) != glm::dvec3(0.0))) t.fail(nullptr, "normal", "must not be [0, 0, 0]");
            const double offset = t.number("offset", 0.0, -HUGE_LENGTH, HUGE_LENGTH);
            return std::make_shared<PlaneField>(normal, offset);
        }
        t.fail(nullptr, "type", "= '" + type + "' is not a node type (one of " + joinTypes() + ")");
    }

    const toml::table* mNodes;
    const std::string& mSource;
    std::filesystem::path mBase;
    std::uint64_t mSeed;
    ImageCache& mImages;
    std::map<std::string, DensityFieldPtr> mBuilt;
    std::set<std::string> mVisiting;
};

} // namespace

const std::vector<std::string>& terrainNodeTypes()
{
    static const std::vector<std::string> types = {
        "box",    "capsule",  "cheese",  "heightfield", "image_heightfield", "intersect", "plane", "spaghetti",
        "sphere", "subtract", "terrace", "translate",   "union",             "warp",      "worms",
    };
    return types;
}

namespace {

/// Builds the tree of [terrain] in `table`; see readTerrainNodes.
DensityFieldPtr buildTree(const toml::table* table, const std::string& source,
                          const std::filesystem::path& baseDirectory, ImageCache& images, std::uint64_t seed)
{
    TableReader terrain(table, "terrain", source);
    if (!terrain.has("root")) {
        terrain.fail(nullptr, "root", "is required with [terrain.nodes]: the name of the node to sample");
    }
    const std::string rootName = terrain.string("root", "");
    const toml::node* nodesNode = terrain.node("nodes");
    if (nodesNode && !nodesNode->is_table()) terrain.fail(nodesNode, "nodes", "must be a table of named node tables");
    NodeBuilder nodes(nodesNode ? nodesNode->as_table() : nullptr, source, baseDirectory, seed, images);
    DensityFieldPtr root = nodes.build(rootName, terrain, "root");
    terrain.finish();
    // A node that nothing uses is most likely a mistake (a misspelt name).
    if (nodesNode) {
        TableReader all(nodesNode->as_table(), "terrain.nodes", source);
        for (const std::string& name : all.keys()) {
            if (!nodes.isBuilt(name)) {
                all.fail(nullptr, name, "is not used: no node's child or children, nor terrain.root, names it");
            }
        }
    }
    return root;
}

} // namespace

TerrainBuilder readTerrainNodes(const toml::table* terrainTable, const std::string& source,
                                const std::filesystem::path& baseDirectory, std::uint64_t seed)
{
    auto images = std::make_shared<ImageCache>();
    // Built once now, from the parsed document, so errors carry its lines.
    buildTree(terrainTable, source, baseDirectory, *images, seed);
    // Rebuilds (another seed) work on a copy of the table, which cannot fail
    // where this one did not (images are cached).
    auto table = std::make_shared<toml::table>(terrainTable ? *terrainTable : toml::table{});
    auto sourceCopy = std::make_shared<std::string>(source);
    return [table, sourceCopy, images, baseDirectory](std::uint64_t s) -> DensityFieldPtr {
        return buildTree(table.get(), *sourceCopy, baseDirectory, *images, s);
    };
}

} // namespace strata::app
