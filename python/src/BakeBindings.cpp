// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Baking a world into tiles with levels of detail (OGC 3D Tiles), as
// `strata bake` does, from Python.

#include "Bindings.h"
#include "Progress.h"

#include <strata/scene/Bake.h>

#include <filesystem>

namespace strata::python {

namespace {

py::dict bake(const std::shared_ptr<const scene::Scene>& scene, const std::filesystem::path& outputDir, double tileSize,
              int lods, const std::string& tiles, std::optional<std::uint64_t> seed, int threads, bool grids, bool force,
              std::uint64_t maxMemory, double skirtDepth, const py::object& progressCallback)
{
    scene::BakeOptions options;
    options.outputDir = outputDir;
    options.tileSize = tileSize;
    options.lods = lods;
    options.tiles = tiles;
    options.seed = seed;
    options.threads = threads;
    options.grids = grids;
    options.force = force;
    options.maxMemoryBytes = maxMemory;
    options.skirtDepth = skirtDepth;
    const scene::BakePlan plan = scene::planBake(*scene, options);
    PythonProgress progress(progressCallback);
    PythonObserver observer(progress);
    const scene::BakeSummary summary = progress.run([&] { return scene::bake(*scene, options, plan, &observer); });
    py::dict d;
    d["tiles"] = summary.tiles;
    d["baked"] = summary.baked;
    d["kept"] = summary.kept;
    d["missing"] = summary.missing;
    d["triangles_per_level"] = summary.trianglesPerLevel;
    d["files_per_level"] = summary.filesPerLevel;
    d["bytes_per_level"] = summary.bytesPerLevel;
    d["error_per_level"] = summary.errorPerLevel;
    d["seconds"] = summary.seconds;
    d["tile_size"] = plan.tileSize;
    d["voxel_size"] = plan.voxelSize;
    d["seed"] = plan.seed;
    return d;
}

} // namespace

void bindBake(py::module_& m)
{
    m.def("bake", &bake, py::arg("scene"), py::arg("out_dir"), py::arg("tile_size") = 0.0, py::arg("lods") = 3,
          py::arg("tiles") = "all", py::arg("seed") = py::none(), py::arg("threads") = 0, py::arg("grids") = true,
          py::arg("force") = false, py::arg("max_memory") = 8ull << 30, py::arg("skirt_depth") = 0.0,
          py::arg("progress") = py::none(),
          "Bakes the scene's world into out_dir as `strata bake` does: tiles/L/X_Z.glb with levels of detail,\n"
          "grids/X_Z.vdb, tileset.json (3D Tiles) and manifest.json. tile_size: metres (0: 256 voxels);\n"
          "lods: 1..8; tiles: 'all' or indices and ranges ('0-63,70'); a folder of the same bake resumes.\n"
          "Returns a summary dict. GIL released; Ctrl-C stops after the tiles in flight (KeyboardInterrupt).");
}

} // namespace strata::python
