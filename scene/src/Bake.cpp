// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Bake.h>
#include <strata/scene/BakeViewer.h>
#include <strata/world/LandformAttributes.h>
#include <strata/scene/Pipeline.h>

#include "BakeManifest.h"
#include "BakeProvenance.h"
#include "LayerMaskSources.h"
#include "TileWorkers.h"

#include <strata/AtomicFile.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/OutputLock.h>
#include <strata/Sha256.h>
#include <strata/Stopwatch.h>
#include <strata/meshing/GltfCompact.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/GridIO.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/meshing/SurfaceError.h>
#include <strata/terrain/SampleLevelSet.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <fstream>
#include <mutex>

namespace strata::scene {

namespace fs = std::filesystem;
using detail::BakeFile;
using detail::BakeManifest;
using detail::TileLevelRecord;
using detail::TileRecord;

namespace {

/// The geometric error of rendering `coarse` instead of `fine` (metres):
/// the larger one-sided Hausdorff distance, each vertex of one mesh to the
/// nearest triangle of the other (SurfaceError's surface-to-mesh measure,
/// exact point-to-triangle). A level with no surface where the other has
/// one errs by the size of what it lost.
double levelError(const meshing::TriangleMesh& fine, const meshing::TriangleMesh& coarse, double voxelSize,
                  double coarseCell)
{
    const auto diagonal = [](const meshing::TriangleMesh& mesh) {
        const meshing::Bounds b = meshing::worldBounds(mesh);
        return glm::length(b.max - b.min);
    };
    if (fine.triangleCount() == 0 || coarse.triangleCount() == 0)
        return std::max(fine.triangleCount() ? diagonal(fine) : 0.0, coarse.triangleCount() ? diagonal(coarse) : 0.0);
    // SurfaceError buckets the target's triangles in cubes of two "voxels":
    // half the target's cell size makes them one cell wide, a few triangles each.
    const auto oneWay = [](const meshing::TriangleMesh& from, const meshing::TriangleMesh& to, double cell) {
        meshing::SurfaceErrorOptions options;
        options.voxelSize = cell;
        options.surfacePoints.reserve(from.positions.size());
        for (const glm::vec3& p : from.positions) options.surfacePoints.push_back(from.origin + glm::dvec3(p));
        options.meshToSurface = false; // only the point-to-mesh direction: there is no analytic side
        const meshing::SurfaceError error = meshing::measureSurfaceError(to, {}, options);
        return error.surfaceToMeshMax * cell;
    };
    return std::max(oneWay(fine, coarse, 0.5 * coarseCell), oneWay(coarse, fine, 0.5 * voxelSize));
}

void addBounds(const meshing::TriangleMesh& mesh, glm::dvec3& lo, glm::dvec3& hi)
{
    for (const glm::vec3& q : mesh.positions) {
        const glm::dvec3 p = mesh.origin + glm::dvec3(q);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
}

/// The grid step of compact tiles: the finest voxel·2^k over which a
/// tile's widest reach (its size, skirts on both sides and a coarsest cell
/// of slack each way) spans 16 bits. One step for every tile of the bake,
/// and tile corners lie on the voxel lattice, so the grid is world-aligned
/// and a seam vertex two tiles share decodes to the same point in both.
double tilePositionStep(const BakePlan& plan)
{
    const double coarsest = plan.voxelSize * double(1 << (plan.lods - 1));
    return meshing::compactPositionStep(plan.tileSize + 2.0 * (plan.skirtDepth + coarsest), plan.voxelSize);
}

/// One level of a tile as .glb bytes: the surface and the skirt.
std::string encodeTile(const world::TileMeshData& mesh, const std::string& name, const BakePlan& plan)
{
    const std::vector<meshing::GlbPart> parts{meshing::GlbPart{&mesh.surface, "strata-terrain", false},
                                              meshing::GlbPart{&mesh.skirt, "strata-skirt", false}};
    if (plan.tileFormat == TileFormat::Plain) return meshing::encodeGlb(parts, mesh.surface.origin, name);
    meshing::CompactGlbOptions options;
    options.positionStep = tilePositionStep(plan);
    return meshing::encodeCompactGlb(parts, mesh.surface.origin, name, options);
}

/// Where a tile's files go, relative to the bake folder.
std::string tileFile(int level, const std::string& name) { return "tiles/" + std::to_string(level) + "/" + name + ".glb"; }
std::string gridFile(const std::string& name) { return "grids/" + name + ".vdb"; }

BakeFile writeBakeFile(const fs::path& dir, const std::string& relative, std::string_view bytes)
{
    writeFileAtomically(dir / relative, bytes);
    return BakeFile{relative, bytes.size(), sha256Hex(bytes)};
}

/// Bakes one tile: every level's mesh and (optionally) the level-0 grid;
/// with `dir`, writes its files and then its record (so a record on disk
/// means every file of the tile is complete).
/// `masks` fills each level's landform and rock masks (either may be
/// null), which the tiles then carry (glTF _LANDFORM, _ROCK) for layer
/// rules that read them.
TileRecord bakeTile(const terrain::DensityField& field, const Scene& scene, const BakePlan& plan, bool grids,
                    std::uint64_t maxMemoryBytes, const BakeTile& tile, const fs::path* dir,
                    const detail::LayerMaskSources& masks)
{
    TileRecord record;
    record.index = tile.index;
    record.cell = tile.cell;
    record.name = tile.name;
    for (int a = 0; a < 3; ++a) {
        record.boxMin[a] = double(tile.box.min[a]) * plan.voxelSize;
        record.boxMax[a] = double(tile.box.min[a] + tile.box.size[a]) * plan.voxelSize;
    }
    meshing::TriangleMesh finest;
    for (int level = 0; level < plan.lods; ++level) {
        world::TileMeshOptions options;
        options.voxelSize = plan.voxelSize;
        options.level = level;
        options.skirtDepth = plan.skirtDepth;
        world::TileMeshData mesh = world::meshTile(field, tile.box, options);
        if (masks.landform) {
            mesh.surface.landform = world::computeLandformAttributes(*masks.landform, mesh.surface);
            mesh.skirt.landform = world::computeLandformAttributes(*masks.landform, mesh.skirt);
        }
        if (masks.rock) {
            mesh.surface.rock = world::computeRockAttributes(*masks.rock, mesh.surface);
            mesh.skirt.rock = world::computeRockAttributes(*masks.rock, mesh.skirt);
        }
        TileLevelRecord out;
        out.level = level;
        out.triangles = mesh.surface.triangleCount();
        out.skirtTriangles = mesh.skirt.triangleCount();
        out.vertices = mesh.surface.vertexCount();
        if (level == 0) finest = mesh.surface;
        else out.error = levelError(finest, mesh.surface, plan.voxelSize, plan.voxelSize * double(1 << level));
        if (out.triangles > 0) {
            out.min = glm::dvec3(std::numeric_limits<double>::max());
            out.max = glm::dvec3(std::numeric_limits<double>::lowest());
            addBounds(mesh.surface, out.min, out.max);
            addBounds(mesh.skirt, out.min, out.max);
            const std::string name = "tile " + tile.name + " level " + std::to_string(level);
            const std::string bytes = encodeTile(mesh, name, plan);
            const std::string relative = tileFile(level, tile.name);
            out.file = dir ? writeBakeFile(*dir, relative, bytes) : BakeFile{relative, bytes.size(), ""};
        }
        record.levels.push_back(out);
    }
    if (grids) {
        terrain::SampleOptions sampling;
        sampling.voxelSize = plan.voxelSize;
        sampling.halfWidth = scene.halfWidth;
        sampling.closed = false;
        sampling.maxMemoryBytes = maxMemoryBytes;
        sampling.region.min = record.boxMin;
        sampling.region.max = record.boxMax;
        openvdb::FloatGrid::Ptr grid = terrain::sampleLevelSet(field, sampling);
        grid->setName("terrain");
        const std::string relative = gridFile(tile.name);
        if (dir) {
            meshing::writeGrid(*grid, *dir / relative);
            record.grid = BakeFile{relative, std::uint64_t(fs::file_size(*dir / relative)), sha256File(*dir / relative)};
        } else {
            record.grid = BakeFile{relative, grid->memUsage(), ""};
        }
    }
    if (dir) writeFileAtomically(detail::recordPath(*dir, tile.index), detail::recordJson(record).dump(1) + "\n");
    return record;
}

bool fileMatches(const fs::path& dir, const BakeFile& file, bool hash)
{
    std::error_code ec;
    const fs::path path = dir / file.path;
    if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) != file.bytes || ec) return false;
    return !hash || sha256File(path) == file.sha256;
}

/// Every file of the record is there with its size (and, when `hash`, its
/// SHA-256), and the record has every level.
bool tileMatches(const fs::path& dir, const TileRecord& tile, int lods, bool grids, bool hash)
{
    if (int(tile.levels.size()) != lods || grids != tile.grid.has_value()) return false;
    for (const TileLevelRecord& level : tile.levels)
        if (level.file && !fileMatches(dir, *level.file, hash)) return false;
    return !tile.grid || fileMatches(dir, *tile.grid, hash);
}

/// Refuses another bake's folder unless `force`: names what differs.
void checkSameBake(const BakeManifest& old, const BakeManifest& now, const fs::path& dir, bool force)
{
    std::string differs;
    if (old.sceneHash != now.sceneHash)
        differs = "another scene (its scene hash " + old.sceneHash.substr(0, 16) + "…, this scene's " +
                  now.sceneHash.substr(0, 16) + "…)";
    else if (old.seed != now.seed)
        differs = "seed " + std::to_string(old.seed) + " (this bake: " + std::to_string(now.seed) + ")";
    else if (old.tileSize != now.tileSize || old.lods != now.lods || old.voxelSize != now.voxelSize ||
             old.counts != now.counts || old.min != now.min || old.skirtDepth != now.skirtDepth ||
             old.grids != now.grids || old.tileFormat != now.tileFormat)
        differs = "other settings (tile size " + formatNumber(old.tileSize) + " m, " + std::to_string(old.lods) +
                  " levels, skirt depth " + formatNumber(old.skirtDepth) + " m, grids " + (old.grids ? "on" : "off") +
                  ", " + old.tileFormat + " tiles; this bake: " + formatNumber(now.tileSize) + " m, " +
                  std::to_string(now.lods) + " levels, " + formatNumber(now.skirtDepth) + " m, grids " +
                  (now.grids ? "on" : "off") + ", " + now.tileFormat + " tiles)";
    if (differs.empty() || force) return;
    throw Error(ErrorKind::BadInput,
                "output folder '" + dir.string() + "' holds a bake of " + differs + ": use another folder, or --force to replace it",
                {dir.string()});
}

/// The record of tile `index` if its files are all there and match it.
std::optional<TileRecord> verifiedRecord(const fs::path& dir, int index, const BakeManifest& header, bool hash)
{
    std::optional<TileRecord> record;
    try {
        record = detail::readRecord(detail::recordPath(dir, index));
    } catch (const Error&) {
        return std::nullopt; // a damaged record: the tile is redone
    }
    if (!record || record->index != index || !tileMatches(dir, *record, header.lods, header.grids, hash))
        return std::nullopt;
    return record;
}

/// With --force over another bake: removes the files its records list.
void removeOldBake(const fs::path& dir, const BakeManifest& old)
{
    std::error_code ec;
    const int count = old.counts[0] * old.counts[1] * old.counts[2];
    for (int index = 0; index < count; ++index) {
        std::optional<TileRecord> record;
        try {
            record = detail::readRecord(detail::recordPath(dir, index));
        } catch (const Error&) {
        }
        if (record) {
            for (const TileLevelRecord& level : record->levels)
                if (level.file) fs::remove(dir / level.file->path, ec);
            if (record->grid) fs::remove(dir / record->grid->path, ec);
        }
        fs::remove(detail::recordPath(dir, index), ec);
    }
    fs::remove_all(dir / detail::PROVENANCE_FOLDER, ec);
    fs::remove(dir / "manifest.json", ec);
    fs::remove(dir / "tileset.json", ec);
}

/// Files, bytes, triangles and errors per level of the tiles in `manifest`.
void summarise(const BakeManifest& manifest, BakeSummary& summary)
{
    const auto lods = std::size_t(manifest.lods);
    summary.trianglesPerLevel.assign(lods, 0);
    summary.filesPerLevel.assign(lods, 0);
    summary.bytesPerLevel.assign(lods, 0);
    for (const auto& [index, tile] : manifest.tiles)
        for (const TileLevelRecord& level : tile.levels) {
            const auto l = std::size_t(level.level);
            if (l >= lods) continue;
            summary.trianglesPerLevel[l] += level.triangles;
            if (level.file) {
                ++summary.filesPerLevel[l];
                summary.bytesPerLevel[l] += level.file->bytes;
            }
        }
    summary.errorPerLevel = manifest.geometricErrors();
    summary.tiles = manifest.counts[0] * manifest.counts[1] * manifest.counts[2];
    summary.missing = summary.tiles - int(manifest.tiles.size());
}

void writeManifestAndTileset(const fs::path& dir, const BakeManifest& manifest)
{
    writeFileAtomically(dir / "manifest.json", detail::toJson(manifest).dump(1) + "\n");
    writeFileAtomically(dir / "tileset.json", detail::makeTileset(manifest).dump(1) + "\n");
}

/// DIR/viewer/ beside tileset.json (BakeViewer.h); a strata built without
/// the web viewer (no node/npm) writes none and says so once.
void writeViewer(const fs::path& dir, const Scene& scene, PipelineObserver* observer)
{
    if (!writeBakeViewer(dir, scene) && observer)
        observer->notice("no web viewer: this strata was built without it (node and npm), so " +
                         (dir / "viewer").string() + " was not written");
}

} // namespace

