// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/PlyIO.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>

#include "FilePlace.h"
#include <strata/meshing/MeshFile.h>

#include "MeshReadSupport.h"
#include "OpenMeshConvert.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

namespace strata::meshing {

namespace {

using detail::OmMesh;

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool plyTypeFromName(std::string_view name, PlyType& type)
{
    static const std::pair<const char*, PlyType> NAMES[] = {
        {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
        {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
        {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
        {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
        {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
        {"float64", PlyType::Float64}};
    for (const auto& [text, value] : NAMES) {
        if (name == text) {
            type = value;
            return true;
        }
    }
    return false;
}

std::size_t plyTypeSize(PlyType type)
{
    switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
    }
    return 1;
}

bool plyTypeIsInteger(PlyType type)
{
    return type != PlyType::Float32 && type != PlyType::Float64;
}

struct PlyProperty
{
    std::string name;
    bool isList = false;
    PlyType countType = PlyType::UInt8; // lists only
    PlyType type = PlyType::Float32;    // the scalar, or the list's items
};

struct PlyElement
{
    std::string name;
    std::uint64_t count = 0;
    std::vector<PlyProperty> properties;
};

/// A strict PLY reader: every header count is checked against the bytes that
/// follow the header before anything is allocated, every value is checked as
/// it is read, and any problem throws BadInput naming the file and element.
class PlyParser
{
public:
    PlyParser(std::string_view bytes, const std::string& name)
        : mBytes(bytes), mName(name)
    {
    }

    TriangleMesh parse()
    {
        readHeader();
        findVertexAndFace();
        checkCounts();
        if (mFormat == Format::Ascii) {
            readAsciiBody();
        } else {
            readBinaryBody();
        }
        return std::move(mMesh);
    }

private:
    enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

    [[noreturn]] void fail(const std::string& what, int line = 0) const { detail::failRead(mName, line, what); }

    std::string itemName(const PlyElement& element, std::uint64_t item) const
    {
        return element.name + " " + std::to_string(item);
    }

    void readHeader()
    {
        detail::LineReader lines(mBytes, '\0');
        if (!lines.next() || lines.tokens().size() != 1 || lines.tokens()[0] != "ply") {
            fail("not a PLY file (no 'ply' on the first line)");
        }
        bool haveFormat = false;
        for (;;) {
            if (!lines.next()) fail("the header has no 'end_header'");
            const auto& t = lines.tokens();
            const int line = lines.line();
            if (t[0] == "end_header") {
                mBodyOffset = lines.offset();
                mHeaderLines = line;
                break;
            }
            if (t[0] == "comment" || t[0] == "obj_info") continue;
            if (t[0] == "format") {
                if (t.size() != 3) fail("malformed 'format' line", line);
                if (t[1] == "ascii") mFormat = Format::Ascii;
                else if (t[1] == "binary_little_endian") mFormat = Format::BinaryLittleEndian;
                else if (t[1] == "binary_big_endian") mFormat = Format::BinaryBigEndian;
                else fail("unknown format " + detail::quoted(t[1]), line);
                haveFormat = true;
            } else if (t[0] == "element") {
                std::int64_t count = 0;
                if (t.size() != 3) fail("malformed 'element' line", line);
                if (!detail::parseInteger(t[2], count) || count < 0) {
                    fail("element '" + std::string(t[1]) + "': count " + detail::quoted(t[2]) +
                             " is not a non-negative integer",
                         line);
                }
                mElements.push_back({std::string(t[1]), std::uint64_t(count), {}});
            } else if (t[0] == "property") {
                if (mElements.empty()) fail("'property' before any 'element'", line);
                PlyProperty property;
                if (t.size() == 5 && t[1] == "list") {
                    property.isList = true;
                    if (!plyTypeFromName(t[2], property.countType) || !plyTypeFromName(t[3], property.type)) {
                        fail("property '" + std::string(t[4]) + "': unknown type", line);
                    }
                    if (!plyTypeIsInteger(property.countType)) {
                        fail("property '" + std::string(t[4]) + "': list count type must be an integer", line);
                    }
                    property.name = t[4];
                } else if (t.size() == 3) {
                    if (!plyTypeFromName(t[1], property.type)) {
                        fail("property '" + std::string(t[2]) + "': unknown type " + detail::quoted(t[1]), line);
                    }
                    property.name = t[2];
                } else {
                    fail("malformed 'property' line", line);
                }
                mElements.back().properties.push_back(property);
            } else {
                fail("unknown header keyword " + detail::quoted(t[0]), line);
            }
        }
        if (!haveFormat) fail("the header has no 'format' line");
    }

    static int findProperty(const PlyElement& element, std::string_view name)
    {
        for (std::size_t i = 0; i < element.properties.size(); ++i) {
            if (element.properties[i].name == name) return int(i);
        }
        return -1;
    }

    void findVertexAndFace()
    {
        for (std::size_t e = 0; e < mElements.size(); ++e) {
            if (mElements[e].name == "vertex" && mVertexElement < 0) mVertexElement = int(e);
            if (mElements[e].name == "face" && mFaceElement < 0) mFaceElement = int(e);
        }
        if (mVertexElement < 0) fail("no 'vertex' element");
        const PlyElement& vertex = mElements[mVertexElement];
        const char* const NAMES[6] = {"x", "y", "z", "nx", "ny", "nz"};
        for (int i = 0; i < 6; ++i) {
            mVertexProperty[i] = findProperty(vertex, NAMES[i]);
            if (mVertexProperty[i] >= 0 && vertex.properties[mVertexProperty[i]].isList) {
                fail(std::string("vertex property '") + NAMES[i] + "' is a list");
            }
        }
        if (mVertexProperty[0] < 0 || mVertexProperty[1] < 0 || mVertexProperty[2] < 0) {
            fail("the 'vertex' element has no x, y and z properties");
        }
        mHasNormals = mVertexProperty[3] >= 0 && mVertexProperty[4] >= 0 && mVertexProperty[5] >= 0;
        if (vertex.count > std::numeric_limits<std::uint32_t>::max()) {
            fail("too many vertices (" + std::to_string(vertex.count) + ")");
        }
        if (mFaceElement >= 0) {
            const PlyElement& face = mElements[mFaceElement];
            mFaceProperty = findProperty(face, "vertex_indices");
            if (mFaceProperty < 0) mFaceProperty = findProperty(face, "vertex_index");
            if (mFaceProperty < 0 || !face.properties[mFaceProperty].isList) {
                fail("the 'face' element has no 'vertex_indices' list");
            }
            if (!plyTypeIsInteger(face.properties[mFaceProperty].type)) {
                fail("face property 'vertex_indices' must hold integers");
            }
        }
    }

    // Every element needs at least some bytes per item; a header that claims
    // more items than the file can hold is rejected before any allocation.
    void checkCounts()
    {
        const std::uint64_t available = mBytes.size() - mBodyOffset;
        std::uint64_t needed = 0;
        for (std::size_t e = 0; e < mElements.size(); ++e) {
            const PlyElement& element = mElements[e];
            std::uint64_t perItem = 0;
            for (std::size_t p = 0; p < element.properties.size(); ++p) {
                const PlyProperty& property = element.properties[p];
                perItem += mFormat == Format::Ascii ? 2 : plyTypeSize(property.isList ? property.countType : property.type);
                if (int(e) == mFaceElement && int(p) == mFaceProperty) {
                    // A face has at least three indices.
                    perItem += mFormat == Format::Ascii ? 6 : 3 * plyTypeSize(property.type);
                }
            }
            perItem = std::max<std::uint64_t>(perItem, 1);
            if (element.count > (available + 1) / perItem) {
                fail("element '" + element.name + "' claims " + std::to_string(element.count) + " items of at least " +
                     std::to_string(perItem) + " bytes, but only " + std::to_string(available) +
                     " bytes follow the header");
            }
            needed += element.count * perItem;
            if (needed > available + 1) {
                fail("the header's elements need at least " + std::to_string(needed) + " bytes, but only " +
                     std::to_string(available) + " bytes follow it");
            }
        }
        const std::uint64_t vertices = mElements[mVertexElement].count;
        mMesh.positions.reserve(vertices);
        if (mHasNormals) mMesh.normals.reserve(vertices);
        if (mFaceElement >= 0) mMesh.indices.reserve(mElements[mFaceElement].count * 3);
    }

    void addVertex(const PlyElement& element, std::uint64_t item, const double* values, int line)
    {
        static const char* const WHAT[6] = {"coordinate x", "coordinate y", "coordinate z",
                                            "normal x",     "normal y",     "normal z"};
        float v[6] = {};
        for (int i = 0; i < (mHasNormals ? 6 : 3); ++i) {
            const double d = values[mVertexProperty[i]];
            if (!std::isfinite(d) || std::abs(d) > double(std::numeric_limits<float>::max())) {
                fail(itemName(element, item) + ": " + WHAT[i] + " is not a finite float", line);
            }
            v[i] = float(d);
        }
        mMesh.positions.emplace_back(v[0], v[1], v[2]);
        if (mHasNormals) mMesh.normals.emplace_back(v[3], v[4], v[5]);
    }

    void addFace(const PlyElement& element, std::uint64_t item, const std::vector<std::int64_t>& loop, int line)
    {
        if (loop.size() < 3) {
            fail(itemName(element, item) + ": has " + std::to_string(loop.size()) + " vertices (at least 3 needed)",
                 line);
        }
        const std::uint64_t vertices = mElements[mVertexElement].count;
        for (std::int64_t index : loop) {
            if (index < 0 || std::uint64_t(index) >= vertices) {
                fail(itemName(element, item) + ": vertex index " + std::to_string(index) + " is out of range (" +
                         std::to_string(vertices) + " vertices)",
                     line);
            }
        }
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
            mMesh.indices.insert(mMesh.indices.end(),
                                 {std::uint32_t(loop[0]), std::uint32_t(loop[i]), std::uint32_t(loop[i + 1])});
        }
    }

    void readAsciiBody()
    {
        detail::LineReader lines(mBytes.substr(mBodyOffset), '\0');
        std::vector<double> values;
        std::vector<std::int64_t> loop;
        for (std::size_t e = 0; e < mElements.size(); ++e) {
            const PlyElement& element = mElements[e];
            values.assign(element.properties.size(), 0.0);
            for (std::uint64_t item = 0; item < element.count; ++item) {
                if (!lines.next()) fail("the file ends before " + itemName(element, item));
                const int line = mHeaderLines + lines.line();
                const auto& tokens = lines.tokens();
                std::size_t next = 0;
                auto token = [&](const PlyProperty& property) {
                    if (next >= tokens.size()) {
                        fail(itemName(element, item) + ": too few values (property '" + property.name + "' is missing)",
                             line);
                    }
                    return tokens[next++];
                };
                auto integer = [&](const PlyProperty& property, std::string_view text) {
                    std::int64_t value = 0;
                    if (!detail::parseInteger(text, value)) {
                        fail(itemName(element, item) + ": " + property.name + " value " + detail::quoted(text) +
                                 " is not an integer",
                             line);
                    }
                    return value;
                };
                loop.clear();
                for (std::size_t p = 0; p < element.properties.size(); ++p) {
                    const PlyProperty& property = element.properties[p];
                    if (property.isList) {
                        const std::int64_t count = integer(property, token(property));
                        if (count < 0 || std::size_t(count) > tokens.size() - next) {
                            fail(itemName(element, item) + ": list '" + property.name + "' claims " +
                                     std::to_string(count) + " values but the line has " +
                                     std::to_string(tokens.size() - next),
                                 line);
                        }
                        const bool isFace = int(e) == mFaceElement && int(p) == mFaceProperty;
                        for (std::int64_t i = 0; i < count; ++i) {
                            const std::string_view text = token(property);
                            if (isFace) {
                                loop.push_back(integer(property, text));
                            } else {
                                checkNumber(element, item, property, text, line);
                            }
                        }
                    } else {
                        values[p] = checkNumber(element, item, property, token(property), line);
                    }
                }
                if (next != tokens.size()) {
                    fail(itemName(element, item) + ": " + std::to_string(tokens.size() - next) +
                             " values more than the header declares",
                         line);
                }
                if (int(e) == mVertexElement) addVertex(element, item, values.data(), line);
                if (int(e) == mFaceElement) addFace(element, item, loop, line);
            }
        }
    }

    double checkNumber(const PlyElement& element, std::uint64_t item, const PlyProperty& property,
                       std::string_view text, int line) const
    {
        std::string_view t = text;
        if (!t.empty() && t.front() == '+') t.remove_prefix(1);
        double value = 0.0;
        const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
        if (ec != std::errc() || end != t.data() + t.size() || t.empty()) {
            const bool coordinate = property.name == "x" || property.name == "y" || property.name == "z";
            fail(itemName(element, item) + ": " + (coordinate ? "coordinate" : property.name + " value") + " " +
                     detail::quoted(text) + " is not a number",
                 line);
        }
        return value;
    }

    // Binary: every read checks the bytes left.
    double readBinary(PlyType type, const PlyElement& element, std::uint64_t item)
    {
        const std::size_t size = plyTypeSize(type);
        if (mBytes.size() - mPos < size) fail("the file ends inside " + itemName(element, item));
        unsigned char raw[8];
        std::memcpy(raw, mBytes.data() + mPos, size);
        mPos += size;
        if (mFormat == Format::BinaryBigEndian) std::reverse(raw, raw + size);
        switch (type) {
        case PlyType::Int8: return double(std::int8_t(raw[0]));
        case PlyType::UInt8: return double(raw[0]);
        case PlyType::Int16: { std::int16_t v; std::memcpy(&v, raw, 2); return double(v); }
        case PlyType::UInt16: { std::uint16_t v; std::memcpy(&v, raw, 2); return double(v); }
        case PlyType::Int32: { std::int32_t v; std::memcpy(&v, raw, 4); return double(v); }
        case PlyType::UInt32: { std::uint32_t v; std::memcpy(&v, raw, 4); return double(v); }
        case PlyType::Float32: { float v; std::memcpy(&v, raw, 4); return double(v); }
        case PlyType::Float64: { double v; std::memcpy(&v, raw, 8); return v; }
        }
        return 0.0;
    }

    void readBinaryBody()
    {
        static_assert(std::endian::native == std::endian::little, "the binary PLY reader assumes a little-endian host");
        mPos = mBodyOffset;
        std::vector<double> values;
        std::vector<std::int64_t> loop;
        for (std::size_t e = 0; e < mElements.size(); ++e) {
            const PlyElement& element = mElements[e];
            values.assign(element.properties.size(), 0.0);
            for (std::uint64_t item = 0; item < element.count; ++item) {
                loop.clear();
                for (std::size_t p = 0; p < element.properties.size(); ++p) {
                    const PlyProperty& property = element.properties[p];
                    if (!property.isList) {
                        values[p] = readBinary(property.type, element, item);
                        continue;
                    }
                    const double count = readBinary(property.countType, element, item);
                    const std::size_t itemSize = plyTypeSize(property.type);
                    if (count < 0 || count > double((mBytes.size() - mPos) / itemSize)) {
                        fail(itemName(element, item) + ": list '" + property.name + "' claims " +
                             std::to_string(std::int64_t(count)) + " values, more than the file holds");
                    }
                    const bool isFace = int(e) == mFaceElement && int(p) == mFaceProperty;
                    if (!isFace) {
                        mPos += std::size_t(count) * itemSize;
                        continue;
                    }
                    for (std::size_t i = 0; i < std::size_t(count); ++i) {
                        loop.push_back(std::int64_t(readBinary(property.type, element, item)));
                    }
                }
                if (int(e) == mVertexElement) addVertex(element, item, values.data(), 0);
                if (int(e) == mFaceElement) addFace(element, item, loop, 0);
            }
        }
    }

    std::string_view mBytes;
    std::string mName;
    Format mFormat = Format::Ascii;
    std::size_t mBodyOffset = 0;
    int mHeaderLines = 0;
    std::vector<PlyElement> mElements;
    int mVertexElement = -1, mFaceElement = -1;
    int mVertexProperty[6] = {-1, -1, -1, -1, -1, -1};
    int mFaceProperty = -1;
    bool mHasNormals = false;
    std::size_t mPos = 0;
    TriangleMesh mMesh;
};

} // namespace

void writePly(const TriangleMesh& mesh, const std::filesystem::path& path)
{
    OmMesh om;
    const bool hasNormals = detail::toOpenMesh(mesh, om);

    OpenMesh::IO::Options options = OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::LSB;
    if (hasNormals) options += OpenMesh::IO::Options::VertexNormal;
    // Serialised in memory, then written with checked writes: OpenMesh's file
    // writers do not report a failed stream.
    std::ostringstream bytes;
    if (!OpenMesh::IO::write_mesh(om, bytes, ".ply", options) || !bytes) {
        throw Error(ErrorKind::Internal, "cannot write mesh file '" + path.string() + "': OpenMesh failed",
                    {.file = path.string()});
    }
    writeFileAtomically(path, bytes.view());
}

TriangleMesh readMeshFile(const std::filesystem::path& path)
{
    return readMesh(path);
}

TriangleMesh readPly(const std::filesystem::path& path)
{
    return parsePly(detail::readWholeFile(path), path.string());
}

TriangleMesh parsePly(std::string_view bytes, const std::string& name)
{
    return PlyParser(bytes, name).parse();
}

} // namespace strata::meshing
