// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "NpzReader.h"

#include "ElevationFileCommon.h"
#include "NpyReader.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace strata::terrain::detail {

namespace {

struct ZipEntry
{
    std::string name;
    int method = 0;
    int flags = 0;
    std::uint32_t crc = 0;
    std::uint64_t compressedSize = 0, size = 0, localOffset = 0;
};

/// The central directory of a zip archive (zip64 included).
std::vector<ZipEntry> zipDirectory(std::string_view bytes, const std::string& name)
{
    constexpr std::size_t EOCD_SIZE = 22;
    if (bytes.size() < EOCD_SIZE) failDem(name, "not a zip archive (.npz): too short");
    // The end of central directory record, searched backwards (a comment may follow it).
    std::size_t eocd = std::string_view::npos;
    const std::size_t lowest = bytes.size() - EOCD_SIZE > 65535 ? bytes.size() - EOCD_SIZE - 65535 : 0;
    for (std::size_t at = bytes.size() - EOCD_SIZE + 1; at-- > lowest;) {
        if (bytes.substr(at, 4) == std::string_view("PK\x05\x06", 4)) {
            eocd = at;
            break;
        }
    }
    if (eocd == std::string_view::npos) failDem(name, "not a zip archive (.npz): no end of central directory record");
    if (readLittle(bytes, eocd + 4, 2) != 0 || readLittle(bytes, eocd + 6, 2) != 0) {
        failDem(name, "multi-part zip archives are not supported");
    }
    std::uint64_t count = readLittle(bytes, eocd + 10, 2);
    std::uint64_t directorySize = readLittle(bytes, eocd + 12, 4);
    std::uint64_t directoryOffset = readLittle(bytes, eocd + 16, 4);
    if (count == 0xFFFF || directorySize == 0xFFFFFFFF || directoryOffset == 0xFFFFFFFF) {
        // zip64: the locator (20 bytes) sits just before the record.
        if (eocd < 20 || bytes.substr(eocd - 20, 4) != std::string_view("PK\x06\x07", 4)) {
            failDem(name, "zip64 archive without its end of central directory locator");
        }
        const std::uint64_t record = readLittle(bytes, eocd - 20 + 8, 8);
        if (!fitsIn(bytes, record, 56) || bytes.substr(std::size_t(record), 4) != std::string_view("PK\x06\x06", 4)) {
            failDem(name, "the zip64 end of central directory record is missing or truncated");
        }
        count = readLittle(bytes, std::size_t(record) + 32, 8);
        directorySize = readLittle(bytes, std::size_t(record) + 40, 8);
        directoryOffset = readLittle(bytes, std::size_t(record) + 48, 8);
    }
    if (!fitsIn(bytes, directoryOffset, directorySize))
        failDem(name, "the zip central directory lies outside the file");
    if (count > directorySize / 46)
        failDem(name, "the zip central directory is too small for its " + std::to_string(count) + " entries");

    std::vector<ZipEntry> entries;
    std::size_t at = std::size_t(directoryOffset);
    const std::size_t end = std::size_t(directoryOffset + directorySize);
    for (std::uint64_t i = 0; i < count; ++i) {
        if (end - at < 46 || bytes.substr(at, 4) != std::string_view("PK\x01\x02", 4)) {
            failDem(name, "zip central directory entry " + std::to_string(i + 1) + " is malformed");
        }
        ZipEntry e;
        e.flags = int(readLittle(bytes, at + 8, 2));
        e.method = int(readLittle(bytes, at + 10, 2));
        e.crc = std::uint32_t(readLittle(bytes, at + 16, 4));
        e.compressedSize = readLittle(bytes, at + 20, 4);
        e.size = readLittle(bytes, at + 24, 4);
        const std::size_t nameLength = std::size_t(readLittle(bytes, at + 28, 2));
        const std::size_t extraLength = std::size_t(readLittle(bytes, at + 30, 2));
        const std::size_t commentLength = std::size_t(readLittle(bytes, at + 32, 2));
        e.localOffset = readLittle(bytes, at + 42, 4);
        if (end - at - 46 < nameLength + extraLength + commentLength) {
            failDem(name, "zip central directory entry " + std::to_string(i + 1) + " runs past the directory");
        }
        e.name = std::string(bytes.substr(at + 46, nameLength));
        // zip64 extended information: the 64-bit forms of the fields set to 0xFFFFFFFF, in order.
        std::size_t extra = at + 46 + nameLength;
        const std::size_t extraEnd = extra + extraLength;
        while (extraEnd - extra >= 4) {
            const std::uint64_t id = readLittle(bytes, extra, 2);
            const std::size_t size = std::size_t(readLittle(bytes, extra + 2, 2));
            if (extraEnd - extra - 4 < size) failDem(name, "zip entry '" + e.name + "' has a malformed extra field");
            if (id == 0x0001) {
                std::size_t field = extra + 4;
                for (std::uint64_t* value : {&e.size, &e.compressedSize, &e.localOffset}) {
                    if (*value != 0xFFFFFFFF) continue;
                    if (field + 8 > extra + 4 + size)
                        failDem(name, "zip entry '" + e.name + "' has a truncated zip64 field");
                    *value = readLittle(bytes, field, 8);
                    field += 8;
                }
            }
            extra += 4 + size;
        }
        entries.push_back(std::move(e));
        at += 46 + nameLength + extraLength + commentLength;
    }
    return entries;
}

/// The first `limit` bytes of a member (all of it by default), stored
/// (method 0) or deflated (method 8, as np.savez_compressed and some
/// packagers write: inflated with zlib). Inflated a step at a time, so
/// memory follows the bytes the data really yields, never the size its
/// header claims; the CRC is checked when the whole member is read. Errors
/// for other methods, 4 GiB or more, more than 1032 times its packed size
/// (deflate's limit) and a failed CRC.
std::string zipMember(std::string_view bytes, const ZipEntry& e, const std::string& name,
                      std::uint64_t limit = std::numeric_limits<std::uint64_t>::max())
{
    if (e.flags & 1) failDem(name, "member '" + e.name + "' is encrypted, which is not supported");
    if (e.method != 0 && e.method != 8) {
        failDem(name, "member '" + e.name + "' uses zip compression method " + std::to_string(e.method) +
                          ", which is not supported (only stored and deflated members)");
    }
    if (e.method == 0 && e.compressedSize != e.size)
        failDem(name, "stored member '" + e.name + "' has different packed and unpacked sizes");
    // zlib counts in 32 bits: 2^32 bytes would read as 0.
    constexpr std::uint64_t FOUR_GIB = std::uint64_t(1) << 32;
    if (e.size >= FOUR_GIB || e.compressedSize >= FOUR_GIB ||
        (e.method == 8 && e.size > 1032 * e.compressedSize + 1024))
        failDem(name, "member '" + e.name + "' claims " + std::to_string(e.size) + " bytes, more than it can hold");
    if (!fitsIn(bytes, e.localOffset, 30) ||
        bytes.substr(std::size_t(e.localOffset), 4) != std::string_view("PK\x03\x04", 4)) {
        failDem(name, "member '" + e.name + "': its local header is missing or lies outside the file");
    }
    const std::uint64_t data = e.localOffset + 30 + readLittle(bytes, std::size_t(e.localOffset) + 26, 2) +
                               readLittle(bytes, std::size_t(e.localOffset) + 28, 2);
    if (!fitsIn(bytes, data, e.compressedSize))
        failDem(name, "member '" + e.name + "' runs past the end of the file (truncated?)");
    const std::string_view packed = bytes.substr(std::size_t(data), std::size_t(e.compressedSize));
    const bool whole = limit >= e.size;
    std::string content;
    if (e.method == 0) {
        content = std::string(packed.substr(0, std::size_t(std::min(limit, e.size))));
    } else {
        // One byte more than the member claims when reading it whole, so a
        // stream that yields more is seen.
        const std::uint64_t room = whole ? e.size + 1 : limit;
        z_stream stream{};
        if (inflateInit2(&stream, -MAX_WBITS) != Z_OK) failDem(name, "zlib could not start inflating");
        stream.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(packed.data()));
        stream.avail_in = uInt(packed.size());
        int status = Z_OK;
        while (status == Z_OK && content.size() < room) {
            const std::size_t have = content.size();
            const std::size_t step = std::size_t(std::min<std::uint64_t>(room - have, std::uint64_t(1) << 20));
            content.resize(have + step);
            stream.next_out = reinterpret_cast<Bytef*>(content.data() + have);
            stream.avail_out = uInt(step);
            status = inflate(&stream, Z_NO_FLUSH);
            content.resize(have + step - stream.avail_out);
        }
        inflateEnd(&stream);
        const bool complete = whole ? status == Z_STREAM_END && content.size() == e.size
                                    : content.size() == limit || status == Z_STREAM_END;
        if (!complete) {
            failDem(name, "member '" + e.name + "' is not valid deflate data of " + std::to_string(e.size) +
                              " bytes (corrupt file)");
        }
    }
    if (whole && ::crc32(0L, reinterpret_cast<const Bytef*>(content.data()), uInt(content.size())) != e.crc)
        failDem(name, "member '" + e.name + "' fails its CRC-32 check (corrupt file)");
    return content;
}

