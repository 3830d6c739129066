// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Engine terrain export, per tile: heights from the level set, weights from
// the layer rules, holes, the remainder mesh; then the files of each engine
// and terrain.json (TerrainExport.h).

#include <strata/scene/TerrainExport.h>

#include "BakeManifest.h"
#include "LayerMaskSources.h"
#include "TileWorkers.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/IntegerMath.h>
#include <strata/OutputLock.h>
#include <strata/Stopwatch.h>
#include <strata/meshing/GltfIO.h>
#include <strata/render/DataImage.h>
#include <strata/render/LayerCoverage.h>
#include <strata/world/TerrainTile.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>

namespace strata::scene {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The tile's heights at the engine's samples (rows along z, columns along
/// x, both ascending), the sample positions in lattice units computed from
/// integers.
std::vector<double> engineHeights(const world::TerrainTile& tile, const TerrainExportPlan& plan)
{
    const int n = plan.resolution;
    std::vector<double> out(std::size_t(n) * n);
    const auto lattice = [&](int index) { return double(std::int64_t(index) * plan.tileVoxels) / double(n - 1); };
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) out[std::size_t(r) * n + c] = world::latticeHeight(tile, lattice(c), lattice(r));
    return out;
}

/// The field's unit gradient at p by central differences `e` apart (up
/// where it vanishes), and its length.
glm::dvec3 gradient(const terrain::DensityField& field, const glm::dvec3& p, double e, double* length)
{
    const glm::dvec3 g{field.density(p + glm::dvec3(e, 0, 0)) - field.density(p - glm::dvec3(e, 0, 0)),
                       field.density(p + glm::dvec3(0, e, 0)) - field.density(p - glm::dvec3(0, e, 0)),
                       field.density(p + glm::dvec3(0, 0, e)) - field.density(p - glm::dvec3(0, 0, e))};
    const double len = glm::length(g) / (2.0 * e);
    *length = len;
    return len > 0.0 && std::isfinite(len) ? g / (len * 2.0 * e) : glm::dvec3(0.0, 1.0, 0.0);
}

/// Weights in 1/255 that sum to exactly 255: floors, then the remainder to
/// the largest fractions (ties to the lower layer).
void quantiseWeights(const float* shares, int count, std::uint8_t* out)
{
    int sum = 0;
    float fraction[render::MAX_MATERIAL_LAYERS];
    for (int i = 0; i < count; ++i) {
        const float w = std::clamp(shares[i], 0.0f, 1.0f) * 255.0f;
        out[i] = floorToInt<std::uint8_t>(w);
        fraction[i] = w - float(out[i]);
        sum += out[i];
    }
    for (int left = 255 - sum; left > 0; --left) {
        int best = 0;
        for (int i = 1; i < count; ++i)
            if (fraction[i] > fraction[best]) best = i;
        ++out[best];
        fraction[best] = -1.0f;
    }
}

struct TileMaps
{
    std::vector<double> heights;            ///< resolution², rows along z
    std::vector<std::uint8_t> weights;      ///< weightSize² × layers
    int weightSize = 0;                     ///< weights per side: samples, or cells for Unity
    world::HeightfieldHoles holes;          ///< (resolution − 1)², rows along z
    meshing::TriangleMesh remainder;
    std::size_t clippedColumns = 0;
};

TileMaps computeTile(const Scene& scene, const terrain::DensityField& field, const terrain::LandformMasks* landform,
                     const terrain::RockMasks* rock, const TerrainExportPlan& plan, int tx, int tz)
{
    const double v = plan.voxelSize;
    world::TileBox box;
    box.min = {plan.minVoxel[0] + tx * plan.tileVoxels, plan.minVoxel[1], plan.minVoxel[2] + tz * plan.tileVoxels};
    box.size = {plan.tileVoxels, plan.heightVoxels, plan.tileVoxels};
    const world::TerrainTile tile = world::extractTerrainTile(field, box, {v});

    TileMaps maps;
    maps.clippedColumns = tile.columnsAtTop;
    maps.heights = engineHeights(tile, plan);
    const int n = plan.resolution;
    maps.holes = world::engineHoles(tile, n - 1, n - 1, plan.spacing);
    maps.remainder = world::heightfieldRemainder(tile, maps.holes);

    // Weights: the layer rules at each sample of the top surface, with the
    // field's normal (as Strata's meshes have), cavity probed along it, and
    // cover 0 (nothing lies above the top surface).
    std::vector<render::LayerRule> rules;
    bool cavity = false;
    for (const LayerSettings& layer : scene.material.layers) {
        rules.push_back(layer.rule);
        cavity = cavity || layer.rule.cavity.enabled;
    }
    const glm::dvec3 origin = glm::dvec3(box.min[0], box.min[1], box.min[2]) * v;
    const render::LayerCoverage coverage(rules, origin);
    const int layers = coverage.layerCount();
    // Unity's alphamaps are 2^n texels a side, one per heightmap cell
    // (texel centres at the cells' centres); the others' weights stand at
    // the heightmap samples.
    const bool cells = plan.engine == TerrainEngine::Unity;
    const int m = maps.weightSize = cells ? n - 1 : n;
    maps.weights.resize(std::size_t(m) * m * layers);
    const double radius = 4.0 * v; // as meshing::SurfaceAttributeOptions' default cavity radius
    std::vector<float> shares(static_cast<std::size_t>(layers), 0.0f);
    const auto lattice = [&](int index) {
        return cells ? (double(index) + 0.5) * double(plan.tileVoxels) / double(n - 1)
                     : double(std::int64_t(index) * plan.tileVoxels) / double(n - 1);
    };
    for (int r = 0; r < m; ++r)
        for (int c = 0; c < m; ++c) {
            const std::size_t s = std::size_t(r) * m + c;
            const double lx = lattice(c), lz = lattice(r);
            const glm::dvec3 p{(double(box.min[0]) + lx) * v, world::latticeHeight(tile, lx, lz),
                               (double(box.min[2]) + lz) * v};
            double slope = 0.0;
            const glm::dvec3 normal = gradient(field, p, 0.5 * v, &slope);
            glm::vec2 surface(0.0f);
            if (cavity && slope > 0.0) {
                // Cavity as meshing::computeSurfaceAttributes() defines it,
                // with the field scaled by its gradient as the distance.
                double shortfall = 0.0;
                for (double d : {0.25 * radius, 0.5 * radius, radius})
                    shortfall += std::clamp(1.0 - field.density(p + normal * d) / slope / d, 0.0, 1.0);
                surface.x = float(shortfall / 3.0);
            }
            glm::vec4 masks(0.0f);
            if (landform) {
                const double x = p.x, z = p.z;
                landform->landformMasks(&x, &z, 1, &masks);
            }
            glm::vec2 rockMasks(0.0f);
            if (rock) rock->rockMasks(&p.x, &p.y, &p.z, 1, &rockMasks);
            coverage.shares(glm::vec3(p - origin), glm::vec3(normal), surface, masks, rockMasks, shares.data());
            quantiseWeights(shares.data(), layers, &maps.weights[s * layers]);
        }
    return maps;
}

// --- Files ------------------------------------------------------------------

/// Column order of an engine's images: Unity's run from the tile's largest
/// x down (Unity x = −x), the others along x.
int sourceColumn(const TerrainExportPlan& plan, int c)
{
    return plan.engine == TerrainEngine::Unity ? plan.resolution - 1 - c : c;
}

std::uint16_t quantiseHeight(const TerrainExportPlan& plan, double height)
{
    const double units = std::round((height - plan.base) / plan.heightStep);
    return std::uint16_t(std::clamp(units, 0.0, 65535.0));
}

render::DataImage heightImage16(const TerrainExportPlan& plan, const std::vector<double>& heights)
{
    const int n = plan.resolution;
    render::DataImage image{n, n, 1, render::SampleType::UInt16, {}};
    image.bytes.resize(std::size_t(n) * n * 2);
    auto* out = reinterpret_cast<std::uint16_t*>(image.bytes.data());
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) out[std::size_t(r) * n + c] = quantiseHeight(plan, heights[std::size_t(r) * n + sourceColumn(plan, c)]);
    return image;
}

