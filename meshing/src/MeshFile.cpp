// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/meshing/MeshFile.h>

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/PlyIO.h>

#include "FilePlace.h"
#include "MeshReadSupport.h"
#include "OpenMeshConvert.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>

namespace strata::meshing {

namespace {

std::string lowerExtension(const std::filesystem::path& path)
{
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}


using detail::failRead;
using detail::quoted;

float finiteFloat(std::string_view token, const std::string& name, int line, const std::string& what)
{
    float value = 0.0f;
    if (!detail::parseFiniteFloat(token, value)) failRead(name, line, what + " " + quoted(token) + " is not a finite number");
    return value;
}

// OBJ: v, vn and f lines (with v, v/t, v//n and v/t/n corners, negative
// indices counting back); other statements are skipped.
TriangleMesh parseObjText(std::string_view text, const std::string& name)
{
    TriangleMesh mesh;
    std::vector<glm::vec3> normals;
    std::vector<std::int64_t> vertexNormal; // per vertex: index into normals, -1 none, -2 conflicting
    bool normalsUsable = true;
    detail::LineReader lines(text, '#');
    std::vector<std::uint32_t> loop;
    std::uint64_t faceNumber = 0;
    while (lines.next()) {
        const auto& t = lines.tokens();
        const int line = lines.line();
        if (t[0] == "v" || t[0] == "vn") {
            if (t.size() < 4) failRead(name, line, std::string(t[0] == "v" ? "vertex" : "normal") + " has fewer than 3 coordinates");
            const bool isVertex = t[0] == "v";
            const std::string what = isVertex ? "vertex " + std::to_string(mesh.positions.size() + 1) + ": coordinate"
                                              : "normal " + std::to_string(normals.size() + 1) + ": component";
            glm::vec3 v(finiteFloat(t[1], name, line, what), finiteFloat(t[2], name, line, what),
                        finiteFloat(t[3], name, line, what));
            if (isVertex) {
                mesh.positions.push_back(v);
                vertexNormal.push_back(-1);
            } else {
                normals.push_back(v);
            }
        } else if (t[0] == "f") {
            ++faceNumber;
            const std::string face = "face " + std::to_string(faceNumber);
            if (t.size() < 4) failRead(name, line, face + ": has " + std::to_string(t.size() - 1) + " vertices (at least 3 needed)");
            loop.clear();
            for (std::size_t c = 1; c < t.size(); ++c) {
                const std::string_view corner = t[c];
                const std::size_t slash = corner.find('/');
                std::int64_t index = 0;
                if (!detail::parseInteger(corner.substr(0, slash), index)) {
                    failRead(name, line, face + ": vertex " + quoted(corner) + " is not an index");
                }
                const std::int64_t count = std::int64_t(mesh.positions.size());
                const std::int64_t resolved = index < 0 ? count + index : index - 1;
                if (index == 0 || resolved < 0 || resolved >= count) {
                    failRead(name, line, face + ": vertex index " + std::to_string(index) + " is out of range (" +
                                             std::to_string(count) + " vertices so far)");
                }
                loop.push_back(std::uint32_t(resolved));
                // The normal index, if any (v//n or v/t/n).
                const std::size_t second = slash == std::string_view::npos ? slash : corner.find('/', slash + 1);
                std::int64_t n = -1;
                if (second != std::string_view::npos && second + 1 < corner.size()) {
                    std::int64_t nIndex = 0;
                    const std::int64_t nCount = std::int64_t(normals.size());
                    if (!detail::parseInteger(corner.substr(second + 1), nIndex)) {
                        failRead(name, line, face + ": normal " + quoted(corner) + " is not an index");
                    }
                    n = nIndex < 0 ? nCount + nIndex : nIndex - 1;
                    if (nIndex == 0 || n < 0 || n >= nCount) {
                        failRead(name, line, face + ": normal index " + std::to_string(nIndex) + " is out of range (" +
                                                 std::to_string(nCount) + " normals so far)");
                    }
                }
                std::int64_t& assigned = vertexNormal[std::size_t(resolved)];
                if (n < 0 || (assigned >= 0 && normals[std::size_t(assigned)] != normals[std::size_t(n)])) {
                    normalsUsable = false;
                }
                if (n >= 0) assigned = n;
            }
            for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
                mesh.indices.insert(mesh.indices.end(), {loop[0], loop[i], loop[i + 1]});
            }
        }
        if (mesh.positions.size() > std::numeric_limits<std::uint32_t>::max()) failRead(name, line, "too many vertices");
    }
    // Per-vertex normals only when every vertex has exactly one.
    if (normalsUsable && !normals.empty() && !mesh.indices.empty()) {
        mesh.normals.resize(mesh.positions.size());
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            if (vertexNormal[i] < 0) {
                mesh.normals.clear();
                break;
            }
            mesh.normals[i] = normals[std::size_t(vertexNormal[i])];
        }
    }
    return mesh;
}

