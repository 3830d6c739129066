// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "SceneTerrain.h"

#include <strata/terrain/ErodedHeightfield.h>

#include "DemFile.h"
#include "HeightImageFile.h"

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/DemHeightfield.h>
#include <strata/terrain/Heightfield.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/terrain/Noise.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
#include <set>

namespace strata::scene {

namespace {

using namespace strata::terrain;

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

/// Input files (height images, DEMs) read once per scene, shared by every
/// build (seed override).
struct ImageCache
{
    std::mutex mutex;
    std::map<std::string, std::shared_ptr<const HeightImage>> images;
    std::map<std::string, std::shared_ptr<const terrain::ElevationRaster>> dems;
};

/// The file at `path` from `files`, read by `read` the first time; a read
/// error names the scene key.
template <typename T, typename Read>
std::shared_ptr<const T> readCached(std::map<std::string, std::shared_ptr<const T>>& files, std::mutex& mutex,
                                    const std::filesystem::path& path, TableReader& t, const std::string& key, Read read)
{
    std::lock_guard<std::mutex> lock(mutex);
    auto found = files.find(path.string());
    if (found != files.end()) return found->second;
    std::shared_ptr<const T> file;
    try {
        file = std::make_shared<const T>(read(path));
    } catch (const Error& e) {
        t.fail(nullptr, key, "= '" + path.string() + "': " + e.what());
    }
    files.emplace(path.string(), file);
    return file;
}

/// The deepest node tree a scene may have: deeper chains are almost surely a
/// generated mistake, and evaluating them would recurse that deep per voxel.
constexpr int MAX_NODE_DEPTH = 256;

/// Builds nodes by name from [terrain.nodes.*], checking every key against
/// the node registry.
class NodeBuilder
{
public:
    NodeBuilder(const toml::table* nodes, const std::string& source, const std::filesystem::path& baseDirectory,
                std::uint64_t seed, ImageCache& images, const NodeBuildContext& context)
        : mNodes(nodes), mSource(source), mBase(baseDirectory), mSeed(seed), mImages(images), mContext(context)
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
            const int line = int(node->source().begin.line);
            throw Error(ErrorKind::BadInput,
                        mSource + ":" + std::to_string(line) + ": terrain.nodes." + name + " " +
                            TableReader::shown(node) + "must be a table",
                        {mSource, line, "terrain.nodes." + name, ""});
        }
        if (mVisiting.count(name)) {
            referrer.fail(nullptr, key, "= '" + name + "' makes a cycle: a node cannot contain itself");
        }
        if (int(mVisiting.size()) >= MAX_NODE_DEPTH) {
            referrer.fail(nullptr, key,
                          "= '" + name + "' is too deep: the node tree may be at most " +
                              std::to_string(MAX_NODE_DEPTH) + " levels deep");
        }
        mVisiting.insert(name);
        TableReader t(node->as_table(), "terrain.nodes." + name, mSource);
        DensityFieldPtr field = make(name, t);
        t.finish();
        mVisiting.erase(name);
        mBuilt.emplace(name, field);
        if (auto masks = std::dynamic_pointer_cast<const LandformMasks>(field)) mLandform.emplace(name, masks);
        if (auto rock = std::dynamic_pointer_cast<const terrain::RockMasks>(field)) mRock.emplace(name, rock);
        if (auto dem = std::dynamic_pointer_cast<const terrain::DemHeightfield>(field); dem && dem->originLatitudeLongitude())
            mPlaced.emplace(name, dem);
        if (auto eroded = std::dynamic_pointer_cast<const ErodedHeightfield>(field); eroded && !mPassOf.count(eroded.get())) {
            mPassOf.insert(eroded.get());
            const ErodedGrid& grid = eroded->grid();
            mPasses.push_back({name, std::size_t(grid.width) * std::size_t(grid.height),
                               ErodedHeightfield::peakBytes(eroded->options()), grid.seconds, eroded->cached(),
                               grid.budget.steps});
        }
        return field;
    }

    bool isBuilt(const std::string& name) const { return mBuilt.count(name) > 0; }

    /// The built nodes with landform masks (erode nodes), by name.
    const std::map<std::string, LandformMasksPtr>& landformNodes() const { return mLandform; }
    /// The built nodes with rock masks (beds nodes), by name.
    const std::map<std::string, RockMasksPtr>& rockNodes() const { return mRock; }
    /// The DEM nodes whose CRS puts them on the Earth.
    const std::map<std::string, std::shared_ptr<const terrain::DemHeightfield>>& placedNodes() const { return mPlaced; }
    /// The erode nodes' passes, in build order.
    const std::vector<LandformPass>& passes() const { return mPasses; }

private:
    /// Reads every key of `type` from `t` into arguments: types and ranges
    /// checked, defaults filled in, children built, images loaded.
    /// A file key's path, relative ones from the scene's folder.
    std::filesystem::path inputFile(TableReader& t, const std::string& key) const
    {
        std::filesystem::path file = t.string(key, "");
        return file.is_relative() ? mBase / file : file;
    }