render::DataImage heightImageFloat(const TerrainExportPlan& plan, const std::vector<double>& heights)
{
    const int n = plan.resolution;
    render::DataImage image{n, n, 1, render::SampleType::Float32, {}};
    image.bytes.resize(std::size_t(n) * n * 4);
    auto* out = reinterpret_cast<float*>(image.bytes.data());
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) out[std::size_t(r) * n + c] = float(heights[std::size_t(r) * n + sourceColumn(plan, c)]);
    return image;
}

/// 16-bit little-endian samples, rows in order, no header.
std::string raw16(const render::DataImage& image)
{
    std::string bytes(image.bytes.size(), '\0');
    const auto* in = reinterpret_cast<const std::uint16_t*>(image.bytes.data());
    for (std::size_t i = 0; i < image.bytes.size() / 2; ++i) {
        bytes[2 * i] = char(in[i] & 0xff);
        bytes[2 * i + 1] = char(in[i] >> 8);
    }
    return bytes;
}

render::DataImage weightImage(const TerrainExportPlan& plan, const TileMaps& maps, int first, int channels)
{
    const int m = maps.weightSize;
    const int layers = int(plan.layers.size());
    render::DataImage image{m, m, channels, render::SampleType::UInt8, {}};
    image.bytes.assign(std::size_t(m) * m * channels, 0);
    for (int r = 0; r < m; ++r)
        for (int c = 0; c < m; ++c) {
            const int source = plan.engine == TerrainEngine::Unity ? m - 1 - c : c;
            const std::size_t s = std::size_t(r) * m + source;
            for (int k = 0; k < channels && first + k < layers; ++k)
                image.bytes[(std::size_t(r) * m + c) * channels + k] = maps.weights[s * layers + first + k];
        }
    return image;
}

