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

MeshoptGlb decodeMeshoptGlb(std::string_view glb, const std::string& name)
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

    // Check every compressed view and give it a place in the decoded buffer;
    // decodeMeshoptViews() decodes them once tinygltf has parsed the rest
    // (so the decoded bytes are written once, never copied).
    MeshoptGlb result;
    std::vector<MeshoptJob>& jobs = result.jobs;
    std::size_t cursor = 0;
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
        MeshoptJob job;
        job.where = where + "'s " + EXTENSION;
        if (!ext.is_object()) failRead(name, 0, job.where + " is not an object");
        if (unsignedMember(ext, "buffer", job.where, name) != 0)
            failRead(name, 0, job.where + " reads a buffer other than the binary chunk (not supported)");
        const std::uint64_t offset = unsignedMember(ext, "byteOffset", job.where, name, 0);
        const std::uint64_t length = unsignedMember(ext, "byteLength", job.where, name);
        job.stride = unsignedMember(ext, "byteStride", job.where, name);
        job.count = unsignedMember(ext, "count", job.where, name);
        const auto mode = ext.find("mode");
        job.mode = mode != ext.end() && mode->is_string() ? mode->get<std::string>() : std::string();
        const auto filter = ext.find("filter");
        job.filter = filter != ext.end() && filter->is_string() ? filter->get<std::string>() : std::string("NONE");
        if (offset > bin.size() || length > bin.size() - offset)
            failRead(name, 0, job.where + " (offset " + std::to_string(offset) + ", length " + std::to_string(length) +
                                  ") runs past the binary chunk (" + std::to_string(bin.size()) + " bytes)");
        job.sourceOffset = std::size_t(offset);
        job.sourceLength = std::size_t(length);
        const std::uint64_t viewLength = unsignedMember(view, "byteLength", where, name);
        if (viewLength > std::numeric_limits<std::uint32_t>::max())
            failRead(name, 0, where + " is larger than a GLB can hold");
        // The extension requires the view's byteLength to be byteStride times
        // count: the decoded buffer holds exactly that, never a larger claim.
        if (job.stride == 0 || job.count > viewLength / job.stride || job.count * job.stride != viewLength)
            failRead(name, 0, where + ": byteLength " + std::to_string(viewLength) + " is not its " +
                                  std::to_string(job.count) + " elements of " + std::to_string(job.stride) +
                                  " bytes (EXT_meshopt_compression requires byteStride * count)");
        // No codec inflates more than 64 times (a vertex byte column costs at
        // least 2 header bits per 16 vertices): a larger claim is a broken
        // file, not a reason to allocate gigabytes.
        if (job.count * job.stride > 64 * length + 4096)
            failRead(name, 0, job.where + ": " + std::to_string(job.count * job.stride) + " decoded bytes from " +
                                  std::to_string(length) + " compressed is more than any codec yields");
        if (job.mode == "ATTRIBUTES") {
            if (job.stride % 4 != 0 || job.stride > 256)
                failRead(name, 0, job.where + ": byteStride " + std::to_string(job.stride) +
                                      " is not a multiple of 4 up to 256");
        } else if (job.mode == "TRIANGLES" || job.mode == "INDICES") {
            if (job.stride != 2 && job.stride != 4)
                failRead(name, 0, job.where + ": byteStride " + std::to_string(job.stride) + " is not 2 or 4 for indices");
            if (job.mode == "TRIANGLES" && job.count % 3 != 0)
                failRead(name, 0, job.where + ": TRIANGLES count " + std::to_string(job.count) +
                                      " is not a multiple of 3");
        } else {
            failRead(name, 0, job.where + ": mode '" + job.mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
        }
        if (job.filter != "NONE" && job.mode != "ATTRIBUTES")
            failRead(name, 0, job.where + ": a filter needs mode ATTRIBUTES");
        if (job.filter == "OCTAHEDRAL" && job.stride != 4 && job.stride != 8)
            failRead(name, 0, job.where + ": OCTAHEDRAL needs byteStride 4 or 8");
        else if (job.filter == "QUATERNION" && job.stride != 8)
            failRead(name, 0, job.where + ": QUATERNION needs byteStride 8");
        else if (job.filter != "NONE" && job.filter != "OCTAHEDRAL" && job.filter != "QUATERNION" &&
                 job.filter != "EXPONENTIAL")
            failRead(name, 0, job.where + ": filter '" + job.filter +
                                  "' is not NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");

        job.at = align4(cursor);
        cursor = job.at + std::size_t(viewLength); // = count * byteStride (checked above)
        if (cursor > std::numeric_limits<std::uint32_t>::max()) failRead(name, 0, "decoded data exceed 4 GiB");
        view["buffer"] = 1; // the decoded buffer, added after parsing
        view["byteOffset"] = job.at;
        view["extensions"].erase(EXTENSION);
        if (view["extensions"].empty()) view.erase("extensions");
        jobs.push_back(std::move(job));
    }
    result.decodedBytes = align4(cursor);
    json kept = json::array({buffers[0]});
    kept[0]["byteLength"] = bin.size();
    buffers = kept;
    for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
        if (!doc.contains(list) || !doc[list].is_array()) continue;
        json& names = doc[list];
        names.erase(std::remove(names.begin(), names.end(), json(EXTENSION)), names.end());
        if (names.empty()) doc.erase(list);
    }

    // The same .glb with the new JSON and the compressed binary chunk.
    std::string text = doc.dump();
    text.resize(align4(text.size()), ' ');
    const std::size_t binLength = align4(bin.size());
    const std::uint64_t total = 12 + 8 + text.size() + 8 + binLength;
    if (total > std::numeric_limits<std::uint32_t>::max()) failRead(name, 0, "glTF exceeds 4 GiB");
    std::string& out = result.glb;
    out.reserve(std::size_t(total));
    out.append("glTF", 4);
    appendU32(out, 2);
    appendU32(out, std::uint32_t(total));
    appendU32(out, std::uint32_t(text.size()));
    out.append("JSON", 4);
    out += text;
    appendU32(out, std::uint32_t(binLength));
    out.append("BIN\0", 4);
    out += bin;
    out.resize(std::size_t(total), '\0');
    return result;
}

