// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// A voxel game's frame loop on strata::world::World: a player walks across
// procedural hills, digging a tunnel that descends under the ground as it
// goes; the world streams chunks around the player on its own threads, and
// each frame the game only polls for finished meshes (here it just holds them,
// as an engine would hold its GPU buffers).
//
//   strata_voxel_game [--frames N] [--speed M_PER_S] [--view-radius M] [--threads N] [--snapshot OUT.png]
//
// Prints one line per frame: chunks generated, re-meshed and evicted during
// the frame, updates received, chunks still pending, and the milliseconds the
// frame spent in World calls: the ground query (a ray cast), the dig and poll().

#include <strata/Error.h>
#include <strata/render/EglContext.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/Image.h>
#include <strata/terrain/TerrainField.h>
#include <strata/world/World.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <string>
#include <thread>

namespace {

using Clock = std::chrono::steady_clock;
using strata::world::ChunkKey;
using strata::world::ChunkMeshData;

double ms(Clock::duration d)
{
    return std::chrono::duration<double, std::milli>(d).count();
}

/// Everything the game holds, merged into one mesh (relative to `origin`).
strata::meshing::TriangleMesh merge(const std::map<ChunkKey, std::shared_ptr<const ChunkMeshData>>& held,
                                    const glm::dvec3& origin)
{
    strata::meshing::TriangleMesh out;
    out.origin = origin;
    for (const auto& [key, data] : held) {
        const auto base = std::uint32_t(out.positions.size());
        const glm::dvec3 shift = data->mesh.origin - origin;
        for (const glm::vec3& p : data->mesh.positions) out.positions.emplace_back(glm::dvec3(p) + shift);
        out.normals.insert(out.normals.end(), data->mesh.normals.begin(), data->mesh.normals.end());
        for (std::uint32_t i : data->mesh.indices) out.indices.push_back(base + i);
    }
    return out;
}

} // namespace