render::DataImage holeImage(const TerrainExportPlan& plan, const world::HeightfieldHoles& holes)
{
    const int n = holes.cellsX;
    render::DataImage image{n, holes.cellsZ, 1, render::SampleType::UInt8, {}};
    image.bytes.assign(std::size_t(n) * holes.cellsZ, 0);
    for (int r = 0; r < holes.cellsZ; ++r)
        for (int c = 0; c < n; ++c) {
            const int source = plan.engine == TerrainEngine::Unity ? n - 1 - c : c;
            image.bytes[std::size_t(r) * n + c] = holes.cells[std::size_t(r) * n + source] ? 255 : 0;
        }
    return image;
}

/// Writes one tile's files; returns its record for terrain.json.
json writeTile(const fs::path& dir, const TerrainExportPlan& plan, const TileMaps& maps, int tx, int tz)
{
    const std::string name = plan.tileName(tx, tz);
    json files = json::object();
    const auto write = [&](const std::string& key, const std::string& relative, const render::DataImage& image) {
        fs::create_directories((dir / relative).parent_path());
        render::writeDataImage(image, dir / relative);
        files[key] = relative;
    };
    const auto writeRaw = [&](const std::string& key, const std::string& relative, const render::DataImage& image) {
        fs::create_directories((dir / relative).parent_path());
        writeFileAtomically(dir / relative, raw16(image));
        files[key] = relative;
    };
    const render::DataImage h16 = heightImage16(plan, maps.heights);
    switch (plan.engine) {
    case TerrainEngine::Unreal:
        write("heightmap", "heightmaps/" + name + ".png", h16);
        writeRaw("heightmap_r16", "heightmaps/" + name + ".r16", h16);
        break;
    case TerrainEngine::Unity: writeRaw("heightmap", "heightmaps/" + name + ".raw", h16); break;
    case TerrainEngine::Godot:
        write("heightmap", "heightmaps/" + name + ".exr", heightImageFloat(plan, maps.heights));
        write("heightmap16", "heightmaps/" + name + ".png", h16);
        break;
    case TerrainEngine::Raw:
        writeRaw("heightmap", "heightmaps/" + name + ".r16", h16);
        write("heightmap_float", "heightmaps/" + name + ".exr", heightImageFloat(plan, maps.heights));
        break;
    }
    const int layers = int(plan.layers.size());
    json weights = json::array();
    if (plan.engine == TerrainEngine::Unreal || plan.engine == TerrainEngine::Raw) {
        for (int l = 0; l < layers; ++l) {
            const std::string relative = "weights/" + plan.layers[std::size_t(l)] + "/" + name + ".png";
            fs::create_directories((dir / relative).parent_path());
            render::writeDataImage(weightImage(plan, maps, l, 1), dir / relative);
            weights.push_back(relative);
        }
    } else {
        for (int first = 0; first < layers; first += 4) {
            const std::string relative = "splat/" + name + "_" + std::to_string(first / 4) + ".png";
            fs::create_directories((dir / relative).parent_path());
            render::writeDataImage(weightImage(plan, maps, first, 4), dir / relative);
            weights.push_back(relative);
        }
    }
    files["weights"] = weights;
    write("holes", "holes/" + name + ".png", holeImage(plan, maps.holes));
    std::error_code stale; // a mesh from an earlier export of this tile
    fs::remove(dir / ("meshes/" + name + ".glb"), stale);
    if (!maps.remainder.indices.empty()) {
        const std::string relative = "meshes/" + name + ".glb";
        fs::create_directories((dir / relative).parent_path());
        meshing::writeGlb(maps.remainder, dir / relative, {name});
        files["mesh"] = relative;
    }

    std::uint64_t holes = 0;
    for (std::uint8_t h : maps.holes.cells) holes += h;
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    for (double h : maps.heights) {
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
    const double v = plan.voxelSize;
    const double x0 = double(plan.minVoxel[0] + tx * plan.tileVoxels) * v;
    const double z0 = double(plan.minVoxel[2] + tz * plan.tileVoxels) * v;
    json record = {{"name", name},
                   {"x", tx},
                   {"z", tz},
                   {"min_x", x0},
                   {"min_z", z0},
                   {"files", files},
                   {"hole_cells", holes},
                   {"mesh_triangles", maps.remainder.indices.size() / 3},
                   {"height_min", lo},
                   {"height_max", hi}};
    switch (plan.engine) {
    case TerrainEngine::Unreal:
        record["location_cm"] = {{"x", x0 * 100.0}, {"y", z0 * 100.0}};
        break;
    case TerrainEngine::Unity:
        record["position"] = {{"x", -(x0 + plan.tileSize)}, {"y", plan.base}, {"z", z0}};
        break;
    default: record["position"] = {{"x", x0}, {"y", plan.base}, {"z", z0}}; break;
    }
    return record;
}

/// The numbers an artist types into the engine's import dialog.
json importSettings(const TerrainExportPlan& plan)
{
    const double x0 = double(plan.minVoxel[0]) * plan.voxelSize, z0 = double(plan.minVoxel[2]) * plan.voxelSize;
    const double top = plan.base + 65535.0 * plan.heightStep;
    switch (plan.engine) {
    case TerrainEngine::Unreal: {
        // Landscape: z_cm = location.z + (value − 32768) · scale.z / 128.
        const double zScale = plan.heightStep * 100.0 * 128.0;
        return {{"heightmap_format", "16-bit grey PNG (and the same as r16 RAW, little-endian), one per tile, World "
                                     "Partition names NAME_xX_yY"},
                {"heightmap_resolution", plan.resolution},
                {"scale_cm", {{"x", plan.spacing * 100.0}, {"y", plan.spacing * 100.0}, {"z", zScale}}},
                {"location_cm", {{"x", x0 * 100.0}, {"y", z0 * 100.0}, {"z", plan.base * 100.0 + 256.0 * zScale}}},
                {"axes", "Unreal X = Strata x, Unreal Y = Strata z, Unreal Z = Strata y (centimetres)"},
                {"weight_layers", plan.layers},
                {"holes", "paint the Landscape Visibility layer from holes/NAME.png (255 = hole), one pixel per quad"}};
    }
    case TerrainEngine::Unity:
        return {{"heightmap_format", "RAW, 16 bit, byte order Windows (little-endian), flip vertically off"},
                {"heightmap_resolution", plan.resolution},
                {"terrain_size", {{"x", plan.tileSize}, {"y", 65535.0 * plan.heightStep}, {"z", plan.tileSize}}},
                {"axes", "Unity x = −Strata x, Unity z = Strata z, y up (the frame of glTFast and UnityGLTF)"},
                {"alphamap_resolution", plan.resolution - 1},
                {"splat_layers", plan.layers},
                {"holes", "holes/NAME.png, one pixel per heightmap cell: TerrainData.SetHoles(false where 255)"}};
    case TerrainEngine::Godot:
        return {{"heightmap_format", "32-bit float EXR in metres (and 16-bit PNG: height = base + value · step)"},
                {"heightmap_resolution", plan.resolution},
                {"vertex_spacing", plan.spacing},
                {"height_base", plan.base},
                {"height_step", plan.heightStep},
                {"axes", "Godot x = Strata x, Godot z = Strata z, y up"},
                {"splat_layers", plan.layers}};
    case TerrainEngine::Raw: break;
    }
    return {{"heightmap_format", "16-bit little-endian .r16 (height = base + value · step) and 32-bit float EXR"},
            {"heightmap_resolution", plan.resolution},
            {"spacing", plan.spacing},
            {"height_base", plan.base},
            {"height_step", plan.heightStep},
            {"height_top", top},
            {"weight_layers", plan.layers}};
}

/// What makes two exports one: the format, the scene (its hash) and every
/// setting the tiles' files depend on. terrain.json holds them.
json exportIdentity(const Scene& scene, const TerrainExportPlan& plan)
{
    return {{"format", "strata-terrain-export"},
            {"version", 1},
            {"engine", terrainEngineName(plan.engine)},
            {"scene_hash", detail::sceneHash(scene)},
            {"seed", plan.seed},
            {"voxel_size", plan.voxelSize},
            {"tile_size", plan.tileSize},
            {"tiles_x", plan.tilesX},
            {"tiles_z", plan.tilesZ},
            {"resolution", plan.resolution},
            {"spacing", plan.spacing},
            {"height_base", plan.base},
            {"height_step", plan.heightStep},
            {"layers", plan.layers}};
}

/// The tile records of the export already in `dir` when it is this one
/// (the same identity), so that exports of some tiles at a time add up in
/// one terrain.json; none when the folder holds no terrain.json. Another
/// export's folder (another engine, scene, seed or setting; a terrain.json
/// that does not parse) is refused naming what differs, unless `force`
/// (its tiles are then left out of the new terrain.json).
std::map<int, json> previousTiles(const fs::path& dir, const json& identity, bool force)
{
    const fs::path path = dir / "terrain.json";
    std::error_code ec;
    if (!fs::exists(path, ec)) return {};
    std::string differs;
    json old;
    // A terrain.json is a few kilobytes a tile; one past 64 MiB is not ours.
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec || size > (std::uintmax_t(64) << 20)) {
        differs = "a terrain.json too large to be an export's";
    } else {
        std::ifstream in(path, std::ios::binary);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        old = json::parse(text, nullptr, false);
        if (!old.is_object()) differs = "a terrain.json that does not parse";
        for (auto item = identity.begin(); differs.empty() && item != identity.end(); ++item) {
            const auto found = old.find(item.key());
            if (found == old.end() || *found != item.value()) {
                differs = item.key() + " " + (found == old.end() ? std::string("(none)") : found->dump()) +
                          " (this export: " + item.value().dump() + ")";
            }
        }
    }
    if (!differs.empty()) {
        if (force) return {};
        throw Error(ErrorKind::BadInput,
                    "output folder '" + dir.string() + "' holds another terrain export: " + differs +
                        "; use another folder, or --force to export over it",
                    {dir.string()});
    }
    std::map<int, json> tiles;
    const auto list = old.find("tiles");
    if (list != old.end() && list->is_array()) {
        // Records of tiles inside this export's grid only (a hand-edited or
        // crafted file can hold anything).
        const std::int64_t tilesX = identity["tiles_x"].get<int>(), tilesZ = identity["tiles_z"].get<int>();
        for (const json& tile : *list) {
            const auto x = tile.find("x"), z = tile.find("z");
            if (x == tile.end() || z == tile.end() || !x->is_number_integer() || !z->is_number_integer()) continue;
            const std::int64_t tx = x->get<std::int64_t>(), tz = z->get<std::int64_t>();
            if (tx >= 0 && tx < tilesX && tz >= 0 && tz < tilesZ) tiles.emplace(int(tz * tilesX + tx), tile);
        }
    }
    return tiles;
}

} // namespace

