// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GltfCompact.h>

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <glm/geometric.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <map>

namespace strata::meshing {

namespace {

using nlohmann::json;

constexpr int GL_ARRAY_BUFFER = 34962;
constexpr int GL_ELEMENT_ARRAY_BUFFER = 34963;
constexpr int GL_BYTE = 5120, GL_SHORT = 5122, GL_UNSIGNED_SHORT = 5123, GL_UNSIGNED_INT = 5125, GL_FLOAT = 5126;
constexpr std::int64_t POSITION_RANGE = 65535;

std::size_t align4(std::size_t n) { return (n + 3) & ~std::size_t(3); }

/// The two buffers of a compact .glb: the compressed bytes (the GLB's BIN
/// chunk, buffer 0) and the fallback buffer's length (buffer 1, no data).
struct Buffers
{
    std::vector<unsigned char> bin;
    std::size_t fallbackLength = 0;
    json views = json::array();

    /// Compresses `count` elements of `stride` bytes (`mode` ATTRIBUTES or
    /// TRIANGLES, `filter` NONE or OCTAHEDRAL) and adds a buffer view for
    /// them; returns its index.
    int add(const void* data, std::size_t count, std::size_t stride, bool indices, const char* filter)
    {
        std::vector<unsigned char> packed;
        if (indices) {
            // The index codec takes 32-bit indices and decodes to 2 or 4 bytes.
            const auto* source = static_cast<const std::uint32_t*>(data);
            std::size_t vertices = 0;
            for (std::size_t i = 0; i < count; ++i) vertices = std::max<std::size_t>(vertices, source[i] + 1);
            packed.resize(meshopt_encodeIndexBufferBound(count, vertices));
            packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(), source, count));
        } else {
            packed.resize(meshopt_encodeVertexBufferBound(count, stride));
            packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), data, count, stride));
        }
        if (packed.empty()) throw Error(ErrorKind::Internal, "meshoptimizer could not encode a glTF buffer view");

        bin.resize(align4(bin.size()), 0);
        json extension = {{"buffer", 0},
                          {"byteOffset", bin.size()},
                          {"byteLength", packed.size()},
                          {"byteStride", stride},
                          {"count", count},
                          {"mode", indices ? "TRIANGLES" : "ATTRIBUTES"}};
        if (std::strcmp(filter, "NONE") != 0) extension["filter"] = filter;
        bin.insert(bin.end(), packed.begin(), packed.end());

        fallbackLength = align4(fallbackLength);
        json view = {{"buffer", 1}, {"byteOffset", fallbackLength}, {"byteLength", count * stride}};
        if (!indices) view["byteStride"] = stride; // index views must not have one
        view["target"] = indices ? GL_ELEMENT_ARRAY_BUFFER : GL_ARRAY_BUFFER;
        view["extensions"] = {{"EXT_meshopt_compression", extension}};
        fallbackLength += count * stride;
        views.push_back(std::move(view));
        return int(views.size() - 1);
    }
};

/// The primitive with its triangles in vertex-cache order and its vertices
/// in first-use order (meshoptimizer), every attribute remapped alike.
TriangleMesh reorder(const TriangleMesh& mesh)
{
    TriangleMesh out = mesh;
    const std::size_t n = mesh.positions.size();
    meshopt_optimizeVertexCache(out.indices.data(), mesh.indices.data(), mesh.indices.size(), n);
    std::vector<unsigned int> remap(n);
    const std::size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), out.indices.data(), out.indices.size(), n);
    meshopt_remapIndexBuffer(out.indices.data(), out.indices.data(), out.indices.size(), remap.data());
    auto apply = [&](auto& values, const auto& source) {
        if (source.size() != n) return;
        values.assign(used, {});
        for (std::size_t i = 0; i < n; ++i)
            if (remap[i] != ~0u) values[remap[i]] = source[i];
    };
    apply(out.positions, mesh.positions);
    apply(out.normals, mesh.normals);
    apply(out.surface, mesh.surface);
    apply(out.landform, mesh.landform);
    apply(out.rock, mesh.rock);
    return out;
}

/// The grid coordinate nearest to `x` (in steps), halves rounded up:
/// floor(x + 1/2) commutes with adding an integer, so a point at a half step
/// rounds the same relative to any corner on the grid (std::llround rounds
/// halves away from zero, which differs on either side of the corner).
std::int64_t roundToGrid(double x) { return floorToInt<std::int64_t>(x + 0.5); }

