// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once

/// \file
/// What the binding files share: one bind function per area (Module.cpp calls
/// them in order), the Python-side holders of library objects, and the
/// helpers that turn Python values into library ones.

#include <strata/meshing/TriangleMesh.h>
#include <strata/scene/Pipeline.h>
#include <strata/scene/Quality.h>
#include <strata/scene/Scene.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <glm/vec3.hpp>

#include <memory>
#include <optional>
#include <string>

namespace strata::python {

namespace py = pybind11;

void bindErrors(py::module_& m);
void bindScene(py::module_& m);
void bindField(py::module_& m);
void bindGrid(py::module_& m);
void bindMesh(py::module_& m);
void bindRender(py::module_& m);
void bindWorld(py::module_& m);
void bindBake(py::module_& m);

/// A sampled grid with what made it: the scene as its quality settings
/// changed it (so mesh() meshes it the way `strata generate` would), or none
/// for a grid read from a file.
struct Grid
{
    scene::SampledTerrain terrain;
    std::shared_ptr<const scene::Scene> source; ///< the scene as given; null: read from a file
    std::shared_ptr<const scene::Scene> scene;  ///< `source` with the quality applied; null: read from a file
    std::optional<std::string> preset;          ///< sample()'s preset and knobs, which mesh() starts from
    scene::QualityOverrides overrides;
    scene::QualitySettings quality;             ///< what they resolved to
};

/// A mesh shared with Python. Arrays handed out view its buffers (no copy)
/// and keep the Python object alive; a mesh owned by a World's chunk is
/// read-only.
struct Mesh
{
    std::shared_ptr<const meshing::TriangleMesh> mesh;
    bool writable = true;
    meshing::TriangleMesh& mutableMesh() const { return const_cast<meshing::TriangleMesh&>(*mesh); }
};

/// (x, y, z) from any Python sequence of three numbers; throws ValueError naming `what`.
glm::dvec3 toVec3(const py::handle& value, const char* what);
py::tuple fromVec3(const glm::dvec3& v);

/// The quality knobs a call was given as keyword arguments (voxel_size,
/// mesher, ...; None = not given) plus a `quality` dict of any knob, checked
/// by the library (scene::checkKnob) so errors name the knob.
scene::QualityOverrides qualityOverrides(const py::dict& knobs, const py::object& quality);

} // namespace strata::python
