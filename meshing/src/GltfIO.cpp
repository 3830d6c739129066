#include <strata/meshing/GltfIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include "FilePlace.h"

#include <glm/common.hpp>
#include <tiny_gltf.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <sstream>
#include <limits>

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

int appendVec3Accessor(tinygltf::Model& model, const std::vector<glm::vec3>& values, bool withBounds)
{
    tinygltf::Accessor accessor;
    accessor.bufferView = appendView(model, values.data(), values.size() * sizeof(glm::vec3),
                                     TINYGLTF_TARGET_ARRAY_BUFFER);
    accessor.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    accessor.count = values.size();
    accessor.type = TINYGLTF_TYPE_VEC3;
    if (withBounds) { // required by the spec for POSITION
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        for (const glm::vec3& v : values) {
            lo = glm::min(lo, v);
            hi = glm::max(hi, v);
        }
        accessor.minValues = {lo.x, lo.y, lo.z};
        accessor.maxValues = {hi.x, hi.y, hi.z};
    }
    model.accessors.push_back(accessor);
    return int(model.accessors.size() - 1);
}

// Copies accessor `index` out of the model as `components` values of type T
// per element, honouring byte strides. Throws on a layout it does not expect.
template <typename T>
std::vector<T> readAccessor(const tinygltf::Model& model, int index, int componentType, int type,
                            const std::string& what, const std::filesystem::path& path)
{
    if (index < 0 || index >= int(model.accessors.size())) {
        throw Error("'" + path.string() + "': " + what + " accessor is missing");
    }
    const tinygltf::Accessor& accessor = model.accessors[index];
    if (accessor.componentType != componentType || accessor.type != type || accessor.bufferView < 0) {
        throw Error("'" + path.string() + "': " + what + " accessor has an unsupported layout");
    }
    const tinygltf::BufferView& view = model.bufferViews[accessor.bufferView];
    const std::vector<unsigned char>& data = model.buffers[view.buffer].data;
    const std::size_t stride = view.byteStride ? view.byteStride : sizeof(T);
    const std::size_t start = view.byteOffset + accessor.byteOffset;
    if (accessor.count > 0 && start + stride * (accessor.count - 1) + sizeof(T) > data.size()) {
        throw Error("'" + path.string() + "': " + what + " accessor runs past its buffer");
    }
    std::vector<T> values(accessor.count);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        std::memcpy(&values[i], data.data() + start + i * stride, sizeof(T));
    }
    return values;
}

// Serialises `model` as binary glTF in memory, then writes it atomically,
// checking the stream (tinygltf's file writer does not report failed writes).
void writeModel(const tinygltf::Model& model, const std::filesystem::path& path)
{
    std::ostringstream bytes;
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToStream(&model, bytes, /*prettyPrint*/ false, /*writeBinary*/ true)) {
        throw Error(ErrorKind::Internal, "cannot encode glTF file '" + path.string() + "'", detail::filePlace(path));
    }
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        std::ofstream out(temporary, std::ios::binary);
        const std::string data = std::move(bytes).str();
        out.write(data.data(), std::streamsize(data.size()));
        out.close();
        if (!out) {
            throw Error(ErrorKind::Io, "cannot write glTF file '" + path.string() + "'", detail::filePlace(path));
        }
    });
}

} // namespace

