// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The density node types a scene can name, each with its keys: name, type,
/// default, range, unit and a one-line description. Scene readers validate
/// every node against it, `strata nodes` prints it and docs/nodes.md's node
/// table is generated from it. Each node type registers itself beside its
/// class (register*Nodes() in the node's .cpp), so adding a type is one class
/// plus one registration.
///
/// The registry knows no file format: a reader checks the user's values
/// against the NodeKeys, fills a NodeArgs (defaults for absent keys, child
/// nodes already built, images already loaded) and calls NodeType::build.

#include <strata/terrain/DensityField.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <variant>
#include <vector>

namespace strata::terrain {

struct HeightImage;
struct ElevationRaster;
struct FractalOptions;

using DensityFieldPtr = std::shared_ptr<const DensityField>;

/// What a key holds.
enum class NodeKeyType
{
    Number,   ///< a finite double within [min, max]
    Integer,  ///< an integer within [min, max]
    Boolean,  ///< true or false
    Choice,   ///< one of `choices`
    Vec2,     ///< [x, z], each component within [min, max]
    Vec3,     ///< [x, y, z], each component within [min, max]
    Child,    ///< the name of another node
    Children, ///< two or more node names
    Image,    ///< a height image file (relative to the scene's folder)
    Elevation, ///< a DEM file read through GDAL (relative to the scene's folder)
    Seed,     ///< this node's seed stream, an integer in [0, 2^63 − 1]; default: a hash of the node's name
    Points,   ///< a curve: two or more [input, output] pairs, inputs strictly increasing
};

/// "number", "integer", "boolean", "choice", "[x, z]", "[x, y, z]", "node", "nodes", "image", "DEM file", "seed",
/// "[[in, out], ...]".
const char* nodeKeyTypeName(NodeKeyType type);

/// A key's value: numbers, integers (and seeds), booleans, strings (choices,
/// image paths), vectors, child nodes, or the loaded image.
using NodeValue = std::variant<std::monostate, double, std::int64_t, bool, std::string, glm::dvec2, glm::dvec3,
                               DensityFieldPtr, std::vector<DensityFieldPtr>, std::shared_ptr<const HeightImage>,
                               std::shared_ptr<const ElevationRaster>, std::vector<glm::dvec2>>;

/// One key of a node type.
struct NodeKey
{
    std::string name;
    NodeKeyType type = NodeKeyType::Number;
    std::string description; ///< one line
    std::string unit;        ///< "m", "noise units", ... ("" for none)
    bool required = false;   ///< no default: the user must give it (child keys: optional ones read null when absent)
    NodeValue defaultValue;  ///< for optional keys (monostate for seeds and required keys)
    double min = 0.0, max = 0.0;      ///< Number, Integer, Vec2, Vec3 (per component)
    std::vector<std::string> choices; ///< Choice

    /// The default as the docs show it: "55", "[0, 0, 0]", "gradient",
    /// "hash of the node's name", "required".
    std::string defaultText() const;
    /// The range as the docs show it: "1 .. 24", "gradient, simplex", "".
    std::string rangeText() const;
};

/// What a whole scene's build shares with each node: limits the caller
/// set (the CLI's --max-memory) for nodes that do heavy work when built.
struct NodeBuildContext
{
    std::uint64_t maxMemoryBytes = 0; ///< 0: no budget
    /// Progress of a node's heavy work in [0, 1] (an erode node's pass);
    /// returning false stops it (strata::Error, Interrupted). May be empty.
    std::function<bool(double)> progress;
    /// The scene's `noise_version` (FractalOptions::version), for every node's noise.
    int noiseVersion = 1;
};

/// The checked values of one node's keys, given or defaulted. A reader
/// fills it (set()), a NodeType::build reads it.
class NodeArgs
{
public:
    NodeArgs(std::string nodeName, std::uint64_t seed)
        : mNodeName(std::move(nodeName)), mSeed(seed)
    {
    }

