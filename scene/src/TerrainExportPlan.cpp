// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Planning an engine terrain export: the engines' legal sizes, the tile
// grid, the height quantisation, the checks (TerrainExport.h).

#include <strata/scene/TerrainExport.h>

#include "BakeManifest.h"
#include "TileGrid.h"

#include <strata/Error.h>
#include <strata/IntegerMath.h>
#include <strata/Format.h>
#include <strata/world/TerrainTile.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace strata::scene {

namespace {

constexpr std::int64_t MAX_HEIGHT_VOXELS = 4096;
constexpr int UNREAL_QUADS[] = {7, 15, 31, 63, 127, 255};
constexpr int UNREAL_MAX_SECTIONS = 64; // 32 components of 2 × 2 sections per side
constexpr double MAX_UNITS = 65535.0;

[[noreturn]] void badFlag(const std::string& flag, const std::string& value, const std::string& why)
{
    throw Error(ErrorKind::BadInput, flag + " " + value + ": " + why, {"", 0, flag, value});
}


std::string gib(std::uint64_t bytes) { return formatNumber(double(bytes) / double(1ull << 30)) + " GiB"; }

int nextLegalResolution(TerrainEngine engine, int samples)
{
    for (int n = std::max(samples, 2); n <= 1 << 16; ++n)
        if (legalTerrainResolution(engine, n)) return n;
    return 0;
}

std::string legalSizesText(TerrainEngine engine)
{
    switch (engine) {
    case TerrainEngine::Unity: return "Unity takes 2^n + 1 samples per side, 33 to 4097";
    case TerrainEngine::Unreal:
        return "Unreal takes q·n + 1 samples per side, q quads per section in 7, 15, 31, 63, 127, 255 and n up to 64 "
               "sections (e.g. 253, 505, 1009, 2017, 4033, 8129)";
    default: return "at least 2 samples per side";
    }
}

} // namespace

const char* terrainEngineName(TerrainEngine engine)
{
    switch (engine) {
    case TerrainEngine::Unreal: return "unreal";
    case TerrainEngine::Unity: return "unity";
    case TerrainEngine::Godot: return "godot";
    case TerrainEngine::Raw: return "raw";
    }
    return "raw";
}

TerrainEngine parseTerrainEngine(const std::string& name, const std::string& flag)
{
    for (TerrainEngine e : {TerrainEngine::Unreal, TerrainEngine::Unity, TerrainEngine::Godot, TerrainEngine::Raw})
        if (name == terrainEngineName(e)) return e;
    badFlag(flag, name, "unknown engine; expected unreal, unity, godot or raw");
}

bool legalTerrainResolution(TerrainEngine engine, int samples)
{
    if (samples < 2) return false;
    const int quads = samples - 1;
    switch (engine) {
    case TerrainEngine::Unity: return samples >= 33 && samples <= 4097 && (quads & (quads - 1)) == 0;
    case TerrainEngine::Unreal:
        for (int q : UNREAL_QUADS)
            if (quads % q == 0 && quads / q <= UNREAL_MAX_SECTIONS) return true;
        return false;
    default: return samples <= (1 << 16);
    }
}

std::string TerrainExportPlan::tileName(int x, int z) const
{
    if (engine == TerrainEngine::Unreal) return "terrain_x" + std::to_string(x) + "_y" + std::to_string(z);
    return std::to_string(x) + "_" + std::to_string(z);
}