void decodeMeshoptViews(const MeshoptGlb& glb, const std::vector<unsigned char>& bin, std::vector<unsigned char>& decoded,
                        const std::string& name)
{
    decoded.assign(glb.decodedBytes, 0);
    for (const MeshoptJob& job : glb.jobs) {
        if (job.sourceOffset > bin.size() || job.sourceLength > bin.size() - job.sourceOffset)
            failRead(name, 0, job.where + ": its compressed bytes run past the binary chunk");
        unsigned char* target = decoded.data() + job.at;
        const unsigned char* source = bin.data() + job.sourceOffset;
        const auto count = std::size_t(job.count), stride = std::size_t(job.stride);
        int rc = 0;
        if (job.mode == "ATTRIBUTES") rc = meshopt_decodeVertexBuffer(target, count, stride, source, job.sourceLength);
        else if (job.mode == "TRIANGLES") rc = meshopt_decodeIndexBuffer(target, count, stride, source, job.sourceLength);
        else rc = meshopt_decodeIndexSequence(target, count, stride, source, job.sourceLength);
        if (rc != 0)
            failRead(name, 0, job.where + ": meshoptimizer cannot decode it (error " + std::to_string(rc) + ")");
        if (job.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(target, count, stride);
        else if (job.filter == "QUATERNION") meshopt_decodeFilterQuat(target, count, stride);
        else if (job.filter == "EXPONENTIAL") meshopt_decodeFilterExp(target, count, stride);
    }
}

} // namespace strata::meshing::detail
