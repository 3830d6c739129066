// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `strata bake`: a scene's region cut into tiles, each meshed at several
/// levels of detail and written as glTF, with a manifest, an OGC 3D Tiles
/// 1.1 tileset and (optionally) each tile's level-0 grid.
///
/// Tiles. The region's corner is snapped down to the coarsest level's cell
/// (2^(lods−1) voxels) and its far corner up; the box between is cut into
/// tiles of `tileSize` metres over x and z (the last row and column
/// shorter where the region is not a whole number of tiles) and into slabs
/// of `tileSize` over y where the region is taller than one tile. Tile
/// index i = (y·nz + z)·nx + x. A tile is a pure function of the scene and
/// its index (world::meshTile(): the field sampled on the voxel lattice,
/// meshed with the World's dual mesher at each level, clipped exactly to
/// the tile's box, skirts on faces with a neighbour), so a tile baked alone,
/// in a full bake, or on any thread count is the same bytes.
///
/// Files (all written atomically):
/// - `tiles/L/X_Z.glb` (`X_Y_Z` when there are several slabs): level L of
///   the tile, positions relative to the tile's corner (the node's
///   translation, double), normals, uint16 indices where they fit; two
///   primitives, the surface and the skirt (material "strata-skirt",
///   one-sided, facing out of the tile, with the surface's normals). A
///   tile with no surface at a level has no file.
///   By default compact (BakeOptions::tileFormat): 16-bit positions on a
///   grid every tile shares, octahedral normals, meshopt-compressed
///   (meshing/GltfCompact.h); readGltf() reads both forms.
/// - `grids/X_Z.vdb`: the tile's level-0 narrow-band level set (open box).
/// - `records/I.json`: tile I's record (its files' paths, sizes and
///   SHA-256, triangles, bounds, measured error), written after its files.
/// - `bake.json`: the bake's identity (scene hash, seed, settings), and
///   `scene.toml`, the scene; the same bytes from every run and worker.
/// - `provenance/I.json` (workers only): the host, CPU architecture and
///   scheduler task that baked tile I. A log beside the bake, not part of
///   it: finalizeBake() reports it and checks nothing by it.
/// - `manifest.json`: bake.json plus every tile's record and the per-level
///   geometric errors; `tileset.json`: 3D Tiles 1.1 (Tileset.cpp). Written
///   by a single bake, or by finalizeBake() after workers.
///
/// Resume. A bake into a folder of the same bake (bake.json: scene hash,
/// seed and settings) keeps every selected tile whose record's files match
/// (sizes and SHA-256) and redoes the rest; another bake's folder is
/// refused unless `force`.
///
/// Workers (a Slurm job array, a Kubernetes Indexed Job): `worker` bakes
/// its selection without the folder lock and without the manifest, so many
/// processes share one folder, each writing only its own tiles;
/// finalizeBake() then checks every tile and writes manifest and tileset.

#include <strata/scene/Georeference.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>

#include <strata/world/TileMesh.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {

/// How tile .glb files are stored (docs/bake.md, "Tile format"): Plain
/// float positions and normals; Meshopt (the default) KHR_mesh_quantization
/// and EXT_meshopt_compression (meshing/GltfCompact.h), 16-bit positions on
/// a grid shared by every tile of the bake, octahedral normals.
enum class TileFormat
{
    Plain,
    Meshopt,
};

/// "plain" or "meshopt".
const char* tileFormatName(TileFormat format);

/// Ascending tile indices as ranges: {3, 7, 8, 9, 12} → "3, 7-9, 12" with
/// separator ", " (the form --tiles takes with ",").
std::string indexRanges(const std::vector<int>& indices, const char* separator);

struct BakeOptions
{
    std::filesystem::path outputDir;
    double tileSize = 0.0; ///< metres; 0 = 256 voxels
    int lods = 3;          ///< levels of detail, 1..8: level l has cells of 2^l voxels
    /// Which tiles: "all", or indices and inclusive ranges separated by
    /// commas ("7", "0-63", "3,7-9").
    std::string tiles = "all";
    /// A worker of a scheduler's array: no lock, no manifest (finalizeBake()).
    bool worker = false;
    bool grids = true;                 ///< write grids/X_Z.vdb
    bool force = false;                ///< bake over another scene's bake
    std::optional<std::uint64_t> seed; ///< overrides the scene's seed
    int threads = 0;                   ///< tiles baked at once; 0 = all cores
    /// Memory budget per tile in bytes (0 = none): a tile whose sample
    /// arrays and grid estimate exceed it is refused before anything runs.
    std::uint64_t maxMemoryBytes = 8ull << 30;
    /// Skirt depth in metres; 0 = two cells of the coarsest level.
    double skirtDepth = 0.0;
    TileFormat tileFormat = TileFormat::Meshopt; ///< part of the bake's identity
    /// Where the world lies on the Earth, "LAT,LON,HEIGHT" (parseGeoreference());
    /// empty: where the scene's georeferenced DEM puts it (Scene::georeference),
    /// else nowhere (the tileset has no root transform); "none": nowhere,
    /// whatever the scene says. Not part of the
    /// bake's identity: a rerun with another point keeps the tiles and
    /// rewrites the tileset.
    std::string georeference;
};

/// One tile of a plan.
struct BakeTile
{
    int index = 0;
    std::array<int, 3> cell{0, 0, 0}; ///< x, y, z position in the tile grid
    world::TileBox box;               ///< voxels; neighbourFaces set
    std::string name;                 ///< "X_Z" or "X_Y_Z"
};