std::string indexRanges(const std::vector<int>& indices, const char* separator)
{
    std::string out;
    for (std::size_t i = 0; i < indices.size();) {
        std::size_t j = i;
        while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
        if (!out.empty()) out += separator;
        out += std::to_string(indices[i]);
        if (j > i) out += "-" + std::to_string(indices[j]);
        i = j + 1;
    }
    return out;
}

const char* tileFormatName(TileFormat format)
{
    return format == TileFormat::Plain ? "plain" : "meshopt";
}

BakeSummary bake(const Scene& scene, const BakeOptions& options, const BakePlan& plan, PipelineObserver* observer)
{
    const Stopwatch clock;
    const fs::path& dir = options.outputDir;
    const std::shared_ptr<const terrain::DensityField> field = fieldForSeed(scene, options.seed);
    const detail::LayerMaskSources masks = detail::layerMaskSources(scene, options.seed);

    BakeManifest manifest = detail::manifestFor(plan, scene, options.grids);
    // Check the folder before creating anything in it.
    std::optional<BakeManifest> old;
    try {
        old = detail::readBakeHeader(dir);
    } catch (const Error& e) {
        // A damaged bake.json: --force bakes anew over it (its tiles' records are redone).
        if (!options.force)
            throw Error(ErrorKind::BadInput, std::string(e.what()) + " (--force bakes anew over it)", e.place());
    }
    if (old) checkSameBake(*old, manifest, dir, options.force);
    if (observer && !observer->progress(0.0)) throw Error(ErrorKind::Interrupted, "interrupted before the bake");

    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw Error(ErrorKind::Io, "cannot create output folder '" + dir.string() + "': " + ec.message(), {dir.string()});
    // Workers share the folder (each writes only its own tiles); a single
    // bake holds it.
    std::optional<OutputLock> lock;
    if (!options.worker) lock.emplace(dir);
    const bool replace = old && options.force && !detail::sameBake(*old, manifest);
    if (replace) removeOldBake(dir, *old);
    // Each folder is checked as it is made: one error code shared by all
    // would keep only the last call's result and lose an earlier failure.
    const auto makeFolder = [](const fs::path& folder) {
        std::error_code error;
        fs::create_directories(folder, error);
        if (error || !fs::is_directory(folder)) {
            throw Error(ErrorKind::Io,
                        "cannot create folder '" + folder.string() + "': " +
                            (error ? error.message() : std::string("a file of that name is in the way")),
                        {folder.string()});
        }
    };
    for (int level = 0; level < plan.lods; ++level) makeFolder(dir / "tiles" / std::to_string(level));
    if (options.grids) makeFolder(dir / "grids");
    makeFolder(dir / "records");
    // The same bytes from every run and worker of this bake.
    writeFileAtomically(dir / "scene.toml", scene.text);
    writeFileAtomically(dir / "bake.json", detail::headerJson(manifest).dump(1) + "\n");

    BakeSummary summary;
    summary.tiles = plan.tileCount();
    std::vector<int> todo;
    for (int index : plan.selected) {
        if (std::optional<TileRecord> record = verifiedRecord(dir, index, manifest, /*hash*/ true)) {
            manifest.tiles[index] = std::move(*record);
            ++summary.kept;
        } else {
            todo.push_back(index);
        }
    }

    // Tiles in parallel: each worker takes the next index; the calling
    // thread reports progress and hears Ctrl-C.
    if (observer) observer->beginStage("bake");
    std::mutex mutex;
    std::map<int, TileRecord> made;
    const detail::TileWorkResult run = detail::runTileWorkers(todo, options.threads, observer, [&](int index) {
        const BakeTile tile = plan.tile(index);
        try {
            const Stopwatch tileClock;
            TileRecord record =
                bakeTile(*field, scene, plan, options.grids, options.maxMemoryBytes, tile, &dir, masks);
            if (options.worker) detail::writeTileProvenance(dir, index, tileClock.seconds());
            std::lock_guard<std::mutex> hold(mutex);
            made.emplace(index, std::move(record));
        } catch (const std::exception& e) {
            // No half-made tile: its finished files go too.
            std::error_code ignored;
            fs::remove(detail::recordPath(dir, index), ignored);
            for (int level = 0; level < plan.lods; ++level) fs::remove(dir / tileFile(level, tile.name), ignored);
            fs::remove(dir / gridFile(tile.name), ignored);
            throw Error(ErrorKind::Io, "tile " + std::to_string(index) + " (" + tile.name + "): " + e.what());
        }
    });
    const bool stop = run.interrupted;
    const std::vector<detail::TileFailure>& failures = run.failures;
    for (auto& [index, record] : made) manifest.tiles[index] = std::move(record);
    summary.baked = int(made.size());

    if (!options.worker) {
        // The manifest and tileset describe every tile present (other
        // selections' tiles included when their files are there), even
        // after a failure or an interruption, so the next run resumes.
        for (int index = 0; index < plan.tileCount(); ++index)
            if (!manifest.tiles.count(index))
                if (std::optional<TileRecord> record = verifiedRecord(dir, index, manifest, /*hash*/ false))
                    manifest.tiles[index] = std::move(*record);
        writeManifestAndTileset(dir, manifest);
        if (!stop && failures.empty()) writeViewer(dir, scene, observer);
    }
    summarise(manifest, summary);
    summary.seconds = clock.seconds();
    if (observer) observer->endStage("bake", summary.seconds, std::to_string(summary.baked) + " tiles baked");
    if (stop) throw Error(ErrorKind::Interrupted, "bake interrupted: " + std::to_string(summary.baked) +
                                                     " tiles baked; run the same command again to resume");
    if (!failures.empty()) {
        std::vector<int> indices;
        for (const auto& failure : failures) indices.push_back(failure.index);
        // The first failure's kind: a tile refused for its input is bad input (exit 2).
        throw Error(failures.front().kind,
                    std::to_string(failures.size()) + " of " + std::to_string(todo.size()) + " tiles failed (" +
                        indexRanges(indices, ", ") + "; none left a file); the first: " + failures.front().message,
                    {dir.string()});
    }
    return summary;
}

