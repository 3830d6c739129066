// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/GltfIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include "FilePlace.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tiny_gltf.h>

#include "GltfMeshoptDecode.h"
#include "MeshReadSupport.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

namespace strata::meshing {

namespace {

// Appends `bytes` to the single buffer, 4-byte aligned as glTF requires, and
// returns the index of a new buffer view over them.
int appendView(tinygltf::Model& model, const void* bytes, std::size_t size, int target)
{
    std::vector<unsigned char>& data = model.buffers[0].data;
    data.resize((data.size() + 3) & ~std::size_t(3), 0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = data.size();
    view.byteLength = size;
    view.target = target;
    const auto* begin = static_cast<const unsigned char*>(bytes);
    data.insert(data.end(), begin, begin + size);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
}

/// Appends a float accessor of `values` (glm::vec2, vec3 or vec4; glTF
/// `type` to match) and returns its index; `withBounds` adds min and max.
template <typename T>
int appendAccessor(tinygltf::Model& model, const std::vector<T>& values, int type, bool withBounds)
{
    tinygltf::Accessor accessor;
    accessor.bufferView = appendView(model, values.data(), values.size() * sizeof(T), TINYGLTF_TARGET_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.count = values.size();
    accessor.type = type;
    if (withBounds) { // required by the spec for POSITION
        T lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (const T& v : values) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        for (int c = 0; c < T::length(); ++c) {
            accessor.minValues.push_back(lo[c]);
            accessor.maxValues.push_back(hi[c]);
        }
    }
    model.accessors.push_back(accessor);
    return int(model.accessors.size() - 1);
}

// Copies accessor `index` out of the model as values of type T (one per
// element), honouring byte strides. Every index, offset, stride and count is
// checked against the buffer view and the buffer, so an accessor that
// overruns its view is an error, not a read of the neighbouring bytes.
template <typename T>
std::vector<T> readAccessor(const tinygltf::Model& model, int index, int componentType, int type,
                            const std::string& what, const std::string& name)
{
    auto fail = [&](const std::string& why) { detail::failRead(name, 0, what + " accessor " + why); };
    if (index < 0 || std::size_t(index) >= model.accessors.size()) fail("is missing");
    const tinygltf::Accessor& accessor = model.accessors[std::size_t(index)];
    if (accessor.componentType != componentType || accessor.type != type) fail("has an unsupported layout");
    if (accessor.sparse.isSparse) fail("is sparse (not supported)");
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= model.bufferViews.size()) {
        fail("has no valid buffer view");
    }
    const tinygltf::BufferView& view = model.bufferViews[std::size_t(accessor.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= model.buffers.size()) fail("has a buffer view without a buffer");
    const std::vector<unsigned char>& data = model.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
        fail("has a buffer view (offset " + std::to_string(view.byteOffset) + ", length " +
             std::to_string(view.byteLength) + ") that runs past its buffer (" + std::to_string(data.size()) +
             " bytes)");
    }
    const std::size_t stride = view.byteStride ? view.byteStride : sizeof(T);
    if (stride < sizeof(T)) fail("has a byte stride of " + std::to_string(stride) + ", smaller than an element");
    const std::size_t count = accessor.count;
    // The last element must end inside the view: offset + (count-1)*stride + size <= length.
    const std::size_t length = view.byteLength;
    if (count > 0 && (accessor.byteOffset > length || (count - 1) > (length - accessor.byteOffset) / stride ||
                      accessor.byteOffset + (count - 1) * stride + sizeof(T) > length)) {
        fail("(" + std::to_string(count) + " elements from offset " + std::to_string(accessor.byteOffset) +
             ") runs past its buffer view (" + std::to_string(length) + " bytes)");
    }
    const unsigned char* start = data.data() + view.byteOffset + accessor.byteOffset;
    std::vector<T> values(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::memcpy(&values[i], start + i * stride, sizeof(T));
    }
    return values;
}

/// Accessor `index` as float vectors T (glm::vec2, vec3 or vec4, glTF
/// `type` to match): FLOAT, or (KHR_mesh_quantization, and any type for an
/// application-specific attribute) BYTE, UNSIGNED_BYTE, SHORT or
/// UNSIGNED_SHORT, normalized (glTF's dequantization: c / (2^(n-1) − 1),
/// at least −1, for signed types, c / (2^n − 1) for unsigned) or not.
/// `quantized` (may be null) says whether it was an integer type.
template <typename T>
std::vector<T> readFloatAccessor(const tinygltf::Model& model, int index, int type, const std::string& what,
                                 const std::string& name, bool* quantized = nullptr)
{
    if (index < 0 || std::size_t(index) >= model.accessors.size()) detail::failRead(name, 0, what + " accessor is missing");
    const tinygltf::Accessor& accessor = model.accessors[std::size_t(index)];
    if (quantized) *quantized = accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
    constexpr int N = T::length();
    auto convert = [&](auto zero, double scale, double lowest) {
        using C = decltype(zero);
        // The element as N components of C (glm vectors of integers have the same layout).
        using Element = glm::vec<N, C, glm::defaultp>;
        const std::vector<Element> raw = readAccessor<Element>(model, index, accessor.componentType, type, what, name);
        std::vector<T> values(raw.size());
        const bool normalized = accessor.normalized;
        for (std::size_t i = 0; i < raw.size(); ++i)
            for (int c = 0; c < N; ++c)
                values[i][c] = normalized ? float(std::max(double(raw[i][c]) / scale, lowest)) : float(raw[i][c]);
        return values;
    };
    switch (accessor.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return convert(std::int8_t(0), 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return convert(std::uint8_t(0), 255.0, 0.0);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return convert(std::int16_t(0), 32767.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return convert(std::uint16_t(0), 65535.0, 0.0);
    default: return readAccessor<T>(model, index, TINYGLTF_COMPONENT_TYPE_FLOAT, type, what, name);
    }
}

// Image data is never needed: do not decode it.
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*)
{
    return true;
}

// External files: only regular files, read with our checks; none at all for
// bytes parsed from memory (user_data == nullptr).
bool externalExists(const std::string& path, void* allow)
{
    std::error_code ec;
    return allow && std::filesystem::is_regular_file(path, ec);
}

std::string externalExpand(const std::string& path, void*)
{
    return path;
}

bool externalRead(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* allow)
{
    if (!allow) {
        if (err) *err += "external file '" + path + "' is not allowed here\n";
        return false;
    }
    try {
        const std::string bytes = detail::readWholeFile(path);
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const std::exception& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}

bool externalWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*)
{
    if (err) *err += "writing is not allowed while reading\n";
    return false;
}

void configureLoader(tinygltf::TinyGLTF& loader, bool allowExternalFiles)
{
    loader.SetImageLoader(skipImage, nullptr);
    static int allow = 1;
    loader.SetFsCallbacks({externalExists, externalExpand, externalRead, externalWrite,
                           allowExternalFiles ? static_cast<void*>(&allow) : nullptr});
}

template <typename T>
void checkFinite(const std::vector<T>& values, const std::string& what, const std::string& name)
{
    for (std::size_t i = 0; i < values.size(); ++i) {
        for (int c = 0; c < T::length(); ++c) {
            if (!std::isfinite(values[i][c])) {
                detail::failRead(name, 0, what + " " + std::to_string(i) + " is not finite");
            }
        }
    }
}

/// The optional per-vertex float attribute `key` of `primitive` (glTF
/// `type`), checked finite and one per position; empty when absent.
template <typename T>
std::vector<T> readVertexAttribute(const tinygltf::Model& model, const tinygltf::Primitive& primitive,
                                   const std::string& key, int type, std::size_t vertexCount, const std::string& name)
{
    const auto found = primitive.attributes.find(key);
    if (found == primitive.attributes.end()) return {};
    bool quantized = false;
    std::vector<T> values = readFloatAccessor<T>(model, found->second, type, key, name, &quantized);
    checkFinite(values, key, name);
    // Quantized normals (KHR_mesh_quantization) are unit only to their precision.
    if (quantized && key == "NORMAL") {
        for (T& v : values) {
            const float length = glm::length(v);
            if (length > 0.0f) v /= length;
        }
    }
    if (values.size() != vertexCount) {
        detail::failRead(name, 0, key + " has " + std::to_string(values.size()) + " elements, POSITION " +
                                      std::to_string(vertexCount));
    }
    return values;
}

/// Appends a primitive's optional attribute to the mesh's while every
/// primitive so far had it (`all`); clears it for good once one lacks it.
template <typename T>
void appendWhileAll(bool& all, std::vector<T>& mesh, const std::vector<T>& part, std::size_t partVertices)
{
    all = all && part.size() == partVertices;
    if (all) mesh.insert(mesh.end(), part.begin(), part.end());
    else mesh.clear();
}

/// One triangle primitive, read and checked.
TriangleMesh primitiveMesh(const tinygltf::Model& model, const tinygltf::Primitive& primitive, const std::string& name)
{
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        throw Error(ErrorKind::BadInput, "'" + name + "': only triangle primitives are supported", {.file = name});
    }

    TriangleMesh mesh;
    const auto position = primitive.attributes.find("POSITION");
    mesh.positions = readFloatAccessor<glm::vec3>(model, position == primitive.attributes.end() ? -1 : position->second,
                                                  TINYGLTF_TYPE_VEC3, "POSITION", name);
    checkFinite(mesh.positions, "POSITION", name);
    if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max()) {
        detail::failRead(name, 0, "too many vertices");
    }
    const std::size_t n = mesh.positions.size();
    mesh.normals = readVertexAttribute<glm::vec3>(model, primitive, "NORMAL", TINYGLTF_TYPE_VEC3, n, name);
    mesh.surface = readVertexAttribute<glm::vec2>(model, primitive, SURFACE_ATTRIBUTE, TINYGLTF_TYPE_VEC2, n, name);
    mesh.landform = readVertexAttribute<glm::vec4>(model, primitive, LANDFORM_ATTRIBUTE, TINYGLTF_TYPE_VEC4, n, name);
    mesh.rock = readVertexAttribute<glm::vec2>(model, primitive, ROCK_ATTRIBUTE, TINYGLTF_TYPE_VEC2, n, name);
    if (primitive.indices >= 0) {
        if (std::size_t(primitive.indices) >= model.accessors.size()) detail::failRead(name, 0, "index accessor is missing");
        const int componentType = model.accessors[std::size_t(primitive.indices)].componentType;
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            for (std::uint16_t i : readAccessor<std::uint16_t>(model, primitive.indices, componentType,
                                                               TINYGLTF_TYPE_SCALAR, "index", name)) {
                mesh.indices.push_back(i);
            }
        } else if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            for (std::uint8_t i : readAccessor<std::uint8_t>(model, primitive.indices, componentType,
                                                             TINYGLTF_TYPE_SCALAR, "index", name)) {
                mesh.indices.push_back(i);
            }
        } else {
            mesh.indices = readAccessor<std::uint32_t>(model, primitive.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                                       TINYGLTF_TYPE_SCALAR, "index", name);
        }
    } else {
        for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
    }
    if (mesh.indices.size() % 3 != 0) {
        detail::failRead(name, 0, "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
    }
    for (std::size_t k = 0; k < mesh.indices.size(); ++k) {
        if (mesh.indices[k] >= mesh.positions.size()) {
            detail::failRead(name, 0, "triangle " + std::to_string(k / 3) + ": index " + std::to_string(mesh.indices[k]) +
                                          " is out of range (" + std::to_string(mesh.positions.size()) + " vertices)");
        }
    }
    return mesh;
}

/// Every triangle primitive of the first mesh, appended in order (a
/// primitive without normals, surface, landform or rock attributes drops them
/// from the whole mesh).
TriangleMesh meshFromModel(const tinygltf::Model& model, const std::string& name)
{
    if (model.meshes.empty() || model.meshes[0].primitives.empty()) {
        throw Error(ErrorKind::BadInput, "'" + name + "' holds no mesh", {.file = name});
    }
    TriangleMesh mesh;
    bool normals = true, surface = true, landform = true, rock = true;
    for (const tinygltf::Primitive& primitive : model.meshes[0].primitives) {
        TriangleMesh part = primitiveMesh(model, primitive, name);
        if (mesh.positions.size() + part.positions.size() > std::numeric_limits<std::uint32_t>::max()) {
            detail::failRead(name, 0, "too many vertices");
        }
        const auto base = std::uint32_t(mesh.positions.size());
        for (std::uint32_t i : part.indices) mesh.indices.push_back(base + i);
        mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
        appendWhileAll(normals, mesh.normals, part.normals, part.positions.size());
        appendWhileAll(surface, mesh.surface, part.surface, part.positions.size());
        appendWhileAll(landform, mesh.landform, part.landform, part.positions.size());
        appendWhileAll(rock, mesh.rock, part.rock, part.positions.size());
    }
    for (const tinygltf::Node& node : model.nodes) {
        if (node.mesh != 0) continue;
        if (node.translation.size() == 3) {
            mesh.origin = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
            if (!std::isfinite(mesh.origin.x) || !std::isfinite(mesh.origin.y) || !std::isfinite(mesh.origin.z)) {
                detail::failRead(name, 0, "the mesh node's translation is not finite");
            }
        }
        // A scale dequantizes KHR_mesh_quantization positions (compact tiles:
        // integer grid coordinates times the grid step).
        if (node.scale.size() == 3) {
            const glm::vec3 scale(float(node.scale[0]), float(node.scale[1]), float(node.scale[2]));
            if (!std::isfinite(scale.x) || !std::isfinite(scale.y) || !std::isfinite(scale.z)) {
                detail::failRead(name, 0, "the mesh node's scale is not finite");
            }
            for (glm::vec3& p : mesh.positions) p *= scale;
            if (!mesh.normals.empty() && scale != glm::vec3(1.0f)) {
                // Normals transform by the inverse transpose: 1/scale, renormalized.
                for (glm::vec3& n : mesh.normals) {
                    n /= scale;
                    const float length = glm::length(n);
                    if (length > 0.0f && std::isfinite(length)) n /= length;
                }
            }
            if (scale.x * scale.y * scale.z < 0.0f) {
                for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
            }
        }
        break;
    }
    return mesh;
}

std::string oneLine(std::string text)
{
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

} // namespace

std::string encodeGlb(const std::vector<GlbPart>& parts, const glm::dvec3& origin, const std::string& name,
                      bool compactIndices)
{
    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "Strata";
    model.buffers.resize(1);

    tinygltf::Node node;
    node.name = name;
    if (origin != glm::dvec3(0.0)) node.translation = {origin.x, origin.y, origin.z};
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;

    tinygltf::Mesh gltfMesh;
    gltfMesh.name = name;
    std::map<std::pair<std::string, bool>, int> materials;
    for (const GlbPart& part : parts) {
        const TriangleMesh& mesh = *part.mesh;
        // glTF accessors cannot be empty: an empty part has no primitive.
        if (mesh.indices.empty() || mesh.positions.empty()) continue;
        tinygltf::Primitive primitive;
        primitive.mode = TINYGLTF_MODE_TRIANGLES;
        const std::size_t n = mesh.positions.size();
        primitive.attributes["POSITION"] = appendAccessor(model, mesh.positions, TINYGLTF_TYPE_VEC3, true);
        if (mesh.normals.size() == n) {
            primitive.attributes["NORMAL"] = appendAccessor(model, mesh.normals, TINYGLTF_TYPE_VEC3, false);
        }
        // Application-specific attributes: glTF requires a leading underscore.
        if (mesh.surface.size() == n) {
            primitive.attributes[SURFACE_ATTRIBUTE] = appendAccessor(model, mesh.surface, TINYGLTF_TYPE_VEC2, false);
        }
        if (mesh.landform.size() == n) {
            primitive.attributes[LANDFORM_ATTRIBUTE] = appendAccessor(model, mesh.landform, TINYGLTF_TYPE_VEC4, false);
        }
        if (mesh.rock.size() == n) {
            primitive.attributes[ROCK_ATTRIBUTE] = appendAccessor(model, mesh.rock, TINYGLTF_TYPE_VEC2, false);
        }
        tinygltf::Accessor indices;
        if (compactIndices && mesh.positions.size() <= 0xffff) {
            const std::vector<std::uint16_t> small(mesh.indices.begin(), mesh.indices.end());
            indices.bufferView = appendView(model, small.data(), small.size() * sizeof(std::uint16_t),
                                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
        } else {
            indices.bufferView = appendView(model, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                                            TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
        }
        indices.count = mesh.indices.size();
        indices.type = TINYGLTF_TYPE_SCALAR;
        model.accessors.push_back(indices);
        primitive.indices = int(model.accessors.size() - 1);

        // A neutral rough dielectric instead of glTF's default (metallic 1).
        const auto [found, added] = materials.emplace(std::make_pair(part.material, part.doubleSided),
                                                      int(model.materials.size()));
        if (added) {
            tinygltf::Material material;
            material.name = part.material;
            material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
            material.pbrMetallicRoughness.metallicFactor = 0.0;
            material.pbrMetallicRoughness.roughnessFactor = 0.9;
            material.doubleSided = part.doubleSided;
            model.materials.push_back(material);
        }
        primitive.material = found->second;
        gltfMesh.primitives.push_back(primitive);
    }
    if (gltfMesh.primitives.empty()) {
        model.buffers.clear();
    } else {
        model.meshes.push_back(gltfMesh);
        node.mesh = 0;
    }
    model.nodes.push_back(node);

    // Serialised in memory: the caller writes the bytes with checked writes
    // (tinygltf's file writer does not report a failed stream).
    std::ostringstream bytes;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, bytes, /*prettyPrint*/ false, /*writeBinary*/ true) || !bytes) {
        throw Error(ErrorKind::Internal, "cannot encode glTF mesh '" + name + "': tinygltf failed");
    }
    return std::move(bytes).str();
}

void writeGlb(const TriangleMesh& mesh, const std::filesystem::path& path, const GlbOptions& options)
{
    std::string name = options.name.empty() ? path.stem().string() : options.name;
    if (name.empty()) name = "terrain";
    writeFileAtomically(path, encodeGlb({GlbPart{&mesh}}, mesh.origin, name, /*compactIndices*/ false));
}

namespace {

/// Runs one tinygltf load (`load(model, error, warning)`) and turns any
/// failure, reported or thrown, into one BadInput error naming the file.
/// `meshopt` (may be null): the compressed views of an
/// EXT_meshopt_compression file, decoded into buffer 1 after parsing.
template <typename LoadFn>
TriangleMesh loadModel(const std::string& name, bool allowExternalFiles, LoadFn&& load,
                       const detail::MeshoptGlb* meshopt = nullptr)
{
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    configureLoader(loader, allowExternalFiles);
    std::string error, warning;
    bool ok = false;
    try {
        ok = load(loader, model, error, warning);
    } catch (const std::exception& e) {
        ok = false;
        error = e.what();
    }
    if (!ok) {
        detail::failRead(name, 0, "cannot read glTF: " + (error.empty() ? std::string("unknown error") : oneLine(error)));
    }
    if (meshopt) {
        if (model.buffers.size() != 1) detail::failRead(name, 0, "EXT_meshopt_compression: expected one buffer after rewriting");
        tinygltf::Buffer decoded;
        detail::decodeMeshoptViews(*meshopt, model.buffers[0].data, decoded.data, name);
        model.buffers.push_back(std::move(decoded));
    }
    return meshFromModel(model, name);
}

} // namespace

TriangleMesh readGltf(const std::filesystem::path& path)
{
    const std::string name = path.string();
    if (path.extension() == ".glb") return parseGlb(detail::readWholeFile(path), name);
    const std::string text = detail::readWholeFile(path);
    return loadModel(name, /*allowExternalFiles*/ true,
                     [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& error, std::string& warning) {
                         return loader.LoadASCIIFromString(&model, &error, &warning, text.data(),
                                                           unsigned(text.size()), path.parent_path().string());
                     });
}

namespace {

std::uint32_t readU32(std::string_view bytes, std::size_t at)
{
    std::uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4); // little-endian, as glTF and this machine
    return value;
}

/// The GLB container (a 12-byte header, then chunks of a length, a type and
/// the bytes) checked before tinygltf parses it: tinygltf copies a BIN chunk
/// by its stated length without comparing it with the bytes left (a heap
/// overflow found by fuzz_glb).
void checkGlbContainer(std::string_view bytes, const std::string& name)
{
    auto fail = [&](const std::string& why) { detail::failRead(name, 0, "not a valid GLB file: " + why); };
    if (bytes.size() < 20) fail("it has " + std::to_string(bytes.size()) + " bytes, less than a header and one chunk");
    if (bytes.substr(0, 4) != "glTF") fail("it does not start with 'glTF'");
    if (readU32(bytes, 4) != 2) fail("version " + std::to_string(readU32(bytes, 4)) + ", not 2");
    if (readU32(bytes, 8) != bytes.size()) {
        fail("its header says " + std::to_string(readU32(bytes, 8)) + " bytes, the file has " +
             std::to_string(bytes.size()));
    }
    std::size_t at = 12;
    for (int chunk = 0; at < bytes.size(); ++chunk) {
        if (bytes.size() - at < 8) fail("chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) + " has no room for its header");
        const std::uint64_t length = readU32(bytes, at);
        const std::uint32_t type = readU32(bytes, at + 4);
        if (chunk == 0 && type != 0x4E4F534Au) fail("its first chunk is not JSON");
        if (length > bytes.size() - at - 8) {
            fail("chunk " + std::to_string(chunk) + " at byte " + std::to_string(at) + " claims " +
                 std::to_string(length) + " bytes, the file has " + std::to_string(bytes.size() - at - 8) + " left");
        }
        at += 8 + length;
    }
}

} // namespace

TriangleMesh parseGlb(std::string_view bytes, const std::string& name)
{
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) detail::failRead(name, 0, "file too large for glTF");
    checkGlbContainer(bytes, name);
    // EXT_meshopt_compression (compact tiles): tinygltf does not know it, so
    // the JSON is rewritten for it first and the views decoded after.
    std::optional<detail::MeshoptGlb> meshopt;
    if (detail::usesMeshoptCompression(bytes)) {
        meshopt = detail::decodeMeshoptGlb(bytes, name);
        checkGlbContainer(meshopt->glb, name);
        bytes = meshopt->glb;
    }
    return loadModel(
        name, /*allowExternalFiles*/ false,
        [&](tinygltf::TinyGLTF& loader, tinygltf::Model& model, std::string& error, std::string& warning) {
            return loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes.data()),
                                               unsigned(bytes.size()), "");
        },
        meshopt ? &*meshopt : nullptr);
}

} // namespace strata::meshing