/// Grid coordinates of a position relative to the origin.
std::array<std::int64_t, 3> gridPoint(const glm::vec3& p, double step)
{
    return {roundToGrid(double(p.x) / step), roundToGrid(double(p.y) / step), roundToGrid(double(p.z) / step)};
}

json material(const std::string& name, bool doubleSided)
{
    json m = {{"name", name},
              {"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}, {"metallicFactor", 0.0},
                                        {"roughnessFactor", 0.9}}}};
    if (doubleSided) m["doubleSided"] = true;
    return m;
}

void appendU32(std::string& out, std::uint32_t v)
{
    char bytes[4];
    std::memcpy(bytes, &v, 4); // little-endian, as glTF and this machine
    out.append(bytes, 4);
}

/// The GLB container: header, JSON chunk (padded with spaces), BIN chunk
/// (padded with zeros) when there is one.
std::string assembleGlb(const std::string& text, const std::vector<unsigned char>& bin)
{
    std::string jsonChunk = text;
    jsonChunk.resize(align4(jsonChunk.size()), ' ');
    const std::size_t binLength = align4(bin.size());
    const std::size_t total = 12 + 8 + jsonChunk.size() + (bin.empty() ? 0 : 8 + binLength);
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw Error(ErrorKind::Internal, "compact glTF is larger than a GLB can hold (4 GiB)");
    std::string out;
    out.reserve(total);
    out.append("glTF", 4);
    appendU32(out, 2);
    appendU32(out, std::uint32_t(total));
    appendU32(out, std::uint32_t(jsonChunk.size()));
    out.append("JSON", 4);
    out += jsonChunk;
    if (!bin.empty()) {
        appendU32(out, std::uint32_t(binLength));
        out.append("BIN\0", 4);
        out.append(reinterpret_cast<const char*>(bin.data()), bin.size());
        out.append(binLength - bin.size(), '\0');
    }
    return out;
}

void checkOptions(const CompactGlbOptions& options)
{
    if (!(options.positionStep > 0.0) || !std::isfinite(options.positionStep))
        throw Error(ErrorKind::BadInput,
                    "compact glTF: position step " + std::to_string(options.positionStep) + " m is not positive");
    if (options.normalBits < 2 || options.normalBits > 16)
        throw Error(ErrorKind::BadInput,
                    "compact glTF: normal bits " + std::to_string(options.normalBits) + " is outside 2..16");
}

/// The parts with a primitive, each mesh reordered when asked.
struct UsedParts
{
    std::vector<TriangleMesh> meshes;
    std::vector<const GlbPart*> parts;
};

UsedParts usedParts(const std::vector<GlbPart>& parts, const CompactGlbOptions& options)
{
    UsedParts used;
    for (const GlbPart& part : parts) {
        // glTF accessors cannot be empty: an empty part has no primitive.
        if (part.mesh->indices.empty() || part.mesh->positions.empty()) continue;
        used.meshes.push_back(options.optimizeOrder ? reorder(*part.mesh) : *part.mesh);
        used.parts.push_back(&part);
    }
    return used;
}

/// The position grid shared by all primitives.
struct PositionGrid
{
    double step = 0.0;                  ///< metres
    std::array<std::int64_t, 3> base{}; ///< the lowest grid point (0 without meshes)
};

/// The grid: one offset (the lowest grid point) for all primitives, the
/// step doubled while any axis spans more than 16 bits.
PositionGrid fitPositionGrid(const std::vector<TriangleMesh>& meshes, double positionStep)
{
    PositionGrid grid;
    grid.step = positionStep;
    for (;;) {
        std::array<std::int64_t, 3> lo{}, hi{};
        lo.fill(std::numeric_limits<std::int64_t>::max());
        hi.fill(std::numeric_limits<std::int64_t>::min());
        for (const TriangleMesh& mesh : meshes)
            for (const glm::vec3& p : mesh.positions) {
                const auto g = gridPoint(p, grid.step);
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], g[a]);
                    hi[a] = std::max(hi[a], g[a]);
                }
            }
        bool fits = true;
        for (int a = 0; a < 3; ++a) fits = fits && (meshes.empty() || hi[a] - lo[a] <= POSITION_RANGE);
        if (fits) {
            if (!meshes.empty()) grid.base = lo;
            break;
        }
        grid.step *= 2.0;
    }
    return grid;
}

/// What the primitives add to the document, as they are added.
struct Primitives
{
    Buffers buffers;
    json accessors = json::array(), materials = json::array(), primitives = json::array();
    std::map<std::pair<std::string, bool>, int> materialIndex;
    CompactGlbStats measured;