void writeGlb(const TriangleMesh& mesh, const std::filesystem::path& path, const GlbOptions& options)
{
    std::string name = options.name.empty() ? path.stem().string() : options.name;
    if (name.empty()) name = "terrain";

    tinygltf::Model model;
    model.asset.version = "2.0";
    model.asset.generator = "Strata";
    model.buffers.resize(1);

    tinygltf::Node node;
    node.name = name;
    if (mesh.origin != glm::dvec3(0.0)) {
        node.translation = {mesh.origin.x, mesh.origin.y, mesh.origin.z};
    }
    tinygltf::Scene scene;
    scene.nodes.push_back(0);
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    if (mesh.indices.empty() || mesh.positions.empty()) {
        // glTF accessors cannot be empty: an empty mesh is a node without one.
        model.buffers.clear();
        model.nodes.push_back(node);
        return writeModel(model, path);
    }

    tinygltf::Primitive primitive;
    primitive.mode = TINYGLTF_MODE_TRIANGLES;
    primitive.attributes["POSITION"] = appendVec3Accessor(model, mesh.positions, true);
    if (!mesh.normals.empty()) {
        primitive.attributes["NORMAL"] = appendVec3Accessor(model, mesh.normals, false);
    }
    tinygltf::Accessor indices;
    indices.bufferView = appendView(model, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                                    TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    indices.count = mesh.indices.size();
    indices.type = TINYGLTF_TYPE_SCALAR;
    model.accessors.push_back(indices);
    primitive.indices = int(model.accessors.size() - 1);

    // A neutral rough dielectric instead of glTF's default (metallic 1).
    tinygltf::Material material;
    material.name = "strata-neutral";
    material.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
    material.pbrMetallicRoughness.metallicFactor = 0.0;
    material.pbrMetallicRoughness.roughnessFactor = 0.9;
    model.materials.push_back(material);
    primitive.material = 0;

    tinygltf::Mesh gltfMesh;
    gltfMesh.name = name;
    gltfMesh.primitives.push_back(primitive);
    model.meshes.push_back(gltfMesh);

    node.mesh = 0;
    model.nodes.push_back(node);

    writeModel(model, path);
}

TriangleMesh readGltf(const std::filesystem::path& path)
{
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    const bool binary = path.extension() == ".glb";
    const bool ok = binary ? loader.LoadBinaryFromFile(&model, &error, &warning, path.string())
                           : loader.LoadASCIIFromFile(&model, &error, &warning, path.string());
    if (!ok) {
        throw Error("cannot read glTF file '" + path.string() + "': " + (error.empty() ? "unknown error" : error));
    }
    if (model.meshes.empty() || model.meshes[0].primitives.empty()) {
        throw Error("'" + path.string() + "' holds no mesh");
    }
    const tinygltf::Primitive& primitive = model.meshes[0].primitives[0];
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1) {
        throw Error("'" + path.string() + "': only triangle primitives are supported");
    }

    TriangleMesh mesh;
    const auto position = primitive.attributes.find("POSITION");
    mesh.positions = readAccessor<glm::vec3>(model, position == primitive.attributes.end() ? -1 : position->second,
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, "POSITION", path);
    const auto normal = primitive.attributes.find("NORMAL");
    if (normal != primitive.attributes.end()) {
        mesh.normals = readAccessor<glm::vec3>(model, normal->second, TINYGLTF_COMPONENT_TYPE_FLOAT,
                                               TINYGLTF_TYPE_VEC3, "NORMAL", path);
    }
    if (primitive.indices >= 0) {
        const int componentType = model.accessors.at(primitive.indices).componentType;
        if (componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            for (std::uint16_t i : readAccessor<std::uint16_t>(model, primitive.indices, componentType,
                                                               TINYGLTF_TYPE_SCALAR, "index", path)) {
                mesh.indices.push_back(i);
            }
        } else {
            mesh.indices = readAccessor<std::uint32_t>(model, primitive.indices, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                                       TINYGLTF_TYPE_SCALAR, "index", path);
        }
    } else {
        for (std::uint32_t i = 0; i < mesh.positions.size(); ++i) mesh.indices.push_back(i);
    }
    for (std::uint32_t i : mesh.indices) {
        if (i >= mesh.positions.size()) {
            throw Error("'" + path.string() + "': index " + std::to_string(i) + " is out of range");
        }
    }
    for (const tinygltf::Node& node : model.nodes) {
        if (node.mesh == 0 && node.translation.size() == 3) {
            mesh.origin = glm::dvec3(node.translation[0], node.translation[1], node.translation[2]);
            break;
        }
    }
    return mesh;
}

} // namespace strata::meshing