    NodeArgs readArgs(const std::string& name, const NodeType& type, TableReader& t)
    {
        // The seed first: NodeArgs carries the derived one.
        std::uint64_t seed = 0;
        if (type.findKey("seed")) {
            const std::int64_t stream =
                t.integer("seed", std::int64_t(nameStream(name) >> 1), 0, std::numeric_limits<std::int64_t>::max());
            seed = deriveSeed(mSeed, std::uint64_t(stream));
        }
        NodeArgs args(name, seed);
        args.setContext(mContext);
        for (const NodeKey& key : type.keys) {
            if (key.required && !t.has(key.name)) t.fail(nullptr, key.name, "is required (" + key.description + ")");
            if (t.has(key.name)) args.markGiven(key.name);
            switch (key.type) {
            case NodeKeyType::Number:
                args.set(key.name, t.number(key.name, std::get<double>(key.defaultValue), key.min, key.max));
                break;
            case NodeKeyType::Integer:
                args.set(key.name, t.integer(key.name, std::get<std::int64_t>(key.defaultValue),
                                             std::int64_t(key.min), std::int64_t(key.max)));
                break;
            case NodeKeyType::Boolean: args.set(key.name, t.boolean(key.name, std::get<bool>(key.defaultValue))); break;
            case NodeKeyType::Choice: {
                const std::string value = t.string(key.name, std::get<std::string>(key.defaultValue));
                if (std::find(key.choices.begin(), key.choices.end(), value) == key.choices.end()) {
                    t.fail(nullptr, key.name, "= '" + value + "' is not one of " + key.rangeText());
                }
                args.set(key.name, value);
                break;
            }
            case NodeKeyType::Vec2: args.set(key.name, vec2(t, key)); break;
            case NodeKeyType::Vec3:
                args.set(key.name, t.vec3(key.name, key.max).value_or(std::get<glm::dvec3>(key.defaultValue)));
                break;
            case NodeKeyType::Child:
                if (!key.required && !t.has(key.name)) args.set(key.name, DensityFieldPtr{});
                else args.set(key.name, build(t.string(key.name, ""), t, key.name));
                break;
            case NodeKeyType::Points: args.set(key.name, points(t, key)); break;
            case NodeKeyType::Children: args.set(key.name, children(t, key.name)); break;
            case NodeKeyType::Image:
                args.set(key.name, readCached(mImages.images, mImages.mutex, inputFile(t, key.name), t, key.name,
                                              readHeightImageFile));
                break;
            case NodeKeyType::Elevation:
                args.set(key.name, readCached(mImages.dems, mImages.mutex, inputFile(t, key.name), t, key.name,
                                              readDemFile));
                break;
            case NodeKeyType::Seed: break; // read above
            }
        }
        return args;
    }

    DensityFieldPtr make(const std::string& name, TableReader& t)
    {
        const NodeRegistry& registry = NodeRegistry::builtin();
        if (!t.has("type")) t.fail(nullptr, "type", "is required (one of " + registry.typeList() + ")");
        const std::string typeName = t.string("type", "");
        const NodeType* type = registry.find(typeName);
        if (!type) {
            t.fail(nullptr, "type", "= '" + typeName + "' is not a node type (one of " + registry.typeList() + ")");
        }
        const NodeArgs args = readArgs(name, *type, t);
        try {
            return type->build(args);
        } catch (const Error& e) {
            if (e.kind() == ErrorKind::Interrupted) throw; // stopped, not wrong
            // A check across keys (NodeArgs::fail) names its key: point at it.
            const std::string& key = e.place().key;
            const std::string what = e.what();
            if (!key.empty() && t.has(key) && what.rfind(key + " ", 0) == 0) {
                const std::string rest = what.substr(key.size() + 1);
                t.fail(nullptr, key, rest.rfind("= ", 0) == 0 ? rest : t.shown(key) + rest);
            }
            // The library's own checks: at the node's type line.
            t.fail(nullptr, "type", "= '" + typeName + "': " + what);
        }
    }

