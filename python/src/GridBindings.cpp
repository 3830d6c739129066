// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Sampling a scene into its narrow-band level set, and the grid as a
// Python object (save, counts, a dense copy of a box). The heavy OpenVDB
// code of the module lives here.

#include "Bindings.h"
#include "Progress.h"

#include <strata/Error.h>
#include <strata/meshing/GridIO.h>

#include <openvdb/openvdb.h>

#include <filesystem>

namespace strata::python {

namespace {

using GridPtr = std::shared_ptr<Grid>;

std::shared_ptr<Grid> sample(const std::shared_ptr<const scene::Scene>& input, std::optional<std::uint64_t> seed,
                             std::optional<std::string> preset, const py::object& quality, std::optional<double> voxelSize,
                             std::uint64_t maxMemory, const py::object& progressCallback)
{
    py::dict knobs;
    knobs["voxel_size"] = voxelSize ? py::object(py::float_(*voxelSize)) : py::none();
    const scene::QualityOverrides overrides = qualityOverrides(knobs, quality);
    auto grid = std::make_shared<Grid>();
    grid->quality = scene::resolveQuality(*input, preset, overrides);
    auto scene = std::make_shared<scene::Scene>(scene::applyQuality(*input, grid->quality));
    PythonProgress progress(progressCallback);
    grid->terrain = progress.run([&] { return scene::sampleTerrain(*scene, seed, maxMemory, std::ref(progress)); });
    grid->scene = std::move(scene);
    grid->source = input;
    grid->preset = preset;
    grid->overrides = overrides;
    return grid;
}

std::shared_ptr<Grid> readGrid(const std::filesystem::path& path)
{
    auto grid = std::make_shared<Grid>();
    {
        py::gil_scoped_release release;
        grid->terrain.grid = meshing::readLevelSet(path);
    }
    grid->quality.voxelSize = grid->terrain.grid->voxelSize().x();
    return grid;
}

openvdb::CoordBBox activeBox(const Grid& grid)
{
    return grid.terrain.grid->evalActiveVoxelBoundingBox();
}

py::tuple coordTuple(const openvdb::Coord& c) { return py::make_tuple(c.x(), c.y(), c.z()); }

openvdb::Coord toCoord(const py::handle& value, const char* what)
{
    const glm::dvec3 v = toVec3(value, what);
    for (int i = 0; i < 3; ++i) {
        if (v[i] != std::floor(v[i]) || std::abs(v[i]) > 1e9) {
            throw Error(ErrorKind::BadInput, std::string(what) + " must be three integer voxel indices",
                        {"", 0, what, std::string(py::str(value))});
        }
    }
    return openvdb::Coord(int(v.x), int(v.y), int(v.z));
}

/// Voxels [lo, hi] (inclusive, index space) as an (nx, ny, nz) float32
/// array indexed [i, j, k]; voxels outside the narrow band read the
/// background (± half width in metres, signed by side).
py::array_t<float> dense(const Grid& grid, const py::object& loValue, const py::object& hiValue)
{
    const openvdb::CoordBBox active = activeBox(grid);
    const openvdb::Coord lo = loValue.is_none() ? active.min() : toCoord(loValue, "min");
    const openvdb::Coord hi = hiValue.is_none() ? active.max() : toCoord(hiValue, "max");
    if (hi.x() < lo.x() || hi.y() < lo.y() || hi.z() < lo.z()) {
        throw Error(ErrorKind::BadInput, "dense(): max must be >= min on every axis", {"", 0, "max"});
    }
    const std::array<std::int64_t, 3> n{std::int64_t(hi.x()) - lo.x() + 1, std::int64_t(hi.y()) - lo.y() + 1,
                                        std::int64_t(hi.z()) - lo.z() + 1};
    const std::uint64_t count = std::uint64_t(n[0]) * std::uint64_t(n[1]) * std::uint64_t(n[2]);
    if (count > (std::uint64_t(1) << 32)) {
        throw Error(ErrorKind::BadInput, "dense(): the box holds " + std::to_string(count) +
                                              " voxels (more than 2^32): copy a smaller box",
                    {"", 0, "max"});
    }
    py::array_t<float> out({py::ssize_t(n[0]), py::ssize_t(n[1]), py::ssize_t(n[2])});
    float* values = out.mutable_data();
    {
        py::gil_scoped_release release;
        openvdb::FloatGrid::ConstAccessor access = grid.terrain.grid->getConstAccessor();
        std::size_t at = 0;
        for (int i = lo.x(); i <= hi.x(); ++i)
            for (int j = lo.y(); j <= hi.y(); ++j)
                for (int k = lo.z(); k <= hi.z(); ++k) values[at++] = access.getValue(openvdb::Coord(i, j, k));
    }
    return out;
}

} // namespace

void bindGrid(py::module_& m)
{
    openvdb::initialize();

    py::class_<Grid, GridPtr>(m, "Grid",
                              "A sparse narrow-band level set (OpenVDB FloatGrid): signed distances in metres,\n"
                              "negative in rock, stored only within half_width voxels of the surface.")
        .def_property_readonly("active_voxel_count", [](const Grid& g) { return g.terrain.grid->activeVoxelCount(); })
        .def_property_readonly("voxel_size", [](const Grid& g) { return g.terrain.grid->voxelSize().x(); }, "metres")
        .def_property_readonly("memory_bytes", [](const Grid& g) { return g.terrain.grid->memUsage(); })
        .def_property_readonly("background", [](const Grid& g) { return g.terrain.grid->background(); },
                               "the value outside the band (half width in metres)")
        .def_property_readonly("seed", [](const Grid& g) -> py::object {
            return g.scene ? py::object(py::int_(g.terrain.seed)) : py::none();
        }, "the terrain seed it was sampled with (None for a grid read from a file)")
        .def_property_readonly("scene", [](const Grid& g) -> py::object {
            return g.scene ? py::cast(std::const_pointer_cast<scene::Scene>(g.scene)) : py::none();
        }, "the scene it was sampled from, with the quality settings applied (None when read from a file)")
        .def_property_readonly("field", [](const Grid& g) -> py::object {
            return g.terrain.field ? py::cast(std::const_pointer_cast<terrain::DensityField>(g.terrain.field)) : py::none();
        }, "the density field it was sampled from (None when read from a file)")
        .def_property_readonly("index_bounds", [](const Grid& g) {
            const openvdb::CoordBBox box = activeBox(g);
            return py::make_tuple(coordTuple(box.min()), coordTuple(box.max()));
        }, "((i, j, k) min, (i, j, k) max) of the active voxels, inclusive; voxel (i, j, k) is centred on voxel_size * (i, j, k)")
        .def_property_readonly("stats", [](const Grid& g) {
            py::dict d;
            d["evaluated_points"] = g.terrain.stats.evaluatedPoints;
            d["bound_evaluations"] = g.terrain.stats.boundEvaluations;
            d["active_voxels"] = g.terrain.stats.activeVoxels;
            d["tiles_visited"] = g.terrain.stats.tilesVisited;
            d["tiles_skipped"] = g.terrain.stats.tilesSkipped;
            d["estimated_bytes"] = g.terrain.stats.estimatedBytes;
            return d;
        }, "what sampling did (all 0 for a grid read from a file)")
        .def("dense", &dense, py::arg("min") = py::none(), py::arg("max") = py::none(),
             "A dense copy of the voxels min..max (inclusive index triples; default: the active bounds)\n"
             "as an (nx, ny, nz) float32 array indexed [i, j, k].")
        .def("save", [](const Grid& g, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            meshing::writeGrid(*g.terrain.grid, path);
        }, py::arg("path"), "Writes the grid as a .vdb file (atomically); the same bytes as `strata generate`'s terrain.vdb.")
        .def("__repr__", [](const Grid& g) {
            return "<strata.Grid " + std::to_string(g.terrain.grid->activeVoxelCount()) + " active voxels of " +
                   std::to_string(g.terrain.grid->voxelSize().x()) + " m>";
        });

    m.def("sample", &sample, py::arg("scene"), py::arg("seed") = py::none(), py::arg("preset") = py::none(),
          py::arg("quality") = py::none(), py::arg("voxel_size") = py::none(), py::arg("max_memory") = 8ull << 30,
          py::arg("progress") = py::none(),
          "Samples the scene's terrain into a narrow-band level set over its region, as `strata generate` does.\n"
          "seed: another terrain seed; preset: 'fast' | 'balanced' | 'accurate'; quality: a dict of knobs\n"
          "({'voxel_size': 0.25, 'mesher': 'surface-nets', ...}, the knobs of docs/cli.md), kept for mesh();\n"
          "max_memory: refuse grids estimated above this many bytes (0: no limit); progress: progress(fraction).\n"
          "Releases the GIL; Ctrl-C raises KeyboardInterrupt.");
    m.def("read_grid", &readGrid, py::arg("path"), "Reads the level set of a .vdb file (the first float grid).");
}

} // namespace strata::python
