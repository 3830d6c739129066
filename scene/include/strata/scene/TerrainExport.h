// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// `strata export-terrain`: a world as a game engine's terrain system
/// imports it (Unreal's Landscape, Unity's Terrain, Godot's terrain
/// plug-ins): per tile a heightmap of the top surface, a weight map per
/// material layer, a hole mask, and the surfaces no heightfield can hold
/// (caves, overhangs, arches) as glTF meshes in the same frame, plus
/// `terrain.json` with every number an artist types into the import
/// dialogs. See docs/export-terrain.md.
///
/// Tiles. The region's corner is snapped down to the voxel (to the bake's
/// coarsest cell when exporting a bake, so tile names match its tiles) and
/// cut into square tiles of `tileSize` metres over x and z; the far row and
/// column are whole tiles too (engines want equal tiles), reaching past the
/// region. Each tile spans the region's whole height. Neighbouring tiles
/// share their edge samples, which come from the same lattice points: the
/// same bits on both sides.
///
/// Heights are the level set's (world::extractTerrainTile()), resampled
/// bilinearly where the engine's grid is not the voxel lattice, then
/// quantised: value = round((height − base) / heightStep), one step being
/// exactly `heightStep` metres (a power of two by default, so every scale
/// the engines ask for is exact).
///
/// Frames (x, z Strata's horizontal axes, y up; engine units in brackets):
///  - unreal: image column → Unreal X = x, image row → Unreal Y = z, Z = y
///    (centimetres); a rotation, not a mirror.
///  - unity: image column c → Unity x = −x (columns run from the tile's
///    largest x down), image row → Unity z = z, y = y: the frame Unity's
///    glTF importers (glTFast, UnityGLTF) give the meshes by negating x.
///  - godot, raw: image column → x, image row → z, y up (Godot's glTF
///    frame, unchanged).
///
/// Files (all written atomically; NAME per engine: Unreal
/// "terrain_xX_yZ" (World Partition's tiled import), otherwise "X_Z"):
///  - heightmaps: unreal `heightmaps/NAME.png` (16-bit grey); unity
///    `heightmaps/NAME.raw` (16-bit little-endian); godot
///    `heightmaps/NAME.exr` (32-bit float metres) and `NAME.png` (16-bit);
///    raw `heightmaps/NAME.r16` (16-bit little-endian) and `NAME.exr`.
///  - weights: unreal `weights/LAYER/NAME.png` (8-bit grey, one per layer);
///    others `splat/NAME_K.png` (RGBA, layers 4K..4K+3). Every sample's
///    weights sum to exactly 255.
///  - `holes/NAME.png`: 8-bit grey, one pixel per heightmap cell
///    ((resolution − 1)²), 255 where the engine must cut its terrain.
///  - `meshes/NAME.glb`: the rest of the level set's surface (caves,
///    overhang undersides, every hole cell's surface), positions relative
///    to the tile corner, which is the node's translation; no file where a
///    tile has none.
///  - `terrain.json`: the export's identity, the import numbers per engine
///    and every tile's files.

#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {

enum class TerrainEngine
{
    Unreal,
    Unity,
    Godot,
    Raw,
};

/// "unreal", "unity", "godot", "raw".
const char* terrainEngineName(TerrainEngine engine);
/// Parses an engine name; throws strata::Error (BadInput) naming `flag`
/// and the accepted names.
TerrainEngine parseTerrainEngine(const std::string& name, const std::string& flag = "--engine");