    double number(const std::string& key) const { return get<double>(key); }
    std::int64_t integer(const std::string& key) const { return get<std::int64_t>(key); }
    bool boolean(const std::string& key) const { return get<bool>(key); }
    const std::string& string(const std::string& key) const { return get<std::string>(key); }
    glm::dvec2 vec2(const std::string& key) const { return get<glm::dvec2>(key); }
    glm::dvec3 vec3(const std::string& key) const { return get<glm::dvec3>(key); }
    DensityFieldPtr child(const std::string& key) const { return get<DensityFieldPtr>(key); }
    const std::vector<DensityFieldPtr>& children(const std::string& key) const
    {
        return get<std::vector<DensityFieldPtr>>(key);
    }
    const HeightImage& image(const std::string& key) const;
    const ElevationRaster& elevation(const std::string& key) const;
    /// A Points key's pairs.
    const std::vector<glm::dvec2>& points(const std::string& key) const { return get<std::vector<glm::dvec2>>(key); }
    /// Whether the user wrote `key` (rather than taking its default).
    bool given(const std::string& key) const { return mGiven.count(key) > 0; }
    void markGiven(const std::string& key) { mGiven.insert(key); }
    const NodeBuildContext& context() const { return mContext; }
    void setContext(const NodeBuildContext& context) { mContext = context; }

    /// This node's noise seed: the scene seed combined with the `seed` key
    /// (deriveSeed), set by the reader.
    std::uint64_t seed() const { return mSeed; }
    const std::string& nodeName() const { return mNodeName; }

    /// Throws strata::Error (BadInput) "KEY WHAT" with place().key = `key`,
    /// for checks across keys (e.g. max > min); the reader adds file and line.
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;

    void set(const std::string& key, NodeValue value) { mValues[key] = std::move(value); }

private:
    template <typename T>
    const T& get(const std::string& key) const;

    std::string mNodeName;
    std::uint64_t mSeed;
    std::map<std::string, NodeValue> mValues;
    std::set<std::string> mGiven;
    NodeBuildContext mContext;
};

/// A node type: its name, what it makes, its keys and how to build it.
struct NodeType
{
    std::string name;
    std::string description; ///< one line
    std::vector<NodeKey> keys;
    /// Builds the field from checked arguments; throws strata::Error
    /// (through NodeArgs::fail) for combinations the key ranges cannot express.
    std::function<DensityFieldPtr(const NodeArgs&)> build;

    /// The key named `key`, or null.
    const NodeKey* findKey(const std::string& key) const;
};

/// The node types by name.
class NodeRegistry
{
public:
    /// Adds a type; a type of the same name is replaced.
    void add(NodeType type);
    /// The type named `name`, or null.
    const NodeType* find(const std::string& name) const;
    /// Every type, sorted by name.
    std::vector<const NodeType*> types() const;
    /// "box, capsule, ..." for messages.
    std::string typeList() const;

    /// Every node type of this library (heightfields, caves, warp, terrace,
    /// translate, CSG, primitives). Built once; thread-safe to read.
    static const NodeRegistry& builtin();

private:
    std::map<std::string, NodeType> mTypes;
};

// Key makers for registrations, so each reads as one line.
NodeKey numberKey(std::string name, double fallback, double min, double max, std::string unit, std::string description);
NodeKey integerKey(std::string name, std::int64_t fallback, std::int64_t min, std::int64_t max, std::string unit,
                   std::string description);
NodeKey booleanKey(std::string name, bool fallback, std::string description);
NodeKey choiceKey(std::string name, std::string fallback, std::vector<std::string> choices, std::string description);
NodeKey vec2Key(std::string name, glm::dvec2 fallback, double limit, std::string unit, std::string description);
NodeKey vec3Key(std::string name, glm::dvec3 fallback, double limit, std::string unit, std::string description);
NodeKey childKey(std::string name, std::string description);
/// A child key that may be left out (the child then reads null).
NodeKey optionalChildKey(std::string name, std::string description);
NodeKey pointsKey(std::string name, std::vector<glm::dvec2> fallback, double limit, std::string unit,
                  std::string description);
NodeKey childrenKey(std::string name, std::string description);
NodeKey imageKey(std::string name, std::string description);
/// A required DEM file key (NodeKeyType::Elevation).
NodeKey elevationKey(std::string name, std::string description);
NodeKey seedKey();

/// The noise keys every noise node takes (noise, fractal, octaves,
/// lacunarity, gain), with `defaults` as their defaults.
void addFractalKeys(std::vector<NodeKey>& keys, const FractalOptions& defaults);
/// Reads them back.
FractalOptions fractalOptions(const NodeArgs& args);

/// The largest coordinate a scene may use (metres) and the largest size
/// (wavelength, radius...), shared by the registrations.
inline constexpr double HUGE_LENGTH = 1e9;
inline constexpr double MAX_LENGTH = 1e7;

} // namespace strata::terrain
