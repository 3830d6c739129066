// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The streaming World for Python: chunks around points of interest, meshed
// in the background (TBB), dug and filled, their meshes as read-only arrays
// shared with the world (no copy).

#include "Bindings.h"

#include <strata/Error.h>
#include <strata/world/World.h>

#include <filesystem>

namespace strata::python {

namespace {

using world::ChunkKey;
using world::EditShape;
using world::World;

ChunkKey toKey(const py::handle& value)
{
    try {
        const auto t = value.cast<std::tuple<int, std::int32_t, std::int32_t, std::int32_t>>();
        return ChunkKey{std::get<0>(t), std::get<1>(t), std::get<2>(t), std::get<3>(t)};
    } catch (const py::cast_error&) {
        throw Error(ErrorKind::BadInput, "a chunk key is (level, x, y, z), not " + std::string(py::repr(value)),
                    {"", 0, "key", std::string(py::repr(value))});
    }
}

py::tuple fromKey(const ChunkKey& k) { return py::make_tuple(k.level, k.x, k.y, k.z); }

/// A chunk's mesh as a read-only Mesh sharing the world's buffers.
py::object chunkMeshObject(const std::shared_ptr<const world::ChunkMeshData>& data)
{
    if (!data) return py::none();
    std::shared_ptr<const meshing::TriangleMesh> mesh(data, &data->mesh); // keeps the chunk's data alive
    return py::cast(std::make_shared<Mesh>(Mesh{std::move(mesh), false}));
}

py::dict editResult(const world::EditResult& r)
{
    py::dict d;
    d["changed_voxels"] = r.changedVoxels;
    py::list marked;
    for (const ChunkKey& k : r.markedChunks) marked.append(fromKey(k));
    d["marked_chunks"] = marked;
    return d;
}

std::unique_ptr<World> makeWorld(const std::shared_ptr<const scene::Scene>& scene, std::optional<double> voxelSize,
                                 int chunkSize, int levels, double lodDistance, double viewRadius, int threads,
                                 std::optional<std::uint64_t> seed, bool lookAhead)
{
    world::WorldOptions options;
    options.voxelSize = voxelSize.value_or(scene->voxelSize);
    options.chunkSize = chunkSize;
    options.levels = levels;
    options.lodDistance = lodDistance;
    options.viewRadius = viewRadius;
    options.threads = threads;
    options.lookAhead = lookAhead;
    options.landform = scene::landformMasksForSeed(*scene, seed);
    options.rock = scene::rockMasksForSeed(*scene, seed);
    auto field = scene::fieldForSeed(*scene, seed);
    py::gil_scoped_release release;
    return std::make_unique<World>(std::move(field), options);
}

} // namespace

void bindWorld(py::module_& m)
{
    py::class_<EditShape>(m, "EditShape", "A shape for dig() and fill(), in world metres.")
        .def_static("sphere", [](const py::handle& centre, double radius) {
            EditShape s = EditShape::sphere(toVec3(centre, "centre"), radius);
            s.validate();
            return s;
        }, py::arg("centre"), py::arg("radius"))
        .def_static("box", [](const py::handle& centre, const py::handle& halfSize, double rounding) {
            EditShape s = EditShape::box(toVec3(centre, "centre"), toVec3(halfSize, "half_size"), rounding);
            s.validate();
            return s;
        }, py::arg("centre"), py::arg("half_size"), py::arg("rounding") = 0.0)
        .def_static("capsule", [](const py::handle& a, const py::handle& b, double radius) {
            EditShape s = EditShape::capsule(toVec3(a, "a"), toVec3(b, "b"), radius);
            s.validate();
            return s;
        }, py::arg("a"), py::arg("b"), py::arg("radius"))
        .def_static("path", [](const py::sequence& points, double radius) {
            std::vector<glm::dvec3> p;
            for (const py::handle& point : points) p.push_back(toVec3(point, "points"));
            EditShape s = EditShape::path(std::move(p), radius);
            s.validate();
            return s;
        }, py::arg("points"), py::arg("radius"), "A brush dragged along a polyline.")
        .def("distance", [](const EditShape& s, const py::handle& p) { return s.distance(toVec3(p, "point")); },
             py::arg("point"), "Signed distance in metres, negative inside.");

    py::class_<World>(m, "World",
                      "A streaming voxel world over a scene's field: chunks with levels of detail around points of\n"
                      "interest, meshed in the background, edited by dig() and fill(). poll() hands out new meshes.")
        .def(py::init(&makeWorld), py::arg("scene"), py::arg("voxel_size") = py::none(), py::arg("chunk_size") = 32,
             py::arg("levels") = 4, py::arg("lod_distance") = 0.0, py::arg("view_radius") = 0.0, py::arg("threads") = 0,
             py::arg("seed") = py::none(), py::arg("look_ahead") = true,
             "voxel_size: metres at level 0 (default the scene's); chunk_size: cells per chunk edge (8..128, power of 2);\n"
             "levels: 1..8; lod_distance, view_radius: metres (0: chosen from the chunk size); threads: 0 = all cores;\n"
             "look_ahead: mesh the chunks a moving point needs after its next chunk border before it crosses.")
        .def("set_points_of_interest", [](World& w, const py::sequence& points) {
            std::vector<glm::dvec3> p;
            for (const py::handle& point : points) p.push_back(toVec3(point, "points"));
            py::gil_scoped_release release;
            w.setPointsOfInterest(std::move(p));
        }, py::arg("points"), "Where the viewers are (world metres): the resident chunks follow them.")
        .def("move_to", [](World& w, const py::handle& point) {
            const glm::dvec3 p = toVec3(point, "point");
            py::gil_scoped_release release;
            w.setPointsOfInterest({p});
        }, py::arg("point"), "One point of interest: set_points_of_interest([point]).")
        .def("poll", [](World& w, std::size_t maxUpdates) {
            std::vector<world::ChunkUpdate> updates;
            {
                py::gil_scoped_release release;
                updates = w.poll(maxUpdates == 0 ? SIZE_MAX : maxUpdates);
            }
            py::list out;
            for (const world::ChunkUpdate& u : updates) out.append(py::make_tuple(fromKey(u.key), chunkMeshObject(u.mesh)));
            return out;
        }, py::arg("max_updates") = 0,
           "Finished chunk meshes since the last poll: a list of (key, mesh) where key is (level, x, y, z)\n"
           "and mesh a read-only Mesh to replace the chunk's, or None to drop it. max_updates: 0 = all.")
        .def("wait_idle", [](World& w) {
            py::gil_scoped_release release;
            w.waitIdle();
        }, "Blocks (GIL released) until every pending chunk is meshed.")
        .def_property_readonly("idle", &World::idle)
        .def("dig", [](World& w, const EditShape& shape, double smooth) {
            world::EditResult r;
            {
                py::gil_scoped_release release;
                r = w.dig(shape, smooth);
            }
            return editResult(r);
        }, py::arg("shape"), py::arg("smooth_radius") = 0.0,
           "Carves the shape out of the terrain; returns {'changed_voxels', 'marked_chunks'}.")
        .def("fill", [](World& w, const EditShape& shape, double smooth) {
            world::EditResult r;
            {
                py::gil_scoped_release release;
                r = w.fill(shape, smooth);
            }
            return editResult(r);
        }, py::arg("shape"), py::arg("smooth_radius") = 0.0, "Adds the shape as rock; returns like dig().")
        .def("save_edits", [](const World& w, const std::filesystem::path& path) { w.saveEdits(path); }, py::arg("path"))
        .def("load_edits", [](World& w, const std::filesystem::path& path) { return editResult(w.loadEdits(path)); },
             py::arg("path"))
        .def("density", [](const World& w, const py::handle& p) { return w.density(toVec3(p, "point")); }, py::arg("point"),
             "The edited density at a point.")
        .def("raycast", [](const World& w, const py::handle& origin, const py::handle& direction, double maxDistance) -> py::object {
            const auto hit = w.raycast(toVec3(origin, "origin"), toVec3(direction, "direction"), maxDistance);
            if (!hit) return py::none();
            py::dict d;
            d["position"] = fromVec3(hit->position);
            d["normal"] = fromVec3(hit->normal);
            d["distance"] = hit->distance;
            return d;
        }, py::arg("origin"), py::arg("direction"), py::arg("max_distance"),
           "The first surface hit along the ray: {'position', 'normal', 'distance'}, or None.")
        .def("chunk_mesh", [](const World& w, const py::handle& key) { return chunkMeshObject(w.chunkMesh(toKey(key))); },
             py::arg("key"), "The current mesh of a resident chunk (read-only Mesh), or None.")
        .def("resident_chunks", [](const World& w) {
            py::list out;
            for (const ChunkKey& k : w.residentChunks()) out.append(fromKey(k));
            return out;
        })
        .def("chunk_bounds", [](const World& w, const py::handle& key) {
            glm::dvec3 lo, hi;
            w.chunkBounds(toKey(key), lo, hi);
            return py::make_tuple(fromVec3(lo), fromVec3(hi));
        }, py::arg("key"))
        .def_property_readonly("stats", [](const World& w) {
            const world::WorldStats s = w.stats();
            py::dict d;
            d["generated"] = s.generated;
            d["remeshed"] = s.remeshed;
            d["evicted"] = s.evicted;
            d["discarded"] = s.discarded;
            d["resident"] = s.resident;
            d["with_surface"] = s.withSurface;
            d["pending"] = s.pending;
            d["holes"] = s.holes;
            d["in_flight"] = s.inFlight;
            d["mesh_bytes"] = s.meshBytes;
            d["prefetched"] = s.prefetched;
            d["prefetch_dropped"] = s.prefetchDropped;
            d["prefetch_held"] = s.prefetchHeld;
            return d;
        });
}

} // namespace strata::python
