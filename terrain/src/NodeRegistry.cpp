// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/NodeRegistry.h>

#include "NodeRegistrations.h"

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/FractalNoise.h>
#include <strata/terrain/Heightfield.h>

#include <limits>

namespace strata::terrain {

namespace {

std::string showVector(const double* v, int n)
{
    std::string out = "[";
    for (int i = 0; i < n; ++i) out += (i ? ", " : "") + formatNumber(v[i]);
    return out + "]";
}

const char* noiseTypeName(NoiseType type)
{
    switch (type) {
    case NoiseType::GRADIENT: return "gradient";
    case NoiseType::SIMPLEX: return "simplex";
    case NoiseType::VALUE: return "value";
    case NoiseType::CELLULAR_F1: return "cellular_f1";
    case NoiseType::CELLULAR_F2: return "cellular_f2";
    }
    return "gradient";
}

const char* fractalTypeName(FractalType type)
{
    switch (type) {
    case FractalType::FBM: return "fbm";
    case FractalType::RIDGED: return "ridged";
    case FractalType::BILLOW: return "billow";
    }
    return "fbm";
}

} // namespace

const char* nodeKeyTypeName(NodeKeyType type)
{
    switch (type) {
    case NodeKeyType::Number: return "number";
    case NodeKeyType::Integer: return "integer";
    case NodeKeyType::Boolean: return "boolean";
    case NodeKeyType::Choice: return "choice";
    case NodeKeyType::Vec2: return "[x, z]";
    case NodeKeyType::Vec3: return "[x, y, z]";
    case NodeKeyType::Child: return "node";
    case NodeKeyType::Children: return "nodes";
    case NodeKeyType::Image: return "image";
    case NodeKeyType::Elevation: return "DEM file";
    case NodeKeyType::Seed: return "seed";
    case NodeKeyType::Points: return "[[in, out], ...]";
    }
    return "number";
}

std::string NodeKey::defaultText() const
{
    if (required) return "required";
    if (type == NodeKeyType::Seed) return "hash of the node's name";
    if (const auto* d = std::get_if<double>(&defaultValue)) return formatNumber(*d);
    if (const auto* i = std::get_if<std::int64_t>(&defaultValue)) return std::to_string(*i);
    if (const auto* b = std::get_if<bool>(&defaultValue)) return *b ? "true" : "false";
    if (const auto* s = std::get_if<std::string>(&defaultValue)) return *s;
    if (const auto* v = std::get_if<glm::dvec2>(&defaultValue)) return showVector(&v->x, 2);
    if (const auto* v = std::get_if<glm::dvec3>(&defaultValue)) return showVector(&v->x, 3);
    if (const auto* p = std::get_if<std::vector<glm::dvec2>>(&defaultValue)) {
        std::string out = "[";
        for (std::size_t i = 0; i < p->size(); ++i) out += (i ? ", " : "") + showVector(&(*p)[i].x, 2);
        return out + "]";
    }
    if (type == NodeKeyType::Child) return "none";
    return "";
}

std::string NodeKey::rangeText() const
{
    switch (type) {
    case NodeKeyType::Number:
    case NodeKeyType::Vec2:
    case NodeKeyType::Vec3:
    case NodeKeyType::Points: return formatNumber(min) + " .. " + formatNumber(max);
    case NodeKeyType::Integer: return std::to_string(std::int64_t(min)) + " .. " + std::to_string(std::int64_t(max));
    case NodeKeyType::Choice: {
        std::string out;
        for (const std::string& c : choices) out += (out.empty() ? "" : ", ") + c;
        return out;
    }
    case NodeKeyType::Children: return "2 or more";
    case NodeKeyType::Seed: return "0 .. 2^63-1";
    default: return "";
    }
}

template <typename T>
const T& NodeArgs::get(const std::string& key) const
{
    const auto found = mValues.find(key);
    // A registration reading a key it did not declare, or of another type, is a bug.
    if (found == mValues.end() || !std::holds_alternative<T>(found->second)) {
        throw Error(ErrorKind::Internal, "node '" + mNodeName + "': key '" + key + "' was not read as declared");
    }
    return std::get<T>(found->second);
}

// The value types NodeArgs hands out (declared in the header, defined here).
template const double& NodeArgs::get<double>(const std::string&) const;
template const std::int64_t& NodeArgs::get<std::int64_t>(const std::string&) const;
template const bool& NodeArgs::get<bool>(const std::string&) const;
template const std::string& NodeArgs::get<std::string>(const std::string&) const;
template const glm::dvec2& NodeArgs::get<glm::dvec2>(const std::string&) const;
template const glm::dvec3& NodeArgs::get<glm::dvec3>(const std::string&) const;
template const DensityFieldPtr& NodeArgs::get<DensityFieldPtr>(const std::string&) const;
template const std::vector<DensityFieldPtr>& NodeArgs::get<std::vector<DensityFieldPtr>>(const std::string&) const;
template const std::vector<glm::dvec2>& NodeArgs::get<std::vector<glm::dvec2>>(const std::string&) const;

const HeightImage& NodeArgs::image(const std::string& key) const
{
    const std::shared_ptr<const HeightImage>& image = get<std::shared_ptr<const HeightImage>>(key);
    if (!image) throw Error(ErrorKind::Internal, "node '" + mNodeName + "': image '" + key + "' was not loaded");
    return *image;
}

const ElevationRaster& NodeArgs::elevation(const std::string& key) const
{
    const std::shared_ptr<const ElevationRaster>& raster = get<std::shared_ptr<const ElevationRaster>>(key);
    if (!raster) throw Error(ErrorKind::Internal, "node '" + mNodeName + "': DEM '" + key + "' was not loaded");
    return *raster;
}

void NodeArgs::fail(const std::string& key, const std::string& what) const
{
    throw Error(ErrorKind::BadInput, key + " " + what, {"", 0, key, ""});
}

const NodeKey* NodeType::findKey(const std::string& key) const
{
    for (const NodeKey& k : keys) {
        if (k.name == key) return &k;
    }
    return nullptr;
}

void NodeRegistry::add(NodeType type)
{
    const std::string name = type.name;
    mTypes.insert_or_assign(name, std::move(type));
}

const NodeType* NodeRegistry::find(const std::string& name) const
{
    const auto found = mTypes.find(name);
    return found == mTypes.end() ? nullptr : &found->second;
}

std::vector<const NodeType*> NodeRegistry::types() const
{
    std::vector<const NodeType*> out;
    for (const auto& [name, type] : mTypes) out.push_back(&type); // std::map: sorted by name
    return out;
}

std::string NodeRegistry::typeList() const
{
    std::string out;
    for (const auto& [name, type] : mTypes) out += (out.empty() ? "" : ", ") + name;
    return out;
}

const NodeRegistry& NodeRegistry::builtin()
{
    static const NodeRegistry registry = [] {
        NodeRegistry r;
        registerHeightfieldNodes(r);
        registerDemNodes(r);
        registerCaveNodes(r);
        registerTransformNodes(r);
        registerCsgNodes(r);
        registerPrimitiveNodes(r);
        registerHeightGraphNodes(r);
        registerGeologyNodes(r);
        return r;
    }();
    return registry;
}

NodeKey numberKey(std::string name, double fallback, double min, double max, std::string unit, std::string description)
{
    NodeKey k;
    k.name = std::move(name);
    k.type = NodeKeyType::Number;
    k.defaultValue = fallback;
    k.min = min;
    k.max = max;
    k.unit = std::move(unit);
    k.description = std::move(description);
    return k;
}

NodeKey integerKey(std::string name, std::int64_t fallback, std::int64_t min, std::int64_t max, std::string unit,
                   std::string description)
{
    NodeKey k = numberKey(std::move(name), 0.0, double(min), double(max), std::move(unit), std::move(description));
    k.type = NodeKeyType::Integer;
    k.defaultValue = fallback;
    return k;
}

NodeKey booleanKey(std::string name, bool fallback, std::string description)
{
    NodeKey k;
    k.name = std::move(name);
    k.type = NodeKeyType::Boolean;
    k.defaultValue = fallback;
    k.description = std::move(description);
    return k;
}

NodeKey choiceKey(std::string name, std::string fallback, std::vector<std::string> choices, std::string description)
{
    NodeKey k;
    k.name = std::move(name);
    k.type = NodeKeyType::Choice;
    k.defaultValue = std::move(fallback);
    k.choices = std::move(choices);
    k.description = std::move(description);
    return k;
}

NodeKey vec2Key(std::string name, glm::dvec2 fallback, double limit, std::string unit, std::string description)
{
    NodeKey k = numberKey(std::move(name), 0.0, -limit, limit, std::move(unit), std::move(description));
    k.type = NodeKeyType::Vec2;
    k.defaultValue = fallback;
    return k;
}

NodeKey vec3Key(std::string name, glm::dvec3 fallback, double limit, std::string unit, std::string description)
{
    NodeKey k = numberKey(std::move(name), 0.0, -limit, limit, std::move(unit), std::move(description));
    k.type = NodeKeyType::Vec3;
    k.defaultValue = fallback;
    return k;
}

NodeKey childKey(std::string name, std::string description)
{
    NodeKey k;
    k.name = std::move(name);
    k.type = NodeKeyType::Child;
    k.required = true;
    k.description = std::move(description);
    return k;
}

NodeKey childrenKey(std::string name, std::string description)
{
    NodeKey k = childKey(std::move(name), std::move(description));
    k.type = NodeKeyType::Children;
    return k;
}

NodeKey optionalChildKey(std::string name, std::string description)
{
    NodeKey k = childKey(std::move(name), std::move(description));
    k.required = false;
    k.defaultValue = DensityFieldPtr{};
    return k;
}

NodeKey pointsKey(std::string name, std::vector<glm::dvec2> fallback, double limit, std::string unit,
                  std::string description)
{
    NodeKey k = numberKey(std::move(name), 0.0, -limit, limit, std::move(unit), std::move(description));
    k.type = NodeKeyType::Points;
    k.defaultValue = std::move(fallback);
    return k;
}

NodeKey imageKey(std::string name, std::string description)
{
    NodeKey k = childKey(std::move(name), std::move(description));
    k.type = NodeKeyType::Image;
    return k;
}

NodeKey elevationKey(std::string name, std::string description)
{
    NodeKey k = childKey(std::move(name), std::move(description));
    k.type = NodeKeyType::Elevation;
    return k;
}

NodeKey seedKey()
{
    NodeKey k;
    k.name = "seed";
    k.type = NodeKeyType::Seed;
    k.min = 0.0;
    k.max = double(std::numeric_limits<std::int64_t>::max());
    k.description = "this node's noise stream, combined with the scene seed";
    return k;
}

void addFractalKeys(std::vector<NodeKey>& keys, const FractalOptions& d)
{
    keys.push_back(choiceKey("noise", noiseTypeName(d.noise),
                             {"gradient", "simplex", "value", "cellular_f1", "cellular_f2"}, "the noise basis"));
    keys.push_back(choiceKey("fractal", fractalTypeName(d.fractal), {"fbm", "ridged", "billow"},
                             "how octaves combine"));
    keys.push_back(integerKey("octaves", d.octaves, 1, 24, "", "number of noise octaves summed"));
    keys.push_back(numberKey("lacunarity", d.lacunarity, 1.0, 8.0, "", "frequency ratio between octaves"));
    keys.push_back(numberKey("gain", d.gain, 0.0, 1.0, "", "amplitude ratio between octaves"));
    keys.push_back(seedKey());
}

FractalOptions fractalOptions(const NodeArgs& args)
{
    FractalOptions o;
    parseNoiseType(args.string("noise"), o.noise);
    parseFractalType(args.string("fractal"), o.fractal);
    o.octaves = int(args.integer("octaves"));
    o.lacunarity = args.number("lacunarity");
    o.gain = args.number("gain");
    o.version = args.context().noiseVersion;
    return o;
}

} // namespace strata::terrain