    std::vector<DensityFieldPtr> children(TableReader& t, const std::string& key)
    {
        const toml::node* node = t.node(key);
        const toml::array* array = node ? node->as_array() : nullptr;
        if (!array || array->size() < 2) {
            t.fail(node, key, TableReader::shown(node) + "must be an array of at least two node names, e.g. [\"land\", \"caves\"]");
        }
        std::vector<DensityFieldPtr> out;
        for (std::size_t i = 0; i < array->size(); ++i) {
            const toml::node& element = *array->get(i);
            if (!element.is_string()) t.fail(&element, key, TableReader::shown(&element) + "must hold node names (strings)");
            out.push_back(build(*element.value<std::string>(), t, key));
        }
        return out;
    }

    /// A curve: [[in, out], ...], two or more pairs of finite numbers
    /// within the key's range (the node checks the order).
    std::vector<glm::dvec2> points(TableReader& t, const NodeKey& key)
    {
        const toml::node* node = t.node(key.name);
        if (!node) return std::get<std::vector<glm::dvec2>>(key.defaultValue);
        const toml::array* array = node->as_array();
        const std::string form = "must be an array of two or more [input, output] pairs of finite numbers within ±" +
                                 formatNumber(key.max) + ", e.g. [[0, 0], [50, 20], [100, 100]]";
        if (!array || array->size() < 2) t.fail(node, key.name, TableReader::shown(node) + form);
        std::vector<glm::dvec2> out;
        for (std::size_t i = 0; i < array->size(); ++i) {
            const toml::array* pair = array->get(i)->as_array();
            if (!pair || pair->size() != 2) t.fail(node, key.name, TableReader::shown(node) + form);
            glm::dvec2 p;
            for (int c = 0; c < 2; ++c) {
                const toml::node& element = *pair->get(std::size_t(c));
                const std::optional<double> value = element.value<double>();
                if (!value || element.is_boolean() || !std::isfinite(*value) || std::abs(*value) > key.max) {
                    t.fail(node, key.name, TableReader::shown(node) + form);
                }
                p[c] = *value;
            }
            out.push_back(p);
        }
        return out;
    }

    glm::dvec2 vec2(TableReader& t, const NodeKey& key)
    {
        const toml::node* node = t.node(key.name);
        if (!node) return std::get<glm::dvec2>(key.defaultValue);
        const toml::array* array = node->as_array();
        if (!array || array->size() != 2) t.fail(node, key.name, TableReader::shown(node) + "must be an array of two numbers [x, z]");
        glm::dvec2 v;
        for (int i = 0; i < 2; ++i) {
            const toml::node& element = *array->get(std::size_t(i));
            const std::optional<double> value = element.value<double>();
            if (!value || element.is_boolean() || !std::isfinite(*value) || *value < key.min || *value > key.max) {
                t.fail(node, key.name,
                       TableReader::shown(node) + "must be an array of two finite numbers [x, z] within ±" +
                           formatNumber(key.max));
            }
            v[i] = *value;
        }
        return v;
    }

    const toml::table* mNodes;
    const std::string& mSource;
    std::filesystem::path mBase;
    std::uint64_t mSeed;
    ImageCache& mImages;
    std::map<std::string, DensityFieldPtr> mBuilt;
    std::map<std::string, LandformMasksPtr> mLandform;
    std::map<std::string, RockMasksPtr> mRock;
    std::map<std::string, std::shared_ptr<const terrain::DemHeightfield>> mPlaced;
    NodeBuildContext mContext;
    std::vector<LandformPass> mPasses;
    std::set<const void*> mPassOf;
    std::set<std::string> mVisiting;
};

/// "'a', 'b'" for messages.
template<typename Masks>
std::string quotedNames(const std::map<std::string, Masks>& nodes)
{
    std::string out;
    for (const auto& [name, masks] : nodes) out += (out.empty() ? "'" : ", '") + name + "'";
    return out;
}

/// The mask source of a built tree: `terrain.KEY` when given (it must name
/// one of `nodes`), else the only one of `nodes`, else null. `what` names
/// the masks ("landform masks"), `nodeType` the node that has them.
template<typename Masks>
Masks chooseMaskSource(TableReader& terrain, const std::map<std::string, Masks>& nodes, const std::string& key,
                       const std::string& what, const std::string& nodeType,
                       const std::string& purpose = "the one layer rules read")
{
    if (terrain.has(key)) {
        const std::string name = terrain.string(key, "");
        auto found = nodes.find(name);
        if (found == nodes.end()) {
            terrain.fail(nullptr, key,
                         "= '" + name + "' is not a node with " + what +
                             (nodes.empty() ? ": the tree has none (add " + nodeType + " node)"
                                            : " (one of " + quotedNames(nodes) + ")"));
        }
        return found->second;
    }
    // Names that lead to the same node (a `heightfield` whose `height` is an
    // erode node is that node) are one source.
    std::set<const void*> distinct;
    for (const auto& [name, masks] : nodes) distinct.insert(masks.get());
    if (distinct.size() > 1) {
        terrain.fail(nullptr, key,
                     "is required: the tree has " + std::to_string(nodes.size()) + " nodes with " + what + " (" +
                         quotedNames(nodes) + "); name " + purpose + ", e.g. " + key + " = '" +
                         nodes.begin()->first + "'");
    }
    return nodes.empty() ? nullptr : nodes.begin()->second;
}

} // namespace