// OFF, NOFF, COFF, CNOFF: counts, then one vertex and one face per line
// (values past the ones we read, such as colours, are ignored).
TriangleMesh parseOffText(std::string_view text, const std::string& name)
{
    detail::LineReader lines(text, '#');
    if (!lines.next()) failRead(name, 0, "empty OFF file");
    std::string_view keyword = lines.tokens()[0];
    const bool hasNormals = keyword == "NOFF" || keyword == "CNOFF";
    if (keyword != "OFF" && keyword != "NOFF" && keyword != "COFF" && keyword != "CNOFF") {
        failRead(name, lines.line(), "not an OFF file (first keyword " + quoted(keyword) + ")");
    }
    std::vector<std::string_view> counts(lines.tokens().begin() + 1, lines.tokens().end());
    if (counts.empty()) {
        if (!lines.next()) failRead(name, 0, "the file ends before the counts");
        counts = lines.tokens();
    }
    if (counts.size() == 1 && counts[0] == "BINARY") failRead(name, lines.line(), "binary OFF is not supported");
    std::int64_t vertexCount = 0, faceCount = 0;
    if (counts.size() < 2 || !detail::parseInteger(counts[0], vertexCount) || !detail::parseInteger(counts[1], faceCount) ||
        vertexCount < 0 || faceCount < 0) {
        failRead(name, lines.line(), "malformed counts line (want: vertices faces edges)");
    }
    // Each vertex line holds at least "x y z\n" (6 bytes), each face "3 a b c\n" (8).
    const std::uint64_t left = text.size() - lines.offset();
    if (std::uint64_t(vertexCount) > left / 6 || std::uint64_t(faceCount) > left / 8 ||
        std::uint64_t(vertexCount) * 6 + std::uint64_t(faceCount) * 8 > left + 1) {
        failRead(name, lines.line(), "the counts (" + std::to_string(vertexCount) + " vertices, " +
                                         std::to_string(faceCount) + " faces) need more than the " +
                                         std::to_string(left) + " bytes the file has left");
    }
    TriangleMesh mesh;
    mesh.positions.reserve(std::size_t(vertexCount));
    if (hasNormals) mesh.normals.reserve(std::size_t(vertexCount));
    for (std::int64_t v = 0; v < vertexCount; ++v) {
        const std::string vertex = "vertex " + std::to_string(v);
        if (!lines.next()) failRead(name, 0, "the file ends before " + vertex);
        const auto& t = lines.tokens();
        const std::size_t needed = hasNormals ? 6 : 3;
        if (t.size() < needed) failRead(name, lines.line(), vertex + ": fewer than " + std::to_string(needed) + " values");
        mesh.positions.emplace_back(finiteFloat(t[0], name, lines.line(), vertex + ": coordinate"),
                                    finiteFloat(t[1], name, lines.line(), vertex + ": coordinate"),
                                    finiteFloat(t[2], name, lines.line(), vertex + ": coordinate"));
        if (hasNormals) {
            mesh.normals.emplace_back(finiteFloat(t[3], name, lines.line(), vertex + ": normal"),
                                      finiteFloat(t[4], name, lines.line(), vertex + ": normal"),
                                      finiteFloat(t[5], name, lines.line(), vertex + ": normal"));
        }
    }
    std::vector<std::uint32_t> loop;
    for (std::int64_t f = 0; f < faceCount; ++f) {
        const std::string face = "face " + std::to_string(f);
        if (!lines.next()) failRead(name, 0, "the file ends before " + face);
        const auto& t = lines.tokens();
        std::int64_t n = 0;
        if (!detail::parseInteger(t[0], n)) failRead(name, lines.line(), face + ": count " + quoted(t[0]) + " is not an integer");
        if (n < 3) failRead(name, lines.line(), face + ": has " + std::to_string(n) + " vertices (at least 3 needed)");
        if (std::uint64_t(n) > t.size() - 1) {
            failRead(name, lines.line(), face + ": claims " + std::to_string(n) + " vertices but lists " + std::to_string(t.size() - 1));
        }
        loop.clear();
        for (std::int64_t i = 1; i <= n; ++i) {
            std::int64_t index = 0;
            if (!detail::parseInteger(t[std::size_t(i)], index)) {
                failRead(name, lines.line(), face + ": vertex " + quoted(t[std::size_t(i)]) + " is not an index");
            }
            if (index < 0 || index >= vertexCount) {
                failRead(name, lines.line(), face + ": vertex index " + std::to_string(index) + " is out of range (" +
                                                 std::to_string(vertexCount) + " vertices)");
            }
            loop.push_back(std::uint32_t(index));
        }
        for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
            mesh.indices.insert(mesh.indices.end(), {loop[0], loop[i], loop[i + 1]});
        }
    }
    return mesh;
}

