// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Meshing a grid, and meshes as NumPy arrays that view the library's own
// buffers (glm::vec3 is three packed floats; indices are uint32): no vertex
// data is copied on the way to Python.

#include "Bindings.h"

#include <strata/Error.h>
#include <strata/meshing/MeshFile.h>

#include <openvdb/openvdb.h>

#include <cstring>
#include <filesystem>

namespace strata::python {

namespace {

using meshing::TriangleMesh;
using MeshPtr = std::shared_ptr<Mesh>;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "glm::vec3 must be packed for zero-copy arrays");
static_assert(sizeof(glm::vec2) == 2 * sizeof(float) && sizeof(glm::vec4) == 4 * sizeof(float));

/// An (rows, cols) array over `data`, alive as long as `owner` (the Python Mesh).
template <class T> py::array view(const T* data, std::size_t rows, std::size_t cols, const py::handle& owner, bool writable)
{
    py::array array(py::dtype::of<T>(), {py::ssize_t(rows), py::ssize_t(cols)},
                    {py::ssize_t(cols * sizeof(T)), py::ssize_t(sizeof(T))}, data, owner);
    if (!writable) array.attr("setflags")(py::arg("write") = false);
    return array;
}

py::object optionalView(const float* data, std::size_t count, std::size_t rows, std::size_t cols, const py::object& self)
{
    if (count == 0) return py::none();
    const Mesh& mesh = self.cast<const Mesh&>();
    return view(data, rows, cols, self, mesh.writable);
}

/// The sampling knobs are the grid's: asking mesh() for them is a mistake.
void refuseSamplingKnobs(const scene::QualityOverrides& overrides)
{
    for (const char* key : {"voxel_size", "voxel_scale", "half_width"}) {
        if (overrides.count(key)) {
            throw Error(ErrorKind::BadInput,
                        std::string(key) + " is a sampling setting: give it to sample(), which made this grid",
                        {"", 0, key, overrides.at(key)});
        }
    }
}

MeshPtr meshGrid(const Grid& grid, std::optional<std::string> preset, std::optional<std::string> mesher,
                 std::optional<double> adaptivity, std::optional<std::string> normals, std::optional<int> projection,
                 std::optional<double> simplify, const py::object& quality)
{
    py::dict knobs;
    knobs["mesher"] = mesher ? py::object(py::str(*mesher)) : py::none();
    knobs["adaptivity"] = adaptivity ? py::object(py::float_(*adaptivity)) : py::none();
    knobs["normals"] = normals ? py::object(py::str(*normals)) : py::none();
    knobs["projection"] = projection ? py::object(py::int_(*projection)) : py::none();
    knobs["simplify"] = simplify ? py::object(py::float_(*simplify)) : py::none();
    const scene::QualityOverrides overrides = qualityOverrides(knobs, quality);
    refuseSamplingKnobs(overrides);

    auto out = std::make_shared<TriangleMesh>();
    if (grid.scene) {
        // sample()'s preset and knobs, then these: one `strata generate`
        // run's settings. The sampling ones stay the grid's own.
        scene::QualityOverrides all = grid.overrides;
        for (const auto& [key, value] : overrides) all[key] = value;
        scene::QualitySettings q = scene::resolveQuality(*grid.source, preset ? preset : grid.preset, all);
        q.voxelSize = grid.quality.voxelSize;
        q.halfWidth = grid.quality.halfWidth;
        const scene::Scene scene = scene::applyQuality(*grid.source, q);
        py::gil_scoped_release release;
        *out = scene::meshTerrain(scene, q, grid.terrain);
    } else {
        // A grid from a file: no scene, no field; positions relative to the
        // centre of its active voxels, for float precision far from the origin.
        const scene::Scene defaults;
        scene::QualitySettings q = scene::resolveQuality(defaults, preset, overrides);
        q.voxelSize = grid.terrain.grid->voxelSize().x();
        if (q.normals == "field") {
            throw Error(ErrorKind::BadInput, "normals = 'field' needs the density field: this grid was read from a file",
                        {"", 0, "normals", "field"});
        }
        const openvdb::CoordBBox box = grid.terrain.grid->evalActiveVoxelBoundingBox();
        const openvdb::Vec3d centre = grid.terrain.grid->indexToWorld(box.getCenter());
        py::gil_scoped_release release;
        *out = scene::meshWithQuality(*grid.terrain.grid, q, {}, glm::dvec3(centre.x(), centre.y(), centre.z()));
    }
    return std::make_shared<Mesh>(Mesh{std::move(out), true});
}

/// A mesh from arrays (copied: the library's buffers are std::vectors).
MeshPtr meshFromArrays(const py::array_t<float, py::array::c_style | py::array::forcecast>& vertices,
                       const py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>& triangles,
                       const py::object& normalsValue, const py::object& originValue)
{
    if (vertices.ndim() != 2 || vertices.shape(1) != 3) {
        throw Error(ErrorKind::BadInput, "vertices must be an (N, 3) array", {"", 0, "vertices"});
    }
    if (triangles.ndim() != 2 || triangles.shape(1) != 3) {
        throw Error(ErrorKind::BadInput, "triangles must be an (M, 3) array of vertex indices", {"", 0, "triangles"});
    }
    auto mesh = std::make_shared<TriangleMesh>();
    const std::size_t n = std::size_t(vertices.shape(0));
    mesh->positions.resize(n);
    std::memcpy(mesh->positions.data(), vertices.data(), n * sizeof(glm::vec3));
    mesh->indices.resize(std::size_t(triangles.size()));
    const std::int64_t* t = triangles.data();
    for (std::size_t i = 0; i < mesh->indices.size(); ++i) {
        if (t[i] < 0 || std::uint64_t(t[i]) >= n) {
            throw Error(ErrorKind::BadInput,
                        "triangles[" + std::to_string(i / 3) + "] names vertex " + std::to_string(t[i]) + " of " +
                            std::to_string(n),
                        {"", 0, "triangles", std::to_string(t[i])});
        }
        mesh->indices[i] = std::uint32_t(t[i]);
    }
    if (!normalsValue.is_none()) {
        const auto normals = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(normalsValue);
        if (!normals || normals.ndim() != 2 || normals.shape(0) != py::ssize_t(n) || normals.shape(1) != 3) {
            throw Error(ErrorKind::BadInput, "normals must be an (N, 3) array, one per vertex", {"", 0, "normals"});
        }
        mesh->normals.resize(n);
        std::memcpy(mesh->normals.data(), normals.data(), n * sizeof(glm::vec3));
    }
    if (!originValue.is_none()) mesh->origin = toVec3(originValue, "origin");
    return std::make_shared<Mesh>(Mesh{std::move(mesh), true});
}

} // namespace

