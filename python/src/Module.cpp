// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The `strata` Python module (issue 28): the library, not the CLI, for
// NumPy and Blender. Each area binds itself in its own file.

#include "Bindings.h"

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
}
