// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// A whole-world snapshot from a bake's tiles: per tile the coarsest level
// whose geometric error (the tile's own measured error) fits the screen (the
// 3D Tiles screen-space error rule), merged into one mesh and rendered like
// any snapshot.

#include <strata/scene/Bake.h>

#include "BakeManifest.h"

#include <strata/Error.h>
#include <strata/meshing/GltfIO.h>
#include <strata/meshing/MeshMetrics.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>

namespace strata::scene {

namespace {

double boxDistance(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& hi)
{
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0)));
}

} // namespace

WorldSnapshotStats renderBakedWorld(const Scene& scene, const std::filesystem::path& bakeDir,
                                    const WorldSnapshotOptions& options, render::GlContext* context,
                                    const std::function<void(const render::Image& image)>& sink)
{
    const std::optional<detail::BakeManifest> manifest = detail::readManifest(bakeDir);
    if (!manifest)
        throw Error(ErrorKind::BadInput, "'" + bakeDir.string() + "' holds no manifest.json: not a bake folder",
                    {bakeDir.string()});
    if (!(options.maxScreenError > 0.0))
        throw Error(ErrorKind::BadInput, "--max-screen-error must be a positive number of pixels", {"", 0, "--max-screen-error", ""});

    // The camera frames the whole world (every level's bounds).
    meshing::Bounds world{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
    for (const auto& [index, tile] : manifest->tiles)
        for (const detail::TileLevelRecord& level : tile.levels)
            if (level.file) {
                world.min = glm::min(world.min, level.min);
                world.max = glm::max(world.max, level.max);
            }
    if (world.min.x > world.max.x)
        throw Error(ErrorKind::BadInput, "'" + bakeDir.string() + "': the bake holds no surface to render", {bakeDir.string()});
    const int width = options.width.value_or(scene.snapshot.width);
    const int height = options.height.value_or(scene.snapshot.height);
    const render::Camera camera =
        snapshotCamera(scene, options.request, world, double(width) / double(height), std::nullopt);
    // Pixels per metre of error at distance 1 (3D Tiles' SSE denominator).
    const double pixelsPerRadian = double(height) / (2.0 * std::tan(0.5 * camera.fovYDegrees * M_PI / 180.0));

    WorldSnapshotStats stats;
    stats.tilesPerLevel.assign(std::size_t(manifest->lods), 0);
    meshing::TriangleMesh merged;
    merged.origin = 0.5 * (world.min + world.max);
    for (const auto& [index, tile] : manifest->tiles) {
        const double distance = boxDistance(camera.position, tile.boxMin, tile.boxMax);
        // This tile's own measured errors (non-decreasing with the level):
        // tighter than the tileset's per-level maximum over all tiles.
        std::vector<double> tileErrors(std::size_t(manifest->lods), 0.0);
        for (const detail::TileLevelRecord& level : tile.levels)
            if (level.level > 0 && level.level < manifest->lods) tileErrors[std::size_t(level.level)] = level.error;
        for (std::size_t l = 1; l < tileErrors.size(); ++l) tileErrors[l] = std::max(tileErrors[l], tileErrors[l - 1]);
        int chosen = 0;
        for (int l = manifest->lods - 1; l > 0; --l)
            if (distance > 0.0 && tileErrors[std::size_t(l)] * pixelsPerRadian / distance <= options.maxScreenError) {
                chosen = l;
                break;
            }
        const detail::TileLevelRecord* level = nullptr;
        for (const detail::TileLevelRecord& candidate : tile.levels)
            if (candidate.level == chosen) level = &candidate;
        if (!level || !level->file) continue;
        const meshing::TriangleMesh part = meshing::readGltf(bakeDir / level->file->path);
        ++stats.tilesPerLevel[std::size_t(chosen)];
        const auto base = std::uint32_t(merged.positions.size());
        const glm::dvec3 shift = part.origin - merged.origin;
        for (const glm::vec3& p : part.positions) merged.positions.emplace_back(glm::dvec3(p) + shift);
        merged.normals.insert(merged.normals.end(), part.normals.begin(), part.normals.end());
        for (std::uint32_t i : part.indices) merged.indices.push_back(base + i);
    }
    if (merged.normals.size() != merged.positions.size()) merged.normals.clear();
    stats.triangles = merged.triangleCount();

    SnapshotRequest request = options.request;
    request.cameraPosition = camera.position;
    request.cameraTarget = camera.target;
    request.fov = camera.fovYDegrees;
    request.turntable = 0;
    stats.render = renderSnapshots(scene, merged, request, context, 1, width, height, std::nullopt,
                                   [&](int, const render::Image& image) { sink(image); });
    return stats;
}

} // namespace strata::scene