struct TerrainExportOptions
{
    std::filesystem::path outputDir;
    TerrainEngine engine = TerrainEngine::Raw;
    /// Metres per tile side; 0: 252 voxels for Unreal (four components of
    /// 63 quads), 256 voxels otherwise; from a bake: the bake's.
    double tileSize = 0.0;
    /// Heightmap samples per tile side; 0: one per voxel (tile voxels + 1),
    /// raised to the engine's next legal size where that is not one (Unity:
    /// 2^n + 1 from 33 to 4097; Unreal: q·n + 1 for q in 7, 15, 31, 63, 127,
    /// 255). A size the engine does not accept is refused.
    int resolution = 0;
    /// "all", or indices and inclusive ranges ("7", "0-63", "3,7-9"); tile
    /// index = z·tilesX + x.
    std::string tiles = "all";
    /// Metres per 16-bit unit; 0: the smallest power of two that spans the
    /// region's height in 65535 units. A region taller than 65535 steps is
    /// refused with the numbers.
    double heightStep = 0.0;
    std::optional<std::uint64_t> seed; ///< overrides the scene's seed
    bool meshes = true;                ///< write meshes/NAME.glb
    int threads = 0;                   ///< tiles at once; 0 = all cores
    /// Memory budget per tile in bytes (0 = none): a tile whose lattice
    /// samples would exceed it is refused before anything runs.
    std::uint64_t maxMemoryBytes = 8ull << 30;
    /// Export over a folder whose terrain.json is another export's (another
    /// engine, scene, seed or setting): its tiles are left out of the new
    /// terrain.json (files of the same names are replaced, others stay).
    /// Without it such a folder is refused before anything is written.
    bool force = false;
};

/// What an export will do; checked, nothing written.
struct TerrainExportPlan
{
    TerrainEngine engine = TerrainEngine::Raw;
    double voxelSize = 1.0;
    std::int64_t tileVoxels = 256;
    double tileSize = 0.0;                  ///< metres
    int resolution = 0;                     ///< samples per tile side
    double spacing = 0.0;                   ///< metres between samples
    double heightStep = 0.0;                ///< metres per 16-bit unit
    double base = 0.0;                      ///< world height of value 0 (metres)
    std::array<std::int64_t, 3> minVoxel{}; ///< the tiles' corner (voxels)
    std::int64_t heightVoxels = 0;          ///< the tiles' height (voxels)
    int tilesX = 1, tilesZ = 1;
    std::vector<int> selected;      ///< tile indices, ascending
    std::vector<std::string> layers; ///< layer names: "base", then the [[layer]]s
    std::uint64_t seed = 0;
    std::uint64_t tileMemoryBytes = 0; ///< the lattice samples of one tile
    std::string tileName(int x, int z) const;
};

/// Checks the options against the scene and plans the export. `bake`,
/// when set, is the bake folder the scene came from (loadBakedScene()):
/// its tile size, corner snapping and seed are taken. Throws strata::Error
/// (BadInput) naming the flag and value: a tile size that is not a
/// positive multiple of the voxel size or holds more than 1024 voxels, a
/// resolution the engine does not accept, a height step that is not
/// positive or leaves the region's height beyond 65535 steps (the numbers
/// named), a tile selection out of range, a tile over the memory budget or
/// taller than 4096 voxels.
TerrainExportPlan planTerrainExport(const Scene& scene, const TerrainExportOptions& options,
                                    const std::optional<std::filesystem::path>& bake = std::nullopt);

struct TerrainExportSummary
{
    int tiles = 0;                  ///< tiles written
    std::uint64_t holeCells = 0;    ///< heightmap cells cut for caves and overhangs
    std::uint64_t meshTriangles = 0; ///< triangles in meshes/*.glb
    std::uint64_t clippedColumns = 0; ///< lattice columns with rock at the region's top
    double seconds = 0.0;
};

/// Writes the planned tiles and terrain.json into options.outputDir
/// (created), holding its lock. `observer` hears the stage "export" with
/// progress per tile and may interrupt (strata::Error, Interrupted:
/// finished tiles stay; terrain.json is written only by a complete run).
/// Throws strata::Error: Io naming a file that could not be written.
TerrainExportSummary exportTerrain(const Scene& scene, const TerrainExportOptions& options,
                                   const TerrainExportPlan& plan, PipelineObserver* observer = nullptr);

/// The legal heightmap sizes: Unity 2^n + 1 (33..4097); Unreal q·n + 1 for
/// quads per section q in {7, 15, 31, 63, 127, 255} and n sections (up to
/// 32 components of 2×2 sections per side); Godot and raw any size >= 2.
bool legalTerrainResolution(TerrainEngine engine, int samples);

} // namespace strata::scene