/// Where the tiles are and what the bake will do; checked, nothing written.
struct BakePlan
{
    double voxelSize = 1.0;
    double tileSize = 0.0; ///< metres
    int lods = 1;
    std::uint64_t seed = 0;
    std::string sceneHash;                  ///< SHA-256 of the scene text and its heightmaps' contents
    std::array<std::int64_t, 3> minVoxel{}; ///< the snapped region corner (voxels)
    std::array<std::int64_t, 3> maxVoxel{}; ///< the snapped far corner (voxels)
    std::array<int, 3> counts{1, 1, 1};     ///< tiles per axis
    double skirtDepth = 0.0;                ///< metres
    TileFormat tileFormat = TileFormat::Meshopt;
    std::optional<Georeference> georeference; ///< the tileset's root transform (east-north-up there)
    std::vector<int> selected;              ///< the indices to bake, ascending
    std::uint64_t tileMemoryBytes = 0;      ///< estimated peak per tile
    int tileCount() const { return counts[0] * counts[1] * counts[2]; }
    BakeTile tile(int index) const;
};

/// Checks the options against the scene and plans the tiles. Throws
/// strata::Error (BadInput) naming the flag and value: a tile size that is
/// not a positive multiple of the coarsest cell (voxelSize · 2^(lods−1)) or
/// holds more than 1024 voxels, a region smaller than one tile over x or z,
/// `lods` out of range, a tile selection that does not parse or is out of
/// range (naming the count), a tile over the memory budget, a
/// georeference that does not parse or is out of range.
/// `options.tiles` is parsed against the tile count.
BakePlan planBake(const Scene& scene, const BakeOptions& options);

/// Tiles one machine baked (from the workers' provenance files).
struct BakeHostTiles
{
    std::string host; ///< the machine's host name
    std::string arch; ///< the CPU architecture of the strata build: "x86_64", "aarch64", ...
    std::vector<int> tiles;
};

/// What a bake did.
struct BakeSummary
{
    int tiles = 0;   ///< tiles in the world
    int baked = 0;   ///< tiles made by this run
    int kept = 0;    ///< selected tiles whose files matched the manifest
    int missing = 0; ///< tiles of the world not baked yet (other selections)
    std::vector<std::uint64_t> trianglesPerLevel;
    std::vector<std::uint64_t> filesPerLevel, bytesPerLevel;
    std::vector<double> errorPerLevel; ///< the tileset's geometric error per level (metres)
    /// finalizeBake(): which machine baked which tile, from the files
    /// workers write to provenance/ (a log beside the bake, not part of
    /// it: tiles are the same bytes whoever baked them). Tiles whose file
    /// is missing come last, as host "unknown" (arch "no provenance file").
    std::vector<BakeHostTiles> bakedBy;
    double seconds = 0.0;
};

/// Bakes the selected tiles of `plan` (tiles in parallel, each a pure
/// function of the scene and its index), then (unless options.worker)
/// rewrites manifest.json and tileset.json from every tile present. `observer` hears the stage "bake"
/// with progress per tile and may interrupt (strata::Error, Interrupted:
/// finished tiles stay, the manifest is written for them). Holds the
/// output folder's lock. Throws strata::Error: BadInput for another bake's
/// folder (both hashes named) without `force`, Io naming a file that could
/// not be written.
BakeSummary bake(const Scene& scene, const BakeOptions& options, const BakePlan& plan,
                 PipelineObserver* observer = nullptr);

/// After the workers: checks every tile of the bake in `dir` against its
/// record (sizes and SHA-256), removes temporaries a killed worker left, and
/// writes manifest.json and tileset.json (the same bytes as a single bake's,
/// and the same bytes when run twice). Throws strata::Error: BadInput when
/// `dir` is not a bake folder; Io naming the missing or damaged tiles by
/// index, with the command that bakes just them (nothing written then).
BakeSummary finalizeBake(const std::filesystem::path& dir, PipelineObserver* observer = nullptr);

/// One tile baked in memory (nothing written) to estimate a bake's cost:
/// the middle column's lowest slab with a surface.
struct BakeSample
{
    int index = 0;
    double seconds = 0.0;
    std::uint64_t triangles = 0; ///< all levels
    std::uint64_t bytes = 0;     ///< its .glb files, all levels
};
BakeSample sampleBakeTile(const Scene& scene, const BakeOptions& options, const BakePlan& plan);

/// A whole-world snapshot from a bake folder: for each tile the coarsest
/// level whose geometric error (the tile's own measured error, made
/// non-decreasing with the level), projected from the camera, stays within
/// `maxScreenError` pixels (the 3D Tiles rule), merged and rendered as
/// renderSnapshots() does. The scene comes from `scene` (its material,
/// lighting and camera); the camera frames the whole world.
struct WorldSnapshotOptions
{
    SnapshotRequest request;
    std::optional<int> width, height;
    double maxScreenError = 2.0; ///< pixels
};

struct WorldSnapshotStats
{
    std::vector<int> tilesPerLevel; ///< tiles drawn at each level
    std::uint64_t triangles = 0;
    RenderStats render;
};

/// Reads DIR/manifest.json and the chosen tiles; throws strata::Error
/// (BadInput) naming a missing or damaged file.
WorldSnapshotStats renderBakedWorld(const Scene& scene, const std::filesystem::path& bakeDir,
                                    const WorldSnapshotOptions& options, render::GlContext* context,
                                    const std::function<void(const render::Image& image)>& sink);

/// The scene a bake folder was made from: DIR/scene.toml (a copy the bake
/// writes), parsed with the original source name for messages.
Scene loadBakedScene(const std::filesystem::path& bakeDir);

} // namespace strata::scene