    std::size_t addAccessor(json accessor)
    {
        accessors.push_back(std::move(accessor));
        return accessors.size() - 1;
    }
};

/// POSITION: 16-bit grid coordinates relative to the grid's base (padded to
/// 8 bytes); measures the largest position error.
std::size_t addPositions(Primitives& out, const TriangleMesh& mesh, const PositionGrid& grid)
{
    const std::size_t n = mesh.positions.size();
    std::vector<std::uint16_t> positions(4 * n, 0);
    std::array<std::uint16_t, 3> lo{0xffff, 0xffff, 0xffff}, hi{0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) {
        const auto g = gridPoint(mesh.positions[i], grid.step);
        for (int a = 0; a < 3; ++a) {
            const auto q = std::uint16_t(g[a] - grid.base[a]);
            positions[4 * i + a] = q;
            lo[a] = std::min(lo[a], q);
            hi[a] = std::max(hi[a], q);
            const double decoded = double(grid.base[a] + q) * grid.step;
            out.measured.maxPositionError =
                std::max(out.measured.maxPositionError, std::abs(decoded - double(mesh.positions[i][a])));
        }
    }
    return out.addAccessor({{"bufferView", out.buffers.add(positions.data(), n, 8, false, "NONE")},
                            {"componentType", GL_UNSIGNED_SHORT},
                            {"count", n},
                            {"type", "VEC3"},
                            {"min", {lo[0], lo[1], lo[2]}},
                            {"max", {hi[0], hi[1], hi[2]}}});
}

/// The largest angle (radians) between the unit normals (4 floats apart)
/// and what a client decodes from `packed`: the filter's inverse, then
/// glTF's normalized dequantization.
double maxDecodedNormalAngle(const std::vector<float>& unit, const std::vector<unsigned char>& packed, std::size_t n,
                             bool wide, double maxAngle)
{
    const std::size_t stride = wide ? 8 : 4;
    std::vector<unsigned char> check = packed;
    meshopt_decodeFilterOct(check.data(), n, stride);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 d;
        for (int a = 0; a < 3; ++a) {
            if (wide) {
                std::int16_t c;
                std::memcpy(&c, check.data() + i * 8 + 2 * a, 2);
                d[a] = std::max(float(c) / 32767.0f, -1.0f);
            } else {
                d[a] = std::max(float(std::int8_t(check[i * 4 + a])) / 127.0f, -1.0f);
            }
        }
        const glm::vec3 v(unit[4 * i], unit[4 * i + 1], unit[4 * i + 2]);
        const double c = std::clamp(double(glm::dot(glm::normalize(d), v)), -1.0, 1.0);
        maxAngle = std::max(maxAngle, dmath::acos(c));
    }
    return maxAngle;
}

/// NORMAL: octahedral, 8 or 16 bits a component (options.normalBits);
/// measures the largest normal angle.
std::size_t addNormals(Primitives& out, const TriangleMesh& mesh, const CompactGlbOptions& options)
{
    const std::size_t n = mesh.positions.size();
    std::vector<float> unit(4 * n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
        glm::vec3 v = mesh.normals[i];
        const float length = glm::length(v);
        v = length > 0.0f && std::isfinite(length) ? v / length : glm::vec3(0.0f, 1.0f, 0.0f);
        for (int a = 0; a < 3; ++a) unit[4 * i + a] = v[a];
    }
    const bool wide = options.normalBits > 8;
    const std::size_t stride = wide ? 8 : 4;
    std::vector<unsigned char> packed(n * stride);
    meshopt_encodeFilterOct(packed.data(), n, stride, options.normalBits, unit.data());
    out.measured.maxNormalAngle = maxDecodedNormalAngle(unit, packed, n, wide, out.measured.maxNormalAngle);
    json accessor = {{"bufferView", out.buffers.add(packed.data(), n, stride, false, "OCTAHEDRAL")},
                     {"componentType", wide ? GL_SHORT : GL_BYTE},
                     {"normalized", true},
                     {"count", n},
                     {"type", "VEC3"}};
    return out.addAccessor(accessor);
}

