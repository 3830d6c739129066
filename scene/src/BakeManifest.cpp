// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "BakeManifest.h"

#include <strata/Error.h>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace strata::scene::detail {

namespace {

using nlohmann::json;

json vec(const glm::dvec3& v) { return json::array({v.x, v.y, v.z}); }

json fileJson(const BakeFile& f) { return {{"path", f.path}, {"bytes", f.bytes}, {"sha256", f.sha256}}; }

/// Typed reads that name the manifest and the key on failure.
class Reader
{
public:
    explicit Reader(std::string path)
        : mPath(std::move(path))
    {
    }

    [[noreturn]] void fail(const std::string& key, const std::string& why) const
    {
        throw Error(ErrorKind::BadInput, "'" + mPath + "': " + key + ": " + why, {mPath, 0, key, ""});
    }

    const json& at(const json& j, const std::string& key) const
    {
        if (!j.is_object() || !j.contains(key)) fail(key, "missing");
        return j.at(key);
    }

    template <typename T>
    T get(const json& j, const std::string& key) const
    {
        try {
            return at(j, key).get<T>();
        } catch (const json::exception& e) {
            fail(key, std::string("wrong type: ") + e.what());
        }
    }

    glm::dvec3 vec3(const json& j, const std::string& key) const
    {
        const json& v = at(j, key);
        if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
            fail(key, "expected [x, y, z]");
        return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
    }

    std::optional<BakeFile> file(const json& j, const std::string& key) const
    {
        if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
        const json& f = j.at(key);
        BakeFile out{get<std::string>(f, "path"), get<std::uint64_t>(f, "bytes"), get<std::string>(f, "sha256")};
        // A manifest names files inside its own folder only.
        if (out.path.empty() || out.path.front() == '/' || out.path.find("..") != std::string::npos)
            fail(key + ".path", "'" + out.path + "' is not a path inside the bake folder");
        return out;
    }

private:
    std::string mPath;
};

} // namespace

std::vector<double> BakeManifest::geometricErrors() const
{
    std::vector<double> errors(std::size_t(std::max(lods, 1)), 0.0);
    for (const auto& [index, tile] : tiles)
        for (const TileLevelRecord& level : tile.levels)
            if (level.level > 0 && level.level < lods)
                errors[std::size_t(level.level)] = std::max(errors[std::size_t(level.level)], level.error);
    for (std::size_t l = 1; l < errors.size(); ++l) errors[l] = std::max(errors[l], errors[l - 1]);
    return errors;
}

BakeManifest manifestFor(const BakePlan& plan, const Scene& scene, bool grids)
{
    BakeManifest m;
    // A file's path made absolute, so the folder's scene resolves its
    // textures from anywhere; a name in angle brackets ("<default scene>",
    // a text scene from Python or a test) is not a path and stays as given
    // (made absolute it named the working directory, so the same scene
    // baked from two folders wrote two bake.json).
    const bool named = scene.source.size() >= 2 && scene.source.front() == '<' && scene.source.back() == '>';
    m.sceneSource = named ? scene.source : std::filesystem::absolute(scene.source).string();
    m.sceneHash = plan.sceneHash;
    m.seed = plan.seed;
    m.voxelSize = plan.voxelSize;
    m.tileSize = plan.tileSize;
    m.skirtDepth = plan.skirtDepth;
    m.lods = plan.lods;
    m.grids = grids;
    m.tileFormat = tileFormatName(plan.tileFormat);
    m.counts = plan.counts;
    for (int a = 0; a < 3; ++a) {
        m.min[a] = double(plan.minVoxel[a]) * plan.voxelSize;
        m.max[a] = double(plan.maxVoxel[a]) * plan.voxelSize;
    }
    m.georeference = plan.georeference;
    return m;
}

json recordJson(const TileRecord& t)
{
    json levels = json::array();
    for (const TileLevelRecord& l : t.levels) {
        json level = {{"level", l.level},       {"triangles", l.triangles}, {"skirt_triangles", l.skirtTriangles},
                      {"vertices", l.vertices}, {"error", l.error},         {"file", nullptr}};
        if (l.file) {
            level["file"] = fileJson(*l.file);
            level["bounds"] = {{"min", vec(l.min)}, {"max", vec(l.max)}};
        }
        levels.push_back(level);
    }
    return {{"index", t.index},
            {"cell", t.cell},
            {"name", t.name},
            {"box", {{"min", vec(t.boxMin)}, {"max", vec(t.boxMax)}}},
            {"levels", levels},
            {"grid", t.grid ? fileJson(*t.grid) : json(nullptr)}};
}

json headerJson(const BakeManifest& m)
{
    json out = {{"format", "strata-bake"},
            {"version", 1},
            {"scene", {{"source", m.sceneSource}, {"sha256", m.sceneHash}}},
            {"seed", m.seed},
            {"voxel_size", m.voxelSize},
            {"tile_size", m.tileSize},
            {"levels", m.lods},
            {"skirt_depth", m.skirtDepth},
            {"grids", m.grids},
            {"tile_format", m.tileFormat},
            {"tiles_per_axis", m.counts},
            {"tile_count", m.counts[0] * m.counts[1] * m.counts[2]},
            {"bounds", {{"min", vec(m.min)}, {"max", vec(m.max)}}}};
    // Only when given: bakes without one keep their bytes.
    if (m.georeference)
        out["georeference"] = {{"latitude", m.georeference->latitude},
                               {"longitude", m.georeference->longitude},
                               {"height", m.georeference->height}};
    return out;
}