int main(int argc, char** argv)
{
    int frames = 90;
    double speed = 12.0; // metres per second
    int threads = 0;
    double viewRadius = 200.0;
    std::string snapshot;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
        else if (arg == "--speed" && i + 1 < argc) speed = std::atof(argv[++i]);
        else if (arg == "--threads" && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (arg == "--view-radius" && i + 1 < argc) viewRadius = std::atof(argv[++i]);
        else if (arg == "--snapshot" && i + 1 < argc) snapshot = argv[++i];
        else {
            std::cerr << "usage: " << argv[0]
                      << " [--frames N] [--speed M_PER_S] [--view-radius M] [--threads N] [--snapshot OUT.png]\n";
            return 2;
        }
    }
    try {
        strata::terrain::TerrainOptions terrain;
        terrain.seed = 42;
        auto field = std::make_shared<strata::terrain::TerrainField>(terrain);

        strata::world::WorldOptions options; // 0.5 m voxels, 32³ chunks, 4 LOD levels
        options.threads = threads;
        options.viewRadius = viewRadius;
        strata::world::World world(field, options);
        // The untouched terrain, for walking on: a world without points of
        // interest streams nothing, but answers queries.
        const strata::world::World pristine(field, options);

        const double dt = 1.0 / 30.0;
        std::map<ChunkKey, std::shared_ptr<const ChunkMeshData>> held; // the game's "GPU buffers"
        strata::world::WorldStats last = world.stats();
        glm::dvec3 previousDig(0.0);
        bool digging = false;
        std::printf("frame  player(x, y, z)            gen  remesh  evict  updates  pending  ms: query   dig   poll\n");
        for (int frame = 0; frame < frames; ++frame) {
            const Clock::time_point start = Clock::now();
            const double x = speed * dt * frame;
            const double z = 20.0 * std::sin(x / 60.0);
            // Stand on the ground: a ray cast straight down, no mesh needed.
            const auto ground = pristine.raycast(glm::dvec3(x, 120.0, z), glm::dvec3(0.0, -1.0, 0.0), 300.0);
            const glm::dvec3 player = ground ? ground->position + glm::dvec3(0.0, 1.8, 0.0) : glm::dvec3(x, 0.0, z);
            world.setPointsOfInterest({player});
            const Clock::time_point queried = Clock::now();

            // The tunnel: a brush stroke from the last dig point, 2.5 m in
            // radius, starting as an open trench and going down 0.1 m per
            // metre walked.
            const double depth = std::min(10.0, 1.5 + 0.1 * x);
            const glm::dvec3 dig = (ground ? ground->position : player) - glm::dvec3(0.0, depth, 0.0);
            if (digging) world.dig(strata::world::EditShape::path({previousDig, dig}, 2.5), 1.0);
            previousDig = dig;
            digging = true;
            const Clock::time_point edited = Clock::now();

            std::size_t updates = 0;
            for (const strata::world::ChunkUpdate& u : world.poll()) {
                ++updates;
                if (u.mesh) held[u.key] = u.mesh; // upload
                else held.erase(u.key);           // free
            }
            const Clock::time_point polled = Clock::now();
            const strata::world::WorldStats s = world.stats();
            std::printf("%5d  (%7.1f, %6.1f, %6.1f)  %5llu  %6llu  %5llu  %7zu  %7zu  %6.2f %6.2f %6.2f\n", frame,
                        player.x, player.y, player.z, (unsigned long long)(s.generated - last.generated),
                        (unsigned long long)(s.remeshed - last.remeshed), (unsigned long long)(s.evicted - last.evicted),
                        updates, s.pending, ms(queried - start), ms(edited - queried), ms(polled - edited));
            last = s;
            // The rest of the frame belongs to the game; the world keeps working.
            std::this_thread::sleep_until(start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(dt)));
        }

        world.waitIdle();
        for (const strata::world::ChunkUpdate& u : world.poll()) {
            if (u.mesh) held[u.key] = u.mesh;
            else held.erase(u.key);
        }
        const strata::world::WorldStats s = world.stats();
        std::size_t triangles = 0;
        for (const auto& [key, data] : held) triangles += data->mesh.triangleCount();
        std::printf("done: %zu resident chunks, %zu with surface (%zu triangles), %llu generated, %llu re-meshed, "
                    "%llu evicted, %zu edited voxels (%.1f MiB of meshes)\n",
                    s.resident, held.size(), triangles, (unsigned long long)s.generated,
                    (unsigned long long)s.remeshed, (unsigned long long)s.evicted, s.editVoxels,
                    double(s.meshBytes) / (1024.0 * 1024.0));

        if (!snapshot.empty()) {
            const glm::dvec3 player = previousDig;
            const strata::meshing::TriangleMesh mesh = merge(held, player);
            strata::render::SnapshotOptions view;
            view.width = 960;
            view.height = 540;
            view.camera.position = player + glm::dvec3(-14.0, 14.0, 16.0);
            view.camera.target = player + glm::dvec3(-10.0, 0.0, 0.0);
            view.lighting.exposure = 0.55f;
            view.shadows.enabled = false; // one shadow map over 400 m of terrain is too coarse for a 5 m tunnel
            view.material.albedoTint = glm::vec3(0.55f, 0.5f, 0.45f);
            view.camera.farPlane = 1000.0;
            strata::render::MeshView meshView;
            meshView.positions = mesh.positions.data();
            meshView.normals = mesh.normals.data();
            meshView.vertexCount = mesh.positions.size();
            meshView.indices = mesh.indices.data();
            meshView.indexCount = mesh.indices.size();
            meshView.origin = mesh.origin;
            auto context = strata::render::EglContext::create();
            strata::render::writeImage(strata::render::renderSnapshot(*context, meshView, view), snapshot);
            std::printf("snapshot: %s\n", snapshot.c_str());
        }
        return held.empty() ? 1 : 0;
    } catch (const strata::Error& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 2;
    }
}
