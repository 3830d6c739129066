// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/ImageFileStructure.h>

#include <strata/Error.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <string>

namespace strata::render {

namespace {

std::string printable(std::string text)
{
    for (char& c : text) {
        if (c < 32 || c > 126) c = '?';
    }
    return text;
}

void checkPng(std::ifstream& in, std::uint64_t size)
{
    std::uint64_t offset = 8;
    for (;;) {
        if (size - offset < 12) {
            throw Error(ErrorKind::BadInput, "is a truncated PNG: it ends at byte " + std::to_string(size) + " without an IEND chunk");
        }
        unsigned char chunk[8];
        in.seekg(std::streamoff(offset));
        if (!in.read(reinterpret_cast<char*>(chunk), 8)) throw Error(ErrorKind::BadInput, "cannot be read at byte " + std::to_string(offset));
        const std::uint64_t length = (std::uint64_t(chunk[0]) << 24) | (std::uint64_t(chunk[1]) << 16) |
                                     (std::uint64_t(chunk[2]) << 8) | std::uint64_t(chunk[3]);
        const std::string type = printable(std::string(reinterpret_cast<const char*>(chunk + 4), 4));
        if (length > 0x7fffffffu || length + 12 > size - offset) {
            throw Error(ErrorKind::BadInput, "is a truncated PNG: chunk '" + type + "' at byte " + std::to_string(offset) + " needs " +
                        std::to_string(length + 12) + " bytes, the file has " + std::to_string(size - offset) + " left");
        }
        offset += length + 12;
        if (type == "IEND") return;
    }
}

std::uint32_t littleEndian32(const std::string& bytes, std::size_t at)
{
    return std::uint32_t(std::uint8_t(bytes[at])) | std::uint32_t(std::uint8_t(bytes[at + 1])) << 8 |
           std::uint32_t(std::uint8_t(bytes[at + 2])) << 16 | std::uint32_t(std::uint8_t(bytes[at + 3])) << 24;
}

/// An OpenEXR attribute's value against its type, as OpenEXR 3 reads it:
/// fixed-size types read their own size whatever the attribute's size
/// says, and a channel list, a preview image and a string vector follow
/// their own contents, so a size that disagrees with the value sends
/// OpenEXR's reader somewhere else in the file than the size does (where
/// a fuzzed "size" made it allocate gigabytes). Returns the reason, or
/// nothing for a value that reads as its size says.
std::string exrValueProblem(const std::string& type, const std::string& value)
{
    static const std::map<std::string, std::size_t> FIXED = {
        {"box2i", 16},      {"box2f", 16},    {"v2i", 8},      {"v2f", 8},        {"v2d", 16},
        {"v3i", 12},        {"v3f", 12},      {"v3d", 24},     {"m33f", 36},      {"m33d", 72},
        {"m44f", 64},       {"m44d", 128},    {"int", 4},      {"float", 4},      {"double", 8},
        {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},   {"deepImageState", 1}, {"rational", 8},
        {"timecode", 8},    {"keycode", 28},  {"tiledesc", 9}, {"chromaticities", 32}};
    const std::size_t size = value.size();
    if (const auto fixed = FIXED.find(type); fixed != FIXED.end()) {
        if (size != fixed->second) return "has " + std::to_string(size) + " bytes, not " + std::to_string(fixed->second);
        return {};
    }
    if (type == "chlist") {
        // Channels: a NUL-terminated name and 16 bytes each; an empty name ends the list.
        for (std::size_t at = 0;;) {
            const std::size_t nul = value.find('\0', at);
            if (nul == std::string::npos) return "runs past its " + std::to_string(size) + " bytes";
            if (nul == at) {
                if (nul + 1 != size) return "ends at byte " + std::to_string(nul + 1) + " of its " + std::to_string(size);
                return {};
            }
            at = nul + 1 + 16;
            if (at > size) return "runs past its " + std::to_string(size) + " bytes";
        }
    }
    if (type == "preview") {
        if (size < 8) return "has " + std::to_string(size) + " bytes, less than a preview's size";
        const std::uint64_t pixels = std::uint64_t(littleEndian32(value, 0)) * littleEndian32(value, 4);
        if (pixels * 4 + 8 != size) {
            return "holds " + std::to_string(littleEndian32(value, 0)) + "x" + std::to_string(littleEndian32(value, 4)) +
                   " preview pixels in " + std::to_string(size) + " bytes";
        }
        return {};
    }
    if (type == "stringvector") {
        for (std::size_t at = 0; at < size;) {
            if (size - at < 4) return "runs past its " + std::to_string(size) + " bytes";
            const std::uint32_t length = littleEndian32(value, at);
            if (length > size - at - 4) return "runs past its " + std::to_string(size) + " bytes";
            at += 4 + length;
        }
        return {};
    }
    if (type == "floatvector" && size % 4 != 0) return "has " + std::to_string(size) + " bytes, not whole floats";
    return {}; // string, and types OpenEXR keeps as opaque bytes: read by the size
}

/// The bytes of one pixel of an OpenEXR channel list (exrValueProblem()
/// checked its structure): UINT and FLOAT channels 4, HALF 2.
std::uint64_t exrPixelBytes(const std::string& chlist)
{
    std::uint64_t bytes = 0;
    for (std::size_t at = 0; at < chlist.size() && chlist[at] != '\0';) {
        const std::size_t nul = chlist.find('\0', at);
        bytes += littleEndian32(chlist, nul + 1) == 1 ? 2 : 4;
        at = nul + 1 + 16;
    }
    return bytes;
}

/// The decoding buffers an OpenEXR part's header makes OpenEXR allocate when
/// the file is opened, before any pixel is read (its line buffers: up to
/// 256 lines of the data window's width for DWAB; or one tile), and the
/// pixels it claims: each must fit what MAX_IMAGE_EXPANSION bytes per file
/// byte allow (a fuzzed 957-byte header claiming a 50-million-pixel-wide
/// window made OpenEXR allocate gigabytes in its compressor).
void checkExrPart(std::int64_t width, std::int64_t height, std::uint64_t pixelBytes, std::uint64_t tileWidth,
                  std::uint64_t tileHeight, std::uint64_t size)
{
    if (width <= 0 || height <= 0) {
        throw Error(ErrorKind::BadInput, "is a corrupt OpenEXR file: its data window is " + std::to_string(width) + "x" +
                    std::to_string(height) + " pixels");
    }
    const double most = double(MAX_IMAGE_EXPANSION) * double(size) + 65536.0;
    const double bytes = double(std::max<std::uint64_t>(pixelBytes, 1));
    const double pixels = double(width) * double(height) * bytes;
    const double lines = double(width) * double(std::min<std::int64_t>(height, 256)) * bytes;
    const double tile = double(tileWidth) * double(tileHeight) * bytes;
    if (pixels > most || lines > most || tile > most) {
        throw Error(ErrorKind::BadInput, "claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels of " +
                    std::to_string(pixelBytes) + " bytes" +
                    (tileWidth ? " in " + std::to_string(tileWidth) + "x" + std::to_string(tileHeight) + " tiles" : "") +
                    " in a file of " + std::to_string(size) +
                    " bytes: more than any image compression holds (a corrupt or hostile header)");
    }
}

/// OpenEXR: after the magic number and version, one header (several for a
/// multi-part file, ended by an empty one) of attributes: name, type name
/// (NUL-terminated), a 32-bit size and the value; an empty name ends it.
/// Each value must read as its size says (exrValueProblem()), and the data
/// window, channels and tiles must fit the file (checkExrPart()).
void checkExr(std::ifstream& in, std::uint64_t size)
{
    std::uint64_t offset = 4;
    std::uint32_t version = 0;
    in.seekg(4);
    if (!in.read(reinterpret_cast<char*>(&version), 4)) throw Error(ErrorKind::BadInput, "is a truncated OpenEXR file: no version");
    offset = 8;
    const bool multipart = (version & 0x1000u) != 0;
    auto readName = [&](const char* what) {
        std::string name;
        for (;;) {
            char c;
            if (offset >= size || !in.get(c)) {
                throw Error(ErrorKind::BadInput, "is a truncated OpenEXR file: " + std::string(what) + " at byte " + std::to_string(offset) +
                            " runs past the end");
            }
            ++offset;
            if (c == '\0') return name;
            if (name.size() >= 255) {
                throw Error(ErrorKind::BadInput, "is a corrupt OpenEXR file: " + std::string(what) + " at byte " +
                            std::to_string(offset - name.size() - 1) + " is longer than 255 characters");
            }
            name += c;
        }
    };
    for (int part = 0;; ++part) {
        int attributes = 0;
        bool haveWindow = false;
        std::int64_t width = 0, height = 0;
        std::uint64_t pixelBytes = 0, tileWidth = 0, tileHeight = 0;
        for (;; ++attributes) {
            const std::string name = readName("an attribute name");
            if (name.empty()) {
                if (haveWindow) checkExrPart(width, height, pixelBytes, tileWidth, tileHeight, size);
                break;
            }
            const std::string type = readName("an attribute type");
            std::int32_t length = 0;
            if (size - offset < 4 || !in.read(reinterpret_cast<char*>(&length), 4)) {
                throw Error(ErrorKind::BadInput, "is a truncated OpenEXR file: attribute '" + printable(name) + "' has no size");
            }
            offset += 4;
            if (length < 0 || std::uint64_t(length) > size - offset) {
                throw Error(ErrorKind::BadInput, "is a corrupt OpenEXR file: attribute '" + printable(name) + "' at byte " +
                            std::to_string(offset - 4) + " claims " + std::to_string(length) + " bytes, the file has " +
                            std::to_string(size - offset) + " left");
            }
            std::string value(std::size_t(length), '\0');
            if (!in.read(value.data(), length)) throw Error(ErrorKind::BadInput, "cannot be read at byte " + std::to_string(offset));
            if (const std::string problem = exrValueProblem(type, value); !problem.empty()) {
                throw Error(ErrorKind::BadInput, "is a corrupt OpenEXR file: attribute '" + printable(name) + "' (" + printable(type) +
                            ") at byte " + std::to_string(offset - 4) + " " + problem);
            }
            offset += std::uint64_t(length);
            if (name == "dataWindow" && type == "box2i") {
                auto at = [&](std::size_t i) { return std::int64_t(std::int32_t(littleEndian32(value, i))); };
                width = at(8) - at(0) + 1;
                height = at(12) - at(4) + 1;
                haveWindow = true;
            } else if (name == "channels" && type == "chlist") {
                pixelBytes = exrPixelBytes(value);
            } else if (name == "tiles" && type == "tiledesc") {
                tileWidth = littleEndian32(value, 0);
                tileHeight = littleEndian32(value, 4);
            }
        }
        if (!multipart || attributes == 0) return; // single part, or the empty header ending a multi-part file
    }
}

} // namespace

const std::vector<std::string>& imageExtensions()
{
    static const std::vector<std::string> extensions = {"png", "jpg", "jpeg", "tif", "tiff", "exr",
                                                        "hdr", "tga", "bmp", "pgm", "ppm", "pnm"};
    return extensions;
}

std::string checkImageFileStructure(const std::filesystem::path& path)
{
    std::string extension = path.extension().string();
    if (!extension.empty()) extension.erase(0, 1);
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    const std::vector<std::string>& known = imageExtensions();
    if (std::find(known.begin(), known.end(), extension) == known.end()) {
        std::string list;
        for (const std::string& e : known) list += (list.empty() ? "." : ", .") + e;
        throw Error(ErrorKind::BadInput, extension.empty() ? "has no file extension to say its image format (one of " + list + ")"
                                      : "has the extension '." + printable(extension) +
                                            "', not an image format Strata reads (" + list + ")");
    }
    static const unsigned char PNG[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    static const unsigned char EXR[4] = {0x76, 0x2f, 0x31, 0x01};
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return extension; // the reader reports it
    std::ifstream in(path, std::ios::binary);
    unsigned char header[8] = {};
    if (size < 8 || !in.read(reinterpret_cast<char*>(header), 8)) return extension;
    if (std::memcmp(header, PNG, 8) == 0) checkPng(in, size);
    if (std::memcmp(header, EXR, 4) == 0) checkExr(in, size);
    return extension;
}

void checkImageSizeAgainstFile(const std::filesystem::path& path, int width, int height, int channels)
{
    std::error_code ec;
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) return; // the reader reports it
    const double claimed = double(std::max(width, 0)) * double(std::max(height, 0)) * double(std::max(channels, 1));
    const double most = double(MAX_IMAGE_EXPANSION) * double(size) + 65536.0;
    if (claimed > most) {
        throw Error(ErrorKind::BadInput, "claims " + std::to_string(width) + "x" + std::to_string(height) + " pixels of " +
                    std::to_string(channels) + " channel(s) in a file of " + std::to_string(size) +
                    " bytes: more than any image compression holds (a corrupt or hostile header)");
    }
}

} // namespace strata::render