/// One primitive: its attributes, indices and material (shared by the parts
/// with the same name and sidedness).
void addPrimitive(Primitives& out, const TriangleMesh& mesh, const GlbPart& part, const PositionGrid& grid,
                  const CompactGlbOptions& options)
{
    const std::size_t n = mesh.positions.size();
    json attributes;
    attributes["POSITION"] = addPositions(out, mesh, grid);
    if (mesh.normals.size() == n) attributes["NORMAL"] = addNormals(out, mesh, options);
    // Application-specific float attributes (one per vertex, or none):
    // lossless (no filter).
    auto floats = [&](const auto& values, const char* type, const char* name) {
        if (values.size() != n) return;
        using Value = typename std::decay_t<decltype(values)>::value_type;
        attributes[name] =
            out.addAccessor({{"bufferView", out.buffers.add(values.data(), n, sizeof(Value), false, "NONE")},
                             {"componentType", GL_FLOAT},
                             {"count", n},
                             {"type", type}});
    };
    floats(mesh.surface, "VEC2", SURFACE_ATTRIBUTE);
    floats(mesh.landform, "VEC4", LANDFORM_ATTRIBUTE);
    floats(mesh.rock, "VEC2", ROCK_ATTRIBUTE);

    const bool small = n <= 0xffff;
    const std::size_t indices = out.addAccessor(
        {{"bufferView", out.buffers.add(mesh.indices.data(), mesh.indices.size(), small ? 2 : 4, true, "NONE")},
         {"componentType", small ? GL_UNSIGNED_SHORT : GL_UNSIGNED_INT},
         {"count", mesh.indices.size()},
         {"type", "SCALAR"}});

    const auto [found, added] =
        out.materialIndex.emplace(std::make_pair(part.material, part.doubleSided), int(out.materials.size()));
    if (added) out.materials.push_back(material(part.material, part.doubleSided));
    out.primitives.push_back(
        {{"attributes", attributes}, {"indices", indices}, {"material", found->second}, {"mode", 4}});
}

/// The glTF document: the mesh (when there are primitives) under one node
/// that scales and moves the grid coordinates back to metres.
json document(const Primitives& in, const PositionGrid& grid, const glm::dvec3& origin, const std::string& name)
{
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "Strata"}};
    const glm::dvec3 translation =
        origin + glm::dvec3(double(grid.base[0]), double(grid.base[1]), double(grid.base[2])) * grid.step;
    json node = {{"name", name}};
    if (!in.primitives.empty()) {
        doc["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        doc["accessors"] = in.accessors;
        doc["bufferViews"] = in.buffers.views;
        doc["buffers"] = json::array({{{"byteLength", align4(in.buffers.bin.size())}},
                                      {{"byteLength", align4(in.buffers.fallbackLength)},
                                       {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
        doc["materials"] = in.materials;
        doc["meshes"] = json::array({{{"name", name}, {"primitives", in.primitives}}});
        node["mesh"] = 0;
        node["scale"] = {grid.step, grid.step, grid.step};
    }
    if (translation != glm::dvec3(0.0)) node["translation"] = {translation.x, translation.y, translation.z};
    doc["nodes"] = json::array({node});
    doc["scene"] = 0;
    doc["scenes"] = json::array({{{"nodes", {0}}}});
    return doc;
}

} // namespace

double compactPositionStep(double extent, double unit)
{
    if (!(unit > 0.0) || !std::isfinite(unit) || !(extent >= 0.0) || !std::isfinite(extent))
        throw Error(ErrorKind::BadInput, "compact glTF: the position grid needs a positive unit and extent (unit " +
                                             std::to_string(unit) + " m, extent " + std::to_string(extent) + " m)");
    double step = unit;
    while (extent / step > double(POSITION_RANGE)) step *= 2.0;
    while (extent / (step * 0.5) <= double(POSITION_RANGE) && step > unit * 0x1p-20) step *= 0.5;
    return step;
}

std::string encodeCompactGlb(const std::vector<GlbPart>& parts, const glm::dvec3& origin, const std::string& name,
                             const CompactGlbOptions& options, CompactGlbStats* stats)
{
    checkOptions(options);
    const UsedParts used = usedParts(parts, options);
    const PositionGrid grid = fitPositionGrid(used.meshes, options.positionStep);
    Primitives primitives;
    primitives.measured.positionStep = grid.step;
    for (std::size_t k = 0; k < used.meshes.size(); ++k) {
        addPrimitive(primitives, used.meshes[k], *used.parts[k], grid, options);
    }
    const json doc = document(primitives, grid, origin, name);
    if (stats) *stats = primitives.measured;
    return assembleGlb(doc.dump(), primitives.buffers.bin);
}

} // namespace strata::meshing