// STL (binary or ASCII): corners equal to the bit are merged into one vertex,
// in order of first appearance.
class StlVertices
{
public:
    explicit StlVertices(TriangleMesh& mesh)
        : mMesh(mesh)
    {
    }

    void add(const glm::vec3& p)
    {
        const glm::vec3 q = p + glm::vec3(0.0f); // -0 and +0 are the same corner
        Key key;
        std::memcpy(key.data(), &q, sizeof(key));
        const auto [it, inserted] = mIndex.try_emplace(key, std::uint32_t(mMesh.positions.size()));
        if (inserted) mMesh.positions.push_back(q);
        mMesh.indices.push_back(it->second);
    }

private:
    using Key = std::array<std::uint32_t, 3>;
    struct Hash
    {
        std::size_t operator()(const Key& k) const
        {
            std::uint64_t h = 0xcbf29ce484222325ull;
            for (std::uint32_t v : k) h = (h ^ v) * 0x100000001b3ull;
            return std::size_t(h ^ (h >> 29));
        }
    };
    TriangleMesh& mMesh;
    std::unordered_map<Key, std::uint32_t, Hash> mIndex;
};

TriangleMesh parseStlBytes(std::string_view bytes, const std::string& name)
{
    TriangleMesh mesh;
    StlVertices vertices(mesh);
    std::uint32_t triangles = 0;
    if (bytes.size() >= 84) std::memcpy(&triangles, bytes.data() + 80, 4);
    const bool binary = bytes.size() >= 84 && bytes.size() == 84 + 50 * std::uint64_t(triangles);
    std::size_t first = bytes.find_first_not_of(" \t\r\n");
    const bool ascii = !binary && first != std::string_view::npos && bytes.substr(first, 5) == "solid";
    if (binary) {
        mesh.indices.reserve(std::size_t(triangles) * 3);
        for (std::uint32_t t = 0; t < triangles; ++t) {
            const char* record = bytes.data() + 84 + 50 * std::size_t(t);
            for (int c = 0; c < 3; ++c) {
                float p[3];
                std::memcpy(p, record + 12 + 12 * c, 12);
                for (float v : p) {
                    if (!std::isfinite(v)) {
                        failRead(name, 0, "triangle " + std::to_string(t) + ": a coordinate is not a finite number");
                    }
                }
                vertices.add({p[0], p[1], p[2]});
            }
        }
        return mesh;
    }
    if (!ascii) {
        if (bytes.size() >= 84) {
            failRead(name, 0, "binary STL header claims " + std::to_string(triangles) + " triangles (" +
                                  std::to_string(84 + 50 * std::uint64_t(triangles)) + " bytes) but the file has " +
                                  std::to_string(bytes.size()) + " bytes");
        }
        failRead(name, 0, "not an STL file (too short for binary, no 'solid' for ASCII)");
    }
    // ASCII: facet normal n n n / outer loop / vertex x y z (x3) / endloop / endfacet.
    detail::LineReader lines(bytes, '\0');
    lines.next(); // "solid [name]"
    std::uint64_t facet = 0;
    int corners = -1; // -1 outside a facet
    while (lines.next()) {
        const auto& t = lines.tokens();
        const int line = lines.line();
        if (t[0] == "endsolid") {
            if (corners != -1) failRead(name, line, "facet " + std::to_string(facet) + ": 'endsolid' inside a facet");
            return mesh;
        }
        if (t[0] == "facet") {
            if (corners != -1) failRead(name, line, "facet " + std::to_string(facet) + ": 'facet' inside a facet");
            corners = 0;
        } else if (t[0] == "vertex") {
            const std::string what = "facet " + std::to_string(facet) + ": coordinate";
            if (corners < 0 || corners >= 3) failRead(name, line, "facet " + std::to_string(facet) + ": unexpected 'vertex'");
            if (t.size() != 4) failRead(name, line, "facet " + std::to_string(facet) + ": a vertex needs 3 coordinates");
            vertices.add({finiteFloat(t[1], name, line, what), finiteFloat(t[2], name, line, what),
                          finiteFloat(t[3], name, line, what)});
            ++corners;
        } else if (t[0] == "endfacet") {
            if (corners != 3) failRead(name, line, "facet " + std::to_string(facet) + ": has " + std::to_string(std::max(corners, 0)) + " vertices, not 3");
            corners = -1;
            ++facet;
        } else if (t[0] != "outer" && t[0] != "endloop") {
            failRead(name, line, "unknown keyword " + quoted(t[0]));
        }
    }
    failRead(name, 0, "the file ends without 'endsolid'");
}

} // namespace