TerrainExportPlan planTerrainExport(const Scene& scene, const TerrainExportOptions& options,
                                    const std::optional<std::filesystem::path>& bake)
{
    TerrainExportPlan plan;
    plan.engine = options.engine;
    plan.voxelSize = scene.voxelSize;

    // The tile grid: the bake's when exporting one (its corner snapping and
    // tile size, so tile names match), else snapped to the voxel.
    double tileSize = options.tileSize;
    int lods = 1;
    std::optional<std::uint64_t> seed = options.seed;
    if (bake) {
        const std::optional<detail::BakeManifest> header = detail::readBakeHeader(*bake);
        if (!header)
            throw Error(ErrorKind::BadInput, "'" + bake->string() + "' holds no bake.json: not a bake folder",
                        {bake->string()});
        if (options.tileSize > 0.0 && std::abs(options.tileSize - header->tileSize) > 1e-9 * header->tileSize)
            badFlag("--tile-size", formatNumber(options.tileSize),
                    "differs from the bake's tile size " + formatNumber(header->tileSize) + " m");
        tileSize = header->tileSize;
        lods = header->lods;
        if (!seed) seed = header->seed;
    } else if (tileSize <= 0.0) {
        tileSize = double(options.engine == TerrainEngine::Unreal ? 252 : 256) * scene.voxelSize;
    }
    plan.seed = seed.value_or(scene.terrain.seed);
    const double v = scene.voxelSize;
    const std::string shownSize = formatNumber(tileSize);
    const detail::TileGrid grid = detail::planTileGrid(scene, tileSize, lods);
    plan.tileVoxels = grid.tileVoxels;
    plan.tileSize = grid.tileSize;
    plan.minVoxel = grid.minVoxel;
    const std::array<std::int64_t, 3> maxVoxel = grid.maxVoxel;
    plan.heightVoxels = std::max<std::int64_t>(maxVoxel[1] - plan.minVoxel[1], 1);
    if (plan.heightVoxels > MAX_HEIGHT_VOXELS)
        throw Error(ErrorKind::BadInput,
                    "the region is " + formatNumber(double(plan.heightVoxels) * v) + " m (" +
                        std::to_string(plan.heightVoxels) + " voxels) tall; an engine terrain tile spans at most " +
                        std::to_string(MAX_HEIGHT_VOXELS) + " voxels up: lower [region] or raise voxel_size",
                    {scene.source, 0, "region"});
    // Whole tiles over x and z (engines want equal tiles).
    std::int64_t total = 1;
    const auto tilesAlong = [&](int a) {
        return detail::tilesAlong(std::max<std::int64_t>(maxVoxel[a] - plan.minVoxel[a], 1), plan.tileVoxels, total,
                                  shownSize);
    };
    plan.tilesX = tilesAlong(0);
    plan.tilesZ = tilesAlong(2);
    plan.selected = detail::parseTileSelection(options.tiles, plan.tilesX * plan.tilesZ);

    // Samples per tile side.
    const int lattice = int(plan.tileVoxels) + 1;
    if (options.resolution != 0) {
        if (!legalTerrainResolution(options.engine, options.resolution))
            badFlag("--resolution", std::to_string(options.resolution),
                    std::string("is not a size ") + terrainEngineName(options.engine) + " accepts: " +
                        legalSizesText(options.engine));
        plan.resolution = options.resolution;
    } else {
        plan.resolution = nextLegalResolution(options.engine, lattice);
        if (plan.resolution == 0)
            badFlag("--tile-size", formatNumber(plan.tileSize),
                    "no heightmap size at or above " + std::to_string(lattice) + " samples fits: " +
                        legalSizesText(options.engine) + "; give --resolution");
    }
    plan.spacing = plan.tileSize / double(plan.resolution - 1);

    // Height quantisation: the region's height in 16-bit units.
    plan.base = double(plan.minVoxel[1]) * v;
    const double span = double(plan.heightVoxels) * scene.voxelSize;
    if (options.heightStep != 0.0) {
        if (!(options.heightStep > 0.0) || !std::isfinite(options.heightStep))
            badFlag("--height-step", formatNumber(options.heightStep), "must be a positive number of metres");
        if (span / options.heightStep > MAX_UNITS)
            badFlag("--height-step", formatNumber(options.heightStep),
                    "the region is " + formatNumber(span) + " m tall, " + formatNumber(span / options.heightStep) +
                        " steps of " + formatNumber(options.heightStep) + " m; 16 bits hold 65535: give a step of at least " +
                        formatNumber(span / MAX_UNITS) + " m, or lower [region]");
        plan.heightStep = options.heightStep;
    } else {
        // The smallest power of two >= span / MAX_UNITS, exactly: q = m·2^e
        // with m in [½, 1), so 2^(e − 1) when m is ½ (q a power of two), else 2^e.
        int e = 0;
        const double m = std::frexp(std::max(span, 1e-300) / MAX_UNITS, &e);
        plan.heightStep = std::ldexp(1.0, m == 0.5 ? e - 1 : e);
        while (span / plan.heightStep > MAX_UNITS) plan.heightStep *= 2.0;
    }

    plan.layers.push_back("base");
    for (std::size_t i = 0; i < scene.material.layers.size(); ++i) {
        std::string name = scene.material.layers[i].material.name;
        if (name.empty() || name == "material") name = "layer" + std::to_string(i + 1);
        std::string file; // a file and folder name: letters, digits, '_' and '-'
        for (char c : name)
            if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-') file += c;
            else if (c != '[' && c != ']') file += '_';
        if (std::find(plan.layers.begin(), plan.layers.end(), file) != plan.layers.end() || file.empty())
            file += "_" + std::to_string(i + 1);
        plan.layers.push_back(file);
    }

    world::TileBox box;
    box.size = {plan.tileVoxels, plan.heightVoxels, plan.tileVoxels};
    plan.tileMemoryBytes = world::terrainTileBytes(box);
    if (options.maxMemoryBytes > 0 && plan.tileMemoryBytes > options.maxMemoryBytes)
        badFlag("--max-memory", gib(options.maxMemoryBytes),
                "one tile's lattice samples take " + gib(plan.tileMemoryBytes) +
                    ": lower --tile-size or [region]'s height, or raise --max-memory");
    return plan;
}

} // namespace strata::scene