bool sameBake(const BakeManifest& a, const BakeManifest& b)
{
    json x = headerJson(a), y = headerJson(b);
    // Where the world lies and where its scene file was read from are not
    // its identity (the scene's hash is).
    for (json* header : {&x, &y}) {
        header->erase("georeference");
        header->at("scene").erase("source");
    }
    return x == y;
}

json toJson(const BakeManifest& m)
{
    json out = headerJson(m);
    out["geometric_error"] = m.geometricErrors();
    json tiles = json::array();
    for (const auto& [index, t] : m.tiles) tiles.push_back(recordJson(t));
    out["tiles"] = tiles;
    return out;
}

namespace {

TileRecord readRecord(const Reader& r, const json& t)
{
    TileRecord tile;
    tile.index = r.get<int>(t, "index");
    tile.cell = r.get<std::array<int, 3>>(t, "cell");
    tile.name = r.get<std::string>(t, "name");
    tile.boxMin = r.vec3(r.at(t, "box"), "min");
    tile.boxMax = r.vec3(r.at(t, "box"), "max");
    tile.grid = r.file(t, "grid");
    const json& levels = r.at(t, "levels");
    if (!levels.is_array()) r.fail("levels", "expected an array");
    for (const json& l : levels) {
        TileLevelRecord level;
        level.level = r.get<int>(l, "level");
        level.triangles = r.get<std::uint64_t>(l, "triangles");
        level.skirtTriangles = r.get<std::uint64_t>(l, "skirt_triangles");
        level.vertices = r.get<std::uint64_t>(l, "vertices");
        level.error = r.get<double>(l, "error");
        level.file = r.file(l, "file");
        if (level.file) {
            level.min = r.vec3(r.at(l, "bounds"), "min");
            level.max = r.vec3(r.at(l, "bounds"), "max");
        }
        tile.levels.push_back(level);
    }
    return tile;
}

BakeManifest readHeader(const Reader& r, const json& j)
{
    if (r.get<std::string>(j, "format") != "strata-bake") r.fail("format", "not a Strata bake file");
    if (r.get<int>(j, "version") != 1) r.fail("version", "unsupported version");
    BakeManifest m;
    m.sceneSource = r.get<std::string>(r.at(j, "scene"), "source");
    m.sceneHash = r.get<std::string>(r.at(j, "scene"), "sha256");
    m.seed = r.get<std::uint64_t>(j, "seed");
    m.voxelSize = r.get<double>(j, "voxel_size");
    m.tileSize = r.get<double>(j, "tile_size");
    m.lods = r.get<int>(j, "levels");
    m.skirtDepth = r.get<double>(j, "skirt_depth");
    m.grids = r.get<bool>(j, "grids");
    // Bakes from before compact tiles have no key: their tiles are plain.
    m.tileFormat = j.contains("tile_format") ? r.get<std::string>(j, "tile_format") : std::string("plain");
    if (m.tileFormat != "plain" && m.tileFormat != "meshopt") r.fail("tile_format", "not plain or meshopt");
    m.counts = r.get<std::array<int, 3>>(j, "tiles_per_axis");
    m.min = r.vec3(r.at(j, "bounds"), "min");
    m.max = r.vec3(r.at(j, "bounds"), "max");
    if (j.contains("georeference") && !j.at("georeference").is_null()) {
        const json& g = j.at("georeference");
        m.georeference = Georeference{r.get<double>(g, "latitude"), r.get<double>(g, "longitude"), r.get<double>(g, "height")};
        try {
            checkGeoreference(*m.georeference, "georeference");
        } catch (const Error& e) {
            r.fail("georeference", e.what());
        }
    }
    if (m.lods < 1 || m.lods > 8) r.fail("levels", "out of range");
    if (m.counts[0] < 1 || m.counts[1] < 1 || m.counts[2] < 1 ||
        std::int64_t(m.counts[0]) * m.counts[1] * m.counts[2] > (1 << 24))
        r.fail("tiles_per_axis", "out of range");
    return m;
}

json parseJsonFile(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in) throw Error(ErrorKind::BadInput, "cannot read '" + path.string() + "'", {path.string()});
    try {
        return json::parse(in);
    } catch (const json::exception& e) {
        throw Error(ErrorKind::BadInput, "'" + path.string() + "' is not valid JSON: " + e.what(), {path.string()});
    }
}

} // namespace

BakeManifest manifestFromJson(const json& j, const std::string& path)
{
    const Reader r(path);
    BakeManifest m = readHeader(r, j);
    const json& tiles = r.at(j, "tiles");
    if (!tiles.is_array()) r.fail("tiles", "expected an array");
    for (const json& t : tiles) {
        TileRecord tile = readRecord(r, t);
        if (tile.index < 0 || tile.index >= m.counts[0] * m.counts[1] * m.counts[2])
            r.fail("tiles.index", std::to_string(tile.index) + " is out of range");
        m.tiles[tile.index] = tile;
    }
    return m;
}

std::optional<BakeManifest> readBakeHeader(const std::filesystem::path& dir)
{
    const std::filesystem::path path = dir / "bake.json";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    return readHeader(Reader(path.string()), parseJsonFile(path));
}

std::optional<TileRecord> readRecord(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    return readRecord(Reader(path.string()), parseJsonFile(path));
}

std::filesystem::path recordPath(const std::filesystem::path& dir, int index)
{
    return dir / "records" / (std::to_string(index) + ".json");
}

std::optional<BakeManifest> readManifest(const std::filesystem::path& dir)
{
    const std::filesystem::path path = dir / "manifest.json";
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return std::nullopt;
    return manifestFromJson(parseJsonFile(path), path.string());
}

} // namespace strata::scene::detail