TriangleMesh parseObj(std::string_view bytes, const std::string& name)
{
    return parseObjText(bytes, name);
}

TriangleMesh parseOff(std::string_view bytes, const std::string& name)
{
    return parseOffText(bytes, name);
}

TriangleMesh parseStl(std::string_view bytes, const std::string& name)
{
    return parseStlBytes(bytes, name);
}

std::string meshFileExtensions()
{
    return ".glb, .ply, .obj, .stl, .off";
}

void checkMeshFileExtension(const std::filesystem::path& path)
{
    const std::string ext = lowerExtension(path);
    if (ext != ".glb" && ext != ".ply" && ext != ".obj" && ext != ".stl" && ext != ".off") {
        throw Error(ErrorKind::BadInput,
                    "cannot write mesh file '" + path.string() + "': unknown extension '" + ext + "' (use " +
                        meshFileExtensions() + ")",
                    detail::filePlace(path));
    }
}

void writeMeshFile(const TriangleMesh& mesh, const std::filesystem::path& path, const MeshFileOptions& fileOptions)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".glb") {
        GlbOptions glb;
        glb.name = fileOptions.name;
        return writeGlb(mesh, path, glb);
    }
    if (ext == ".ply") return writePly(mesh, path);
    checkMeshFileExtension(path);
    detail::OmMesh om;
    const bool hasNormals = detail::toOpenMesh(mesh, om);
    OpenMesh::IO::Options options;
    if (ext == ".stl") {
        options += OpenMesh::IO::Options::Binary;
    } else if (hasNormals) {
        options += OpenMesh::IO::Options::VertexNormal;
    }
    // Serialised in memory, then written with checked writes: OpenMesh's file
    // writers do not report a failed stream.
    std::ostringstream bytes;
    omlog().disable();
    // max_digits10 significant digits: every float reads back bit-identical
    // (OpenMesh's default of 6 merges nearby vertices into zero-area triangles).
    const bool ok = OpenMesh::IO::write_mesh(om, bytes, ext, options, std::numeric_limits<float>::max_digits10);
    omlog().enable();
    if (!ok || !bytes) {
        throw Error(ErrorKind::Internal, "cannot write mesh file '" + path.string() + "': OpenMesh failed",
                    {.file = path.string()});
    }
    writeFileAtomically(path, bytes.view());
}

TriangleMesh readMesh(const std::filesystem::path& path)
{
    const std::string ext = lowerExtension(path);
    if (ext == ".glb" || ext == ".gltf") {
        if (!std::filesystem::exists(path)) throw Error(ErrorKind::BadInput, "mesh file '" + path.string() + "' does not exist");
        return readGltf(path);
    }
    if (ext != ".ply" && ext != ".obj" && ext != ".off" && ext != ".stl") {
        throw Error(ErrorKind::BadInput,
                    "cannot read mesh file '" + path.string() + "': unknown extension '" + ext + "' (use " +
                        meshFileExtensions() + ")",
                    {.file = path.string()});
    }
    return parseMesh(detail::readWholeFile(path), ext, path.string());
}

TriangleMesh parseMesh(std::string_view bytes, const std::string& extension, const std::string& name)
{
    if (extension == ".ply") return parsePly(bytes, name);
    if (extension == ".obj") return parseObj(bytes, name);
    if (extension == ".off") return parseOff(bytes, name);
    if (extension == ".stl") return parseStl(bytes, name);
    if (extension == ".glb") return parseGlb(bytes, name);
    throw Error(ErrorKind::BadInput, name + ": unknown mesh format '" + extension + "'", {.file = name});
}

} // namespace strata::meshing