BakeSummary finalizeBake(const fs::path& dir, PipelineObserver* observer)
{
    const Stopwatch clock;
    const std::optional<BakeManifest> header = detail::readBakeHeader(dir);
    if (!header)
        throw Error(ErrorKind::BadInput, "'" + dir.string() + "' holds no bake.json: not a bake folder", {dir.string()});
    const OutputLock lock(dir);
    // Every worker has ended: temporaries left by a killed one are litter.
    std::error_code ec;
    for (const auto& entry : fs::recursive_directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && name.size() > 1 && name[0] == '.' && name.find(".partial-") != std::string::npos)
            fs::remove(entry.path(), ec);
    }
    if (observer) observer->beginStage("finalize");
    BakeManifest manifest = *header;
    std::vector<int> missing;
    const int count = header->counts[0] * header->counts[1] * header->counts[2];
    for (int index = 0; index < count; ++index) {
        if (std::optional<TileRecord> record = verifiedRecord(dir, index, manifest, /*hash*/ true))
            manifest.tiles[index] = std::move(*record);
        else
            missing.push_back(index);
        if (observer && !observer->progressCount(std::uint64_t(index + 1), std::uint64_t(count), "tiles"))
            throw Error(ErrorKind::Interrupted, "finalize interrupted; nothing was written");
    }
    if (!missing.empty()) {
        const std::string scene = header->sceneSource == "<default scene>" ? "" : header->sceneSource + " ";
        throw Error(ErrorKind::Io,
                    "'" + dir.string() + "': " + std::to_string(missing.size()) + " of " + std::to_string(count) +
                        " tiles are missing or damaged: " + indexRanges(missing, ", ") +
                        "; bake them with: strata bake " + scene + "-o " + dir.string() + " --tiles " +
                        indexRanges(missing, ",") + " (then finalize again)",
                    {dir.string()});
    }
    writeManifestAndTileset(dir, manifest);
    writeViewer(dir, loadBakedScene(dir), observer);
    BakeSummary summary;
    summarise(manifest, summary);
    summary.bakedBy = detail::readProvenance(dir, count);
    summary.kept = count;
    summary.seconds = clock.seconds();
    if (observer) observer->endStage("finalize", summary.seconds, std::to_string(count) + " tiles verified");
    return summary;
}

