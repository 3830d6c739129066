// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The streaming world's figures (a program that prints numbers and asserts
// nothing): time from an edit to its re-meshed chunks, chunks generated per
// second under a moving point of interest, memory per resident chunk, and
// triangles and time per LOD level. The terrain is the default TerrainField
// (fBm hills and cave tunnels, seed 1), 0.5 m voxels, 32³ chunks.
//
//   world_bench [--quick|--lod|--stream] [--noise-version=1|2]   (--quick: fewer repetitions, shorter runs;
//       --lod: LOD levels only; --stream: streaming only, with look-ahead and without; the noise version of
//       the terrain's fBms, 2 by default, as the examples)

#include <strata/terrain/TerrainField.h>
#include <strata/world/World.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <thread>
#include <vector>

using namespace strata;
using Clock = std::chrono::steady_clock;

namespace {

double seconds(Clock::duration d)
{
    return std::chrono::duration<double>(d).count();
}

/// CPU time of the calling thread (seconds): what poll() itself costs, without
/// the time the thread waits for a core on a loaded machine.
double threadCpuSeconds()
{
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double percentile(std::vector<double> v, double q)
{
    if (v.empty()) return 0.0;
    std::sort(v.begin(), v.end());
    const double pos = q * double(v.size() - 1);
    const std::size_t i = std::size_t(pos);
    const double f = pos - double(i);
    return i + 1 < v.size() ? v[i] * (1.0 - f) + v[i + 1] * f : v.back();
}

std::shared_ptr<terrain::TerrainField> terrainField(int noiseVersion)
{
    terrain::TerrainOptions options;
    options.noiseVersion = noiseVersion;
    return std::make_shared<terrain::TerrainField>(options);
}

glm::dvec3 groundBelow(const world::World& w, double x, double z)
{
    const auto hit = w.raycast(glm::dvec3(x, 150.0, z), glm::dvec3(0.0, -1.0, 0.0), 400.0);
    return hit ? hit->position : glm::dvec3(x, 0.0, z);
}

void editLatency(const std::shared_ptr<terrain::TerrainField>& field, bool quick)
{
    world::WorldOptions options;
    options.viewRadius = 100.0;
    world::World w(field, options);
    const glm::dvec3 poi = groundBelow(w, 0.0, 0.0);
    w.setPointsOfInterest({poi});
    const Clock::time_point warm = Clock::now();
    w.waitIdle();
    w.poll();
    std::printf("warm-up: %zu resident chunks (%zu with surface) meshed in %.2f s\n", w.stats().resident,
                w.stats().withSurface, seconds(Clock::now() - warm));

    for (const double radius : {2.0, 10.0}) {
        const int repeats = quick ? 8 : (radius < 5.0 ? 60 : 20);
        std::vector<double> total, edit, marked;
        for (int i = 0; i < repeats; ++i) {
            // Digs walk along a line on the ground near the point of interest,
            // alternating with fills so the terrain does not run out of rock.
            const double x = -6.0 + 12.0 * double(i % 6) / 5.0, z = 3.0 * double(i % 4);
            const glm::dvec3 centre = groundBelow(w, x, z) - glm::dvec3(0.0, 0.5 * radius, 0.0);
            const Clock::time_point t0 = Clock::now();
            const world::EditResult r = (i % 2 == 0) ? w.dig(world::EditShape::sphere(centre, radius))
                                                     : w.fill(world::EditShape::sphere(centre, radius));
            const Clock::time_point t1 = Clock::now();
            w.waitIdle();
            const Clock::time_point t2 = Clock::now();
            w.poll();
            edit.push_back(1e3 * seconds(t1 - t0));
            total.push_back(1e3 * seconds(t2 - t0));
            marked.push_back(double(r.markedChunks.size()));
        }
        std::printf("%4.0f m sphere edit -> re-meshed chunks available: median %.1f ms, p99 %.1f ms "
                    "(the edit call itself: median %.1f ms; chunks re-meshed per edit: median %.0f) over %d edits\n",
                    radius, percentile(total, 0.5), percentile(total, 0.99), percentile(edit, 0.5),
                    percentile(marked, 0.5), repeats);
        if (radius < 5.0)
            std::printf("     = %.0f edits per second on the same few chunks, edit to mesh\n",
                        1e3 / percentile(total, 0.5));
    }
    const world::WorldStats s = w.stats();
    std::printf("edit grid after the edits: %zu voxels, %.2f MiB\n", s.editVoxels,
                double(s.editBytes) / (1024.0 * 1024.0));
}

void streaming(const std::shared_ptr<terrain::TerrainField>& field, bool quick, bool lookAhead)
{
    std::printf("-- look-ahead %s --\n", lookAhead ? "on (the default)" : "off");
    world::WorldOptions options;
    options.viewRadius = 200.0;
    options.lookAhead = lookAhead;
    world::World w(field, options);
    double x = 0.0;
    // The point moves at this height throughout: a first frame at another
    // height would change the partition at once and count as holes.
    const double height = 10.0;
    w.setPointsOfInterest({glm::dvec3(x, height, 0.0)});
    const Clock::time_point warm = Clock::now();
    w.waitIdle();
    w.poll();
    world::WorldStats s = w.stats();
    std::printf("initial fill (view radius 200 m): %zu chunks (%zu with surface) in %.2f s = %.0f chunks/s\n",
                s.resident, s.withSurface, seconds(Clock::now() - warm),
                double(s.generated) / seconds(Clock::now() - warm));
    std::size_t withSurface = 0, meshBytes = 0;
    for (const world::ChunkKey& key : w.residentChunks())
        if (auto m = w.chunkMesh(key); m && !m->mesh.indices.empty()) {
            ++withSurface;
            meshBytes += m->memoryBytes();
        }
    std::size_t level0 = 0;
    for (const world::ChunkKey& key : w.residentChunks()) level0 += key.level == 0;
    std::printf("memory: meshes %.1f KiB per resident chunk (all %zu), %.1f KiB per chunk with surface (%zu); "
                "kept samples (level 0 only) %.1f MiB = %.1f KiB per resident level-0 chunk (%zu)\n",
                double(s.meshBytes) / 1024.0 / double(s.resident), s.resident,
                double(meshBytes) / 1024.0 / double(withSurface), withSurface,
                double(s.cacheBytes) / (1024.0 * 1024.0), double(s.cacheBytes) / 1024.0 / double(level0), level0);

    const double frame = 1.0 / 60.0;
    for (const double speed : {10.0, 50.0, 200.0}) {
        const double duration = quick ? 2.0 : 6.0;
        const world::WorldStats before = w.stats();
        const Clock::time_point start = Clock::now();
        std::vector<double> pollMs, pollCpuMs, pending, holes;
        std::size_t retained = 0;
        int frames = 0;
        while (seconds(Clock::now() - start) < duration) {
            const Clock::time_point f0 = Clock::now();
            const double c0 = threadCpuSeconds();
            x += speed * frame;
            w.setPointsOfInterest({glm::dvec3(x, height, 0.0)});
            w.poll();
            pollCpuMs.push_back(1e3 * (threadCpuSeconds() - c0));
            pollMs.push_back(1e3 * seconds(Clock::now() - f0));
            const world::WorldStats now = w.stats();
            retained = std::max(retained, now.retained);
            holes.push_back(double(now.holes)); // every frame: the view must be whole from the start
            // Pending after the first second: the backlog once the motion is under way.
            if (seconds(Clock::now() - start) >= 1.0) pending.push_back(double(now.pending));
            ++frames;
            std::this_thread::sleep_until(f0 + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(frame)));
        }
        const double elapsed = seconds(Clock::now() - start);
        const world::WorldStats after = w.stats();
        std::printf("POI at %3.0f m/s for %.1f s: %.0f chunks generated/s, %.0f re-meshed/s (LOD changes), "
                    "%.0f evicted/s, %zu pending at the end (after the first second: median %.0f, p95 %.0f, max %.0f), "
                    "holes in the view (chunks with nothing shown) in any frame: median %.0f, p95 %.0f, max %.0f, "
                    "poll() median %.2f ms, p99 %.2f ms, max %.2f ms over %d "
                    "frames (CPU time of the polling thread: median %.2f ms, p99 %.2f ms, max %.2f ms); at most %zu "
                    "chunks retained until replaced; meshed ahead: %.0f used/s, %.0f dropped/s, %zu held at the end "
                    "(%.1f MiB)\n",
                    speed, elapsed, double(after.generated - before.generated) / elapsed,
                    double(after.remeshed - before.remeshed) / elapsed,
                    double(after.evicted - before.evicted) / elapsed, after.pending, percentile(pending, 0.5),
                    percentile(pending, 0.95), percentile(pending, 1.0), percentile(holes, 0.5), percentile(holes, 0.95),
                    percentile(holes, 1.0), percentile(pollMs, 0.5),
                    percentile(pollMs, 0.99), percentile(pollMs, 1.0), frames, percentile(pollCpuMs, 0.5),
                    percentile(pollCpuMs, 0.99), percentile(pollCpuMs, 1.0), retained,
                    double(after.prefetched - before.prefetched) / elapsed,
                    double(after.prefetchDropped - before.prefetchDropped) / elapsed, after.prefetchHeld,
                    double(after.prefetchBytes) / (1024.0 * 1024.0));
    }
}

void lodLevels(const std::shared_ptr<terrain::TerrainField>& field)
{
    // Level l of a world with 0.5 m voxels samples the same lattice points as
    // level 0 of a world with 0.5·2^l m voxels: mesh the chunks within 64 m
    // of the origin at each level and count the triangles of the same
    // 128 m × 128 m square.
    for (int level = 0; level < 4; ++level) {
        world::WorldOptions options;
        options.voxelSize = 0.5 * double(1 << level);
        options.levels = 1;
        options.viewRadius = 64.0;
        world::World w(field, options);
        w.setPointsOfInterest({glm::dvec3(0.0, 0.0, 0.0)});
        const Clock::time_point t0 = Clock::now();
        w.waitIdle();
        const double elapsed = seconds(Clock::now() - t0);
        std::size_t triangles = 0, chunks = 0, inSquare = 0;
        for (const world::ChunkKey& key : w.residentChunks())
            if (auto m = w.chunkMesh(key); m && !m->mesh.indices.empty()) {
                triangles += m->mesh.triangleCount();
                ++chunks;
                const auto& p = m->mesh.positions;
                const auto& idx = m->mesh.indices;
                for (std::size_t t = 0; t < idx.size(); t += 3) {
                    const glm::dvec3 c = m->mesh.origin + glm::dvec3(p[idx[t]] + p[idx[t + 1]] + p[idx[t + 2]]) / 3.0;
                    if (std::abs(c.x) < 64.0 && std::abs(c.z) < 64.0) ++inSquare;
                }
            }
        std::printf("LOD %d (%.1f m cells): %zu triangles in the 128 m x 128 m square around the origin; "
                    "%zu chunks with surface of %zu resident (%zu triangles), %.2f s wall on %d threads = %.1f ms "
                    "per chunk per thread, %.0f triangles per chunk with surface\n",
                    level, options.voxelSize, inSquare, chunks, w.stats().resident, triangles, elapsed,
                    w.options().threads, 1e3 * elapsed * w.options().threads / double(w.stats().resident),
                    double(triangles) / double(chunks));
    }
}

} // namespace