/// Enough of a .npy member to hold its header (at most 64 KiB long).
constexpr std::uint64_t NPY_HEADER_BYTES = 12 + 65536;

} // namespace

ElevationGrid parseNpz(std::string_view bytes, const std::string& name)
{
    const std::vector<ZipEntry> entries = zipDirectory(bytes, name);
    auto isArray = [](const ZipEntry& e) { return e.name.size() > 4 && e.name.ends_with(".npy"); };
    const ZipEntry* chosen = nullptr;
    for (const ZipEntry& e : entries) {
        if (e.name == "elevation.npy") chosen = &e;
    }
    if (!chosen) {
        // The only 2D array, found by each member's header alone.
        std::vector<const ZipEntry*> planes;
        std::string names;
        for (const ZipEntry& e : entries) {
            if (!isArray(e)) continue;
            names += (names.empty() ? "" : ", ") + e.name;
            const NpyHeader header =
                parseNpyHeader(zipMember(bytes, e, name, NPY_HEADER_BYTES), name + " member '" + e.name + "'");
            if (header.shape.size() == 2) planes.push_back(&e);
        }
        if (planes.size() > 1) {
            std::string list;
            for (const ZipEntry* e : planes) list += (list.empty() ? "" : ", ") + e->name;
            failDem(name,
                    "holds several 2D arrays (" + list + ") and none named 'elevation': save the DEM as 'elevation'");
        }
        if (planes.empty()) {
            failDem(name, "holds no 2D array" +
                              (names.empty() ? std::string(" (no .npy member at all)") : " (arrays: " + names + ")"));
        }
        chosen = planes.front();
    }
    // The header's layout against the member's size before inflating it all.
    const std::string member = name + " member '" + chosen->name + "'";
    checkNpySize(npyLayout(zipMember(bytes, *chosen, name, NPY_HEADER_BYTES), member), chosen->size, member);
    ElevationGrid grid = parseNpy(zipMember(bytes, *chosen, name), member);
    grid.format = "npz";
    grid.member = chosen->name;
    return grid;
}

} // namespace strata::terrain::detail
