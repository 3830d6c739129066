// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The `strata` Python module (issue 28): the library, not the CLI, for
// NumPy and Blender. Each area binds itself in its own file.

#include "Bindings.h"

#include <strata/CacheMemory.h>

PYBIND11_MODULE(strata, m)
{
    m.doc() = R"(Strata: procedural terrain and caves, sampled into sparse OpenVDB level sets,
meshed without UVs and rendered with height-blended triplanar materials.

    import strata
    scene = strata.default_scene()            # or strata.load_scene("world.toml")
    grid = strata.sample(scene)               # the narrow-band level set
    mesh = strata.mesh(grid)                  # vertices, normals, triangles as NumPy arrays
    image = strata.render(scene, mesh, size=(640, 360))   # (360, 640, 4) uint8
    mesh.save("terrain.glb")

Long calls release the GIL, report to an optional `progress(fraction)` callable
and stop on Ctrl-C with KeyboardInterrupt. Errors: BadInputError (a ValueError
with file, line, key and value), FileError (an OSError), GLError (a
RuntimeError), MemoryError.)";
    m.attr("__version__") = STRATA_VERSION;
    strata::python::bindErrors(m);
    strata::python::bindScene(m);
    strata::python::bindField(m);
    strata::python::bindGrid(m);
    strata::python::bindMesh(m);
    strata::python::bindRender(m);
    strata::python::bindWorld(m);
    strata::python::bindBake(m);

    // The process-wide limit of the caches (CacheMemory.h): what the CLI's
    // --max-memory sets. Dropped entries are recomputed bit for bit.
    m.def("set_cache_memory_limit", [](std::uint64_t bytes) { strata::setCacheMemoryLimit(bytes); }, pybind11::arg("bytes"),
          "Bytes the caches (erosion grids, detail and talus blocks, worm caves) may hold together; 0 restores the "
          "default, a quarter of the machine's memory. A lower limit costs time, never changes results.");
    m.def("cache_memory_limit", [] { return strata::cacheMemoryLimit(); }, "The caches' limit now, bytes.");
    m.def("cache_memory_used", [] { return strata::cacheMemoryUsed(); }, "What the caches hold now, bytes.");
}
