// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "GltfMeshoptDecode.h"

#include "MeshReadSupport.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

namespace strata::meshing::detail {

namespace {

using nlohmann::json;

constexpr const char* EXTENSION = "EXT_meshopt_compression";

std::uint32_t readU32(std::string_view bytes, std::size_t at)
{
    std::uint32_t value;
    std::memcpy(&value, bytes.data() + at, 4); // little-endian, as glTF and this machine
    return value;
}

void appendU32(std::string& out, std::uint32_t v)
{
    char bytes[4];
    std::memcpy(bytes, &v, 4);
    out.append(bytes, 4);
}

std::size_t align4(std::size_t n) { return (n + 3) & ~std::size_t(3); }

/// A non-negative integer member of `object`, or `fallback` when absent.
std::uint64_t unsignedMember(const json& object, const char* key, const std::string& where, const std::string& name,
                             std::optional<std::uint64_t> fallback = std::nullopt)
{
    const auto found = object.find(key);
    if (found == object.end()) {
        if (fallback) return *fallback;
        failRead(name, 0, where + " has no '" + key + "'");
    }
    if (!found->is_number_unsigned()) failRead(name, 0, where + "'s '" + key + "' is not a non-negative integer");
    return found->get<std::uint64_t>();
}

} // namespace

bool usesMeshoptCompression(std::string_view glb)
{
    if (glb.size() < 20) return false;
    const std::size_t length = readU32(glb, 12);
    return glb.substr(20, std::min<std::size_t>(length, glb.size() - 20)).find(EXTENSION) != std::string_view::npos;
}

std::string decodeMeshoptGlb(std::string_view glb, const std::string& name)
{
    // The container is checked (checkGlbContainer): header, JSON, then BIN.
    const std::size_t jsonLength = readU32(glb, 12);
    json doc = json::parse(glb.substr(20, jsonLength), nullptr, /*allow_exceptions*/ false);
    if (doc.is_discarded() || !doc.is_object()) failRead(name, 0, "cannot read glTF: its JSON chunk does not parse");
    std::string_view bin;
    const std::size_t binAt = 20 + jsonLength;
    if (glb.size() - binAt >= 8 && readU32(glb, binAt + 4) == 0x004E4942u) bin = glb.substr(binAt + 8, readU32(glb, binAt));

    json& buffers = doc["buffers"];
    json& views = doc["bufferViews"];
    if (!buffers.is_array() || !views.is_array()) failRead(name, 0, "EXT_meshopt_compression: no buffers or buffer views");
    // Buffer 0 is the binary chunk: it must be there, without a uri.
    if (buffers.empty() || !buffers[0].is_object() || buffers[0].contains("uri") || bin.empty())
        failRead(name, 0, "EXT_meshopt_compression: buffer 0 is not the GLB's binary chunk");
    std::vector<bool> fallback(buffers.size(), false);
    for (std::size_t b = 0; b < buffers.size(); ++b) {
        const json& buffer = buffers[b];
        fallback[b] = buffer.is_object() && buffer.contains("extensions") && buffer["extensions"].is_object() &&
                      buffer["extensions"].contains(EXTENSION) && buffer["extensions"][EXTENSION].is_object() &&
                      buffer["extensions"][EXTENSION].value("fallback", false);
        if (b > 0 && !fallback[b]) failRead(name, 0, "EXT_meshopt_compression: buffer " + std::to_string(b) +
                                                         " is neither the binary chunk nor a fallback buffer (not supported)");
    }
    if (fallback[0]) failRead(name, 0, "EXT_meshopt_compression: buffer 0 is a fallback buffer");

    std::string out(bin); // the new binary chunk: the old one, then every decoded view
    for (std::size_t v = 0; v < views.size(); ++v) {
        json& view = views[v];
        const std::string where = "buffer view " + std::to_string(v);
        if (!view.is_object()) failRead(name, 0, where + " is not an object");
        const bool compressed = view.contains("extensions") && view["extensions"].is_object() &&
                                view["extensions"].contains(EXTENSION);
        const std::uint64_t buffer = unsignedMember(view, "buffer", where, name);
        if (!compressed) {
            if (buffer != 0) failRead(name, 0, where + " reads fallback buffer " + std::to_string(buffer) + " uncompressed");
            continue;
        }
        const json& ext = view["extensions"][EXTENSION];
        const std::string extWhere = where + "'s " + EXTENSION;
        if (!ext.is_object()) failRead(name, 0, extWhere + " is not an object");
        if (unsignedMember(ext, "buffer", extWhere, name) != 0)
            failRead(name, 0, extWhere + " reads a buffer other than the binary chunk (not supported)");
        const std::uint64_t offset = unsignedMember(ext, "byteOffset", extWhere, name, 0);
        const std::uint64_t length = unsignedMember(ext, "byteLength", extWhere, name);
        const std::uint64_t stride = unsignedMember(ext, "byteStride", extWhere, name);
        const std::uint64_t count = unsignedMember(ext, "count", extWhere, name);
        const std::string mode = ext.value("mode", std::string());
        const std::string filter = ext.value("filter", std::string("NONE"));
        if (offset > bin.size() || length > bin.size() - offset)
            failRead(name, 0, extWhere + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
                                  ") runs past the binary chunk (" + std::to_string(bin.size()) + " bytes)");
        const std::uint64_t viewLength = unsignedMember(view, "byteLength", where, name);
        if (stride == 0 || count > viewLength / stride)
            failRead(name, 0, extWhere + ": " + std::to_string(count) + " elements of " + std::to_string(stride) +
                                  " bytes do not fit the view's " + std::to_string(viewLength) + " bytes");
        if (viewLength > std::numeric_limits<std::uint32_t>::max())
            failRead(name, 0, where + " is larger than a GLB can hold");
        // No codec inflates more than 64 times (a vertex byte column costs at
        // least 2 bits per 16 vertices): a larger claim is a broken file, not
        // a reason to allocate gigabytes.
        if (count * stride > 1024 * length + 4096)
            failRead(name, 0, extWhere + ": " + std::to_string(count * stride) + " decoded bytes from " +
                                  std::to_string(length) + " compressed is more than any codec yields");

        std::vector<unsigned char> decoded(std::size_t(count * stride));
        const auto* source = reinterpret_cast<const unsigned char*>(bin.data() + offset);
        int rc = 0;
        if (mode == "ATTRIBUTES") {
            if (stride % 4 != 0 || stride > 256)
                failRead(name, 0, extWhere + ": byteStride " + std::to_string(stride) + " is not a multiple of 4 up to 256");
            rc = meshopt_decodeVertexBuffer(decoded.data(), count, stride, source, length);
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4)
                failRead(name, 0, extWhere + ": byteStride " + std::to_string(stride) + " is not 2 or 4 for indices");
            if (mode == "TRIANGLES" && count % 3 != 0)
                failRead(name, 0, extWhere + ": TRIANGLES count " + std::to_string(count) + " is not a multiple of 3");
            rc = mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(decoded.data(), count, stride, source, length)
                                     : meshopt_decodeIndexSequence(decoded.data(), count, stride, source, length);
        } else {
            failRead(name, 0, extWhere + ": mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
        }
        if (rc != 0) failRead(name, 0, extWhere + ": meshoptimizer cannot decode it (error " + std::to_string(rc) + ")");
        if (filter != "NONE" && mode != "ATTRIBUTES") failRead(name, 0, extWhere + ": a filter needs mode ATTRIBUTES");
        if (filter == "OCTAHEDRAL") {
            if (stride != 4 && stride != 8) failRead(name, 0, extWhere + ": OCTAHEDRAL needs byteStride 4 or 8");
            meshopt_decodeFilterOct(decoded.data(), count, stride);
        } else if (filter == "QUATERNION") {
            if (stride != 8) failRead(name, 0, extWhere + ": QUATERNION needs byteStride 8");
            meshopt_decodeFilterQuat(decoded.data(), count, stride);
        } else if (filter == "EXPONENTIAL") {
            meshopt_decodeFilterExp(decoded.data(), count, stride);
        } else if (filter != "NONE") {
            failRead(name, 0, extWhere + ": filter '" + filter + "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
        }

        out.resize(align4(out.size()), '\0');
        const std::size_t at = out.size();
        out.append(reinterpret_cast<const char*>(decoded.data()), decoded.size());
        out.resize(at + std::size_t(viewLength), '\0'); // the view's full length, as declared
        if (out.size() > std::numeric_limits<std::uint32_t>::max()) failRead(name, 0, "decoded data exceed 4 GiB");
        view["buffer"] = 0;
        view["byteOffset"] = at;
        view["extensions"].erase(EXTENSION);
        if (view["extensions"].empty()) view.erase("extensions");
    }
    out.resize(align4(out.size()), '\0');
    json kept = json::array({buffers[0]});
    kept[0]["byteLength"] = out.size();
    buffers = kept;
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        if (!doc.contains(list) || !doc[list].is_array()) continue;
        json& names = doc[list];
        names.erase(std::remove(names.begin(), names.end(), json(EXTENSION)), names.end());
        if (names.empty()) doc.erase(list);
    }

    std::string text = doc.dump();
    text.resize(align4(text.size()), ' ');
    const std::uint64_t total = 12 + 8 + text.size() + 8 + out.size();
    if (total > std::numeric_limits<std::uint32_t>::max()) failRead(name, 0, "decoded glTF exceeds 4 GiB");
    std::string glbOut;
    glbOut.reserve(std::size_t(total));
    glbOut.append("glTF", 4);
    appendU32(glbOut, 2);
    appendU32(glbOut, std::uint32_t(total));
    appendU32(glbOut, std::uint32_t(text.size()));
    glbOut.append("JSON", 4);
    glbOut += text;
    appendU32(glbOut, std::uint32_t(out.size()));
    glbOut.append("BIN\0", 4);
    glbOut += out;
    return glbOut;
}

} // namespace strata::meshing::detail