void bindMesh(py::module_& m)
{
    py::class_<Mesh, MeshPtr>(m, "Mesh",
                              "An indexed triangle mesh: positions in metres relative to `origin` (float precision far\n"
                              "from the world origin), counter-clockwise triangles seen from outside, unit normals.\n"
                              "The arrays view the mesh's own memory (no copy); they keep the mesh alive.")
        .def(py::init(&meshFromArrays), py::arg("vertices"), py::arg("triangles"), py::arg("normals") = py::none(),
             py::arg("origin") = py::none(), "A mesh from (N, 3) vertices, (M, 3) triangles and optional (N, 3) normals.")
        .def_property_readonly("vertices", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return view(reinterpret_cast<const float*>(m.mesh->positions.data()), m.mesh->positions.size(), 3, self, m.writable);
        }, "(N, 3) float32 positions, metres relative to origin")
        .def_property_readonly("normals", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return optionalView(reinterpret_cast<const float*>(m.mesh->normals.data()), m.mesh->normals.size(),
                                m.mesh->normals.size(), 3, self);
        }, "(N, 3) float32 unit normals, or None")
        .def_property_readonly("triangles", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return view(m.mesh->indices.data(), m.mesh->indices.size() / 3, 3, self, m.writable);
        }, "(M, 3) uint32 vertex indices")
        .def_property_readonly("surface", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return optionalView(reinterpret_cast<const float*>(m.mesh->surface.data()), m.mesh->surface.size(),
                                m.mesh->surface.size(), 2, self);
        }, "(N, 2) float32 cavity and cover per vertex (when a layer rule reads them), or None")
        .def_property_readonly("landform", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return optionalView(reinterpret_cast<const float*>(m.mesh->landform.data()), m.mesh->landform.size(),
                                m.mesh->landform.size(), 4, self);
        }, "(N, 4) float32 flow, wear, deposition, water per vertex (when a layer rule reads them), or None")
        .def_property_readonly("rock", [](const py::object& self) {
            const Mesh& m = self.cast<const Mesh&>();
            return optionalView(reinterpret_cast<const float*>(m.mesh->rock.data()), m.mesh->rock.size(),
                                m.mesh->rock.size(), 2, self);
        }, "(N, 2) float32 rock hardness and bed index per vertex (when a layer rule reads them), or None")
        .def_property_readonly("origin", [](const Mesh& m) { return fromVec3(m.mesh->origin); },
                               "(x, y, z) in metres, double: world position = origin + vertex")
        .def_property_readonly("vertex_count", [](const Mesh& m) { return m.mesh->vertexCount(); })
        .def_property_readonly("triangle_count", [](const Mesh& m) { return m.mesh->triangleCount(); })
        .def("save", [](const Mesh& m, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            meshing::writeMeshFile(*m.mesh, path);
        }, py::arg("path"),
           "Writes the mesh atomically; the format follows the extension (.glb, .ply, .obj, .stl, .off).\n"
           "A .glb holds the same bytes as `strata generate`'s terrain.glb for the same mesh.")
        .def("__repr__", [](const Mesh& m) {
            return "<strata.Mesh " + std::to_string(m.mesh->vertexCount()) + " vertices, " +
                   std::to_string(m.mesh->triangleCount()) + " triangles>";
        });

    m.def("mesh", &meshGrid, py::arg("grid"), py::arg("preset") = py::none(), py::arg("mesher") = py::none(),
          py::arg("adaptivity") = py::none(), py::arg("normals") = py::none(), py::arg("projection") = py::none(),
          py::arg("simplify") = py::none(), py::arg("quality") = py::none(),
          "Meshes a grid as `strata generate` would: its scene's quality settings, then these overrides.\n"
          "mesher: 'volume' | 'surface-nets' | 'dual-contouring'; adaptivity: 0..1 (volume);\n"
          "normals: 'grid' | 'field' | 'face'; projection: Newton steps onto the surface; simplify: triangle fraction.\n"
          "The layer attributes (surface, landform, rock) come with it when the scene's layers read them. GIL released.");
    m.def("read_mesh", [](const std::filesystem::path& path) {
        auto mesh = std::make_shared<TriangleMesh>();
        {
            py::gil_scoped_release release;
            *mesh = meshing::readMesh(path);
        }
        return std::make_shared<Mesh>(Mesh{std::move(mesh), true});
    }, py::arg("path"), "Reads a mesh file (.glb, .gltf, .ply, .obj, .stl, .off).");
}

} // namespace strata::python
