// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: the bake's manifest.json as a value, to and from JSON, and the
// 3D Tiles tileset built from it.

#include <strata/scene/Bake.h>

#include <nlohmann/json.hpp>

#include <glm/vec3.hpp>

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene::detail {

/// One written file: path relative to the bake folder, size, SHA-256.
struct BakeFile
{
    std::string path;
    std::uint64_t bytes = 0;
    std::string sha256;
};

struct TileLevelRecord
{
    int level = 0;
    std::optional<BakeFile> file; ///< none when the level has no surface in the tile
    std::uint64_t triangles = 0, skirtTriangles = 0, vertices = 0;
    double error = 0.0;            ///< measured against level 0: two-sided Hausdorff distance (metres)
    glm::dvec3 min{0.0}, max{0.0}; ///< bounds of surface and skirt (metres); valid with a file
};

struct TileRecord
{
    int index = 0;
    std::array<int, 3> cell{0, 0, 0};
    std::string name;
    glm::dvec3 boxMin{0.0}, boxMax{0.0}; ///< the tile's box (metres)
    std::vector<TileLevelRecord> levels;
    std::optional<BakeFile> grid;
};

struct BakeManifest
{
    std::string sceneSource, sceneHash;
    std::uint64_t seed = 0;
    double voxelSize = 0.0, tileSize = 0.0, skirtDepth = 0.0;
    int lods = 0;
    bool grids = true;
    std::string tileFormat = "meshopt"; ///< "plain" or "meshopt" (tileFormatName())
    std::array<int, 3> counts{1, 1, 1};
    glm::dvec3 min{0.0}, max{0.0}; ///< the baked box (metres)
    /// The tileset's root transform is east-north-up here; not part of the
    /// bake's identity (sameBake()).
    std::optional<Georeference> georeference;
    std::map<int, TileRecord> tiles;

    /// Per level: the largest measured error over the tiles, made
    /// non-decreasing with the level; level 0 is 0 (the finest there is).
    std::vector<double> geometricErrors() const;
};

/// SHA-256 of the scene text and of the contents of the files its terrain
/// reads (Scene::inputFiles).
std::string sceneHash(const Scene& scene);

BakeManifest manifestFor(const BakePlan& plan, const Scene& scene, bool grids);
/// The bake's identity (every field but the tiles): DIR/bake.json, written
/// by every run and worker with the same bytes.
nlohmann::json headerJson(const BakeManifest& manifest);
/// Whether two headers describe the same tiles (every field of headerJson()
/// but the georeference, which changes only the tileset).
bool sameBake(const BakeManifest& a, const BakeManifest& b);
/// One tile's record: DIR/records/INDEX.json, written after its files.
nlohmann::json recordJson(const TileRecord& tile);
/// The header, the per-level errors and every tile: DIR/manifest.json.
nlohmann::json toJson(const BakeManifest& manifest);
/// Throws strata::Error (BadInput) naming `path` and the key when the JSON
/// is not a manifest.
BakeManifest manifestFromJson(const nlohmann::json& json, const std::string& path);
/// A bake's manifest, or nothing when `dir` has none.
std::optional<BakeManifest> readManifest(const std::filesystem::path& dir);
/// DIR/bake.json (no tiles), or nothing when `dir` has none.
std::optional<BakeManifest> readBakeHeader(const std::filesystem::path& dir);
/// A tile's record file, or nothing when it does not exist. Throws
/// strata::Error (BadInput) naming the file when it is not a record.
std::optional<TileRecord> readRecord(const std::filesystem::path& path);
std::filesystem::path recordPath(const std::filesystem::path& dir, int index);

/// The OGC 3D Tiles 1.1 tileset of the manifest's tiles (see Tileset.cpp).
nlohmann::json makeTileset(const BakeManifest& manifest);

} // namespace strata::scene::detail