BakeSample sampleBakeTile(const Scene& scene, const BakeOptions& options, const BakePlan& plan)
{
    const std::shared_ptr<const terrain::DensityField> field = fieldForSeed(scene, options.seed);
    const detail::LayerMaskSources masks = detail::layerMaskSources(scene, options.seed);
    // The middle column's slab that holds the surface: the lowest slab with
    // triangles at level 0, else slab 0.
    BakeSample sample;
    const int x = plan.counts[0] / 2, z = plan.counts[2] / 2;
    const Stopwatch clock;
    for (int y = 0; y < plan.counts[1]; ++y) {
        sample.index = (y * plan.counts[2] + z) * plan.counts[0] + x;
        const TileRecord record =
            bakeTile(*field, scene, plan, options.grids, options.maxMemoryBytes, plan.tile(sample.index), nullptr,
                     masks);
        sample.triangles = 0;
        for (const TileLevelRecord& level : record.levels) sample.triangles += level.triangles;
        for (const TileLevelRecord& level : record.levels)
            if (level.file) sample.bytes += level.file->bytes;
        if (sample.triangles > 0) break;
    }
    sample.seconds = clock.seconds();
    return sample;
}

Scene loadBakedScene(const fs::path& bakeDir)
{
    std::optional<BakeManifest> header = detail::readBakeHeader(bakeDir);
    if (!header) header = detail::readManifest(bakeDir);
    if (!header)
        throw Error(ErrorKind::BadInput, "'" + bakeDir.string() + "' holds no bake.json: not a bake folder",
                    {bakeDir.string()});
    const fs::path copy = bakeDir / "scene.toml";
    std::ifstream in(copy, std::ios::binary);
    if (!in) throw Error(ErrorKind::BadInput, "cannot read '" + copy.string() + "'", {copy.string()});
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // Parsed under the original name, so relative paths (heightmaps,
    // textures) resolve from the original scene's folder.
    Scene scene = header->sceneSource == "<default scene>" ? defaultScene() : parseScene(text, header->sceneSource);
    if (scene.text != text || detail::sceneHash(scene) != header->sceneHash)
        throw Error(ErrorKind::BadInput,
                    "'" + copy.string() + "' or the heightmaps it reads changed since the bake (the scene hash differs)",
                    {copy.string()});
    return scene;
}

} // namespace strata::scene