TerrainExportSummary exportTerrain(const Scene& scene, const TerrainExportOptions& options,
                                   const TerrainExportPlan& plan, PipelineObserver* observer)
{
    const Stopwatch clock;
    const fs::path& dir = options.outputDir;
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
        throw Error(ErrorKind::Io, "cannot create the output folder '" + dir.string() + "': " +
                                       (ec ? ec.message() : "a file is in the way"),
                    {dir.string()});
    const OutputLock lock(dir);
    const json identity = exportIdentity(scene, plan);
    std::map<int, json> previous = previousTiles(dir, identity, options.force);

    const std::shared_ptr<const terrain::DensityField> field = fieldForSeed(scene, plan.seed);
    const detail::LayerMaskSources masks = detail::layerMaskSources(scene, plan.seed);

    if (observer) observer->beginStage("export");
    std::mutex mutex;
    std::map<int, json> records;
    TerrainExportSummary summary;
    const detail::TileWorkResult run =
        detail::runTileWorkers(plan.selected, options.threads, observer, [&](int index) {
            const int tx = index % plan.tilesX, tz = index / plan.tilesX;
            TileMaps maps = computeTile(scene, *field, masks.landform.get(), masks.rock.get(), plan, tx, tz);
            if (!options.meshes) maps.remainder = {};
            json record = writeTile(dir, plan, maps, tx, tz);
            std::lock_guard<std::mutex> hold(mutex);
            summary.holeCells += record["hole_cells"].get<std::uint64_t>();
            summary.meshTriangles += maps.remainder.indices.size() / 3;
            summary.clippedColumns += maps.clippedColumns;
            records.emplace(index, std::move(record));
        });
    summary.tiles = int(records.size());
    summary.seconds = clock.seconds();
    if (observer)
        observer->endStage("export", summary.seconds, std::to_string(summary.tiles) + " tiles exported");
    if (run.interrupted)
        throw Error(ErrorKind::Interrupted, "export interrupted: " + std::to_string(summary.tiles) +
                                                " tiles written; terrain.json was not written");
    if (!run.failures.empty()) {
        std::string message = "export failed on " + std::to_string(run.failures.size()) + " tile(s): ";
        for (std::size_t i = 0; i < run.failures.size() && i < 3; ++i)
            message += (i ? "; tile " : "tile ") + std::to_string(run.failures[i].index) + ": " + run.failures[i].message;
        throw Error(run.failures.front().kind, message, {dir.string()}); // the first's kind, as the bake
    }

    // This run's tiles, and those an earlier run of the same export wrote.
    for (auto& [index, record] : records) previous[index] = std::move(record);
    json tiles = json::array();
    for (auto& [index, record] : previous) tiles.push_back(std::move(record));
    json manifest = identity;
    manifest["scene"] = scene.source;
    manifest["import"] = importSettings(plan);
    manifest["tiles"] = std::move(tiles);
    writeFileAtomically(dir / "terrain.json", manifest.dump(1) + "\n");
    return summary;
}

} // namespace strata::scene