const std::vector<std::string>& terrainNodeTypes()
{
    static const std::vector<std::string> types = [] {
        std::vector<std::string> out;
        for (const NodeType* type : NodeRegistry::builtin().types()) out.push_back(type->name);
        return out;
    }();
    return types;
}

namespace {

/// Builds the tree of [terrain] in `table`; see readTerrainNodes.
TerrainTree buildTree(const toml::table* table, const std::string& source, const std::filesystem::path& baseDirectory,
                      ImageCache& images, std::uint64_t seed, const NodeBuildContext& context)
{
    TableReader terrain(table, "terrain", source);
    if (!terrain.has("root")) {
        terrain.fail(nullptr, "root", "is required with [terrain.nodes]: the name of the node to sample");
    }
    const std::string rootName = terrain.string("root", "");
    const toml::node* nodesNode = terrain.node("nodes");
    if (nodesNode && !nodesNode->is_table()) terrain.fail(nodesNode, "nodes", "must be a table of named node tables");
    NodeBuilder nodes(nodesNode ? nodesNode->as_table() : nullptr, source, baseDirectory, seed, images, context);
    TerrainTree tree;
    tree.root = nodes.build(rootName, terrain, "root");
    tree.landformMasks = chooseMaskSource(terrain, nodes.landformNodes(), "masks", "landform masks", "an `erode`");
    tree.rockMasks = chooseMaskSource(terrain, nodes.rockNodes(), "rock", "rock masks", "a `beds`");
    if (auto dem = chooseMaskSource(terrain, nodes.placedNodes(), "georeference", "a georeferenced DEM",
                                    "a `dem_heightfield`",
                                    "the one that places the scene on the Earth")) {
        const glm::dvec2 latLon = *dem->originLatitudeLongitude();
        tree.georeference = Georeference{latLon.x, latLon.y, dem->originHeight()};
    }
    tree.passes = nodes.passes();
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
    return tree;
}

/// The last tree built, by seed (a rebuild for --seed builds the erosion
/// of an `erode` node once for the root and its masks).
struct LastTree
{
    std::mutex mutex;
    std::uint64_t seed = 0;
    TerrainTree tree;
};

} // namespace

TerrainBuilder readTerrainNodes(const toml::table* terrainTable, const std::string& source,
                                const std::filesystem::path& baseDirectory, std::uint64_t seed,
                                std::vector<std::filesystem::path>* inputFiles, std::uint64_t maxMemoryBytes,
                                const std::function<bool(double)>& progress, int noiseVersion)
{
    NodeBuildContext context{maxMemoryBytes, progress, noiseVersion};
    auto images = std::make_shared<ImageCache>();
    // Built once now, from the parsed document, so errors carry its lines.
    auto last = std::make_shared<LastTree>();
    last->seed = seed;
    last->tree = buildTree(terrainTable, source, baseDirectory, *images, seed, context);
    if (inputFiles)
    {
        for (const auto& [path, image] : images->images) inputFiles->push_back(path);
        for (const auto& [path, dem] : images->dems) inputFiles->push_back(path);
        std::sort(inputFiles->begin(), inputFiles->end());
    }
    // Rebuilds (another seed) work on a copy of the table, which cannot fail
    // where this one did not (images are cached).
    auto table = std::make_shared<toml::table>(terrainTable ? *terrainTable : toml::table{});
    auto sourceCopy = std::make_shared<std::string>(source);
    context.progress = nullptr; // the caller's callable need not outlive the load
    return [table, sourceCopy, images, baseDirectory, last, context](std::uint64_t s) -> TerrainTree {
        std::lock_guard<std::mutex> lock(last->mutex);
        if (last->seed != s) {
            last->tree = buildTree(table.get(), *sourceCopy, baseDirectory, *images, s, context);
            last->seed = s;
        }
        return last->tree;
    };
}

} // namespace strata::scene