int main(int argc, char** argv)
{
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const bool lodOnly = argc > 1 && std::strcmp(argv[1], "--lod") == 0;
    const bool streamOnly = argc > 1 && std::strcmp(argv[1], "--stream") == 0;
    // The examples' noise version unless told (the last argument).
    int noiseVersion = 2;
    if (argc > 1 && std::strncmp(argv[argc - 1], "--noise-version=", 16) == 0) noiseVersion = std::atoi(argv[argc - 1] + 16);
    if (noiseVersion != 1 && noiseVersion != 2) {
        std::fprintf(stderr, "world_bench: --noise-version=%s: 1 or 2\n", argv[argc - 1] + 16);
        return 2;
    }
    std::printf("terrain: TerrainField, noise version %d\n", noiseVersion);
    const auto field = terrainField(noiseVersion);
    if (streamOnly) {
        std::printf("== streaming ==\n");
        streaming(field, false, true);
        streaming(field, false, false);
        return 0;
    }
    std::printf("== LOD levels ==\n");
    lodLevels(field);
    if (lodOnly) return 0;
    std::printf("== edits ==\n");
    editLatency(field, quick);
    std::printf("== streaming ==\n");
    streaming(field, quick, true);
    if (!quick) streaming(field, quick, false);
    return 0;
}
