// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Rendering a mesh with its scene's material into a NumPy image, on the CPU
// reference renderer or on OpenGL through EGL: the pipeline's render stage.

#include "Bindings.h"

#include <strata/Error.h>
#include <strata/scene/CaveView.h>
#include <strata/scene/Snapshot.h>

#include <cstring>
#include <filesystem>
#include <sstream>

namespace strata::python {

namespace {

py::array_t<std::uint8_t> render(const std::shared_ptr<const scene::Scene>& input, const Mesh& mesh,
                                 const std::string& backend, const py::object& size, const std::string& view,
                                 const std::string& debugView, const py::object& cameraPosition,
                                 const py::object& cameraTarget, std::optional<double> fov,
                                 std::optional<std::string> preset, const py::object& quality,
                                 const std::shared_ptr<Grid>& grid)
{
    scene::SnapshotRequest request;
    request.backend = backend;
    request.view = view;
    request.debugView = debugView;
    request.fov = fov;
    if (!cameraPosition.is_none()) request.cameraPosition = toVec3(cameraPosition, "camera_position");
    if (!cameraTarget.is_none()) request.cameraTarget = toVec3(cameraTarget, "camera_target");
    std::optional<int> width, height;
    if (!size.is_none()) {
        const auto wh = size.cast<std::pair<int, int>>();
        if (wh.first < 1 || wh.second < 1 || wh.first > 16384 || wh.second > 16384) {
            throw Error(ErrorKind::BadInput, "size must be (width, height), each 1..16384", {"", 0, "size"});
        }
        width = wh.first;
        height = wh.second;
    }
    // The quality knobs that matter here (filtering, projections, normal
    // blend, shadows, backend) resolve as `strata generate` resolves them.
    scene::QualityOverrides flags = qualityOverrides({}, quality);
    if (backend != "auto") flags["backend"] = scene::checkKnob("backend", backend);
    const scene::QualitySettings q = scene::resolveQuality(*input, preset, flags);
    const scene::Scene scene = scene::applyQuality(*input, q);
    request.backend = q.backend;
    scene::checkSnapshotRequest(request);
    scene::neededMasks(scene, request.debugView);

    std::optional<render::Camera> cave;
    if (request.view == "cave") {
        if (!grid) throw Error(ErrorKind::BadInput, "view = 'cave' needs the grid (render(..., grid=grid))", {"", 0, "view", "cave"});
        cave = scene::findCaveView(*grid->terrain.grid, scene.region.min, scene.region.max).camera;
    }

    render::Image image;
    std::ostringstream notices;
    {
        py::gil_scoped_release release;
        std::string renderer;
        std::unique_ptr<render::EglContext> context = scene::openBackend(request, notices, renderer);
        scene::renderSnapshots(scene, *mesh.mesh, request, context.get(), 1, width, height, cave,
                               [&image](int, const render::Image& frame) { image = frame; });
    }
    if (!notices.str().empty()) {
        py::module_::import("warnings").attr("warn")(notices.str(), py::module_::import("builtins").attr("RuntimeWarning"));
    }
    py::array_t<std::uint8_t> out({image.height, image.width, 4});
    std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size());
    return out;
}

} // namespace

void bindRender(py::module_& m)
{
    m.def("read_image", [](const std::filesystem::path& path) {
        render::Image image;
        {
            py::gil_scoped_release release;
            image = render::readImage(path);
        }
        py::array_t<std::uint8_t> out({image.height, image.width, 4});
        std::memcpy(out.mutable_data(), image.pixels.data(), image.pixels.size());
        return out;
    }, py::arg("path"), "Reads an image file (PNG, EXR, ...) as (height, width, 4) uint8 RGBA, top row first.");
    m.def("write_image", [](const py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>& pixels,
                            const std::filesystem::path& path) {
        if (pixels.ndim() != 3 || pixels.shape(2) != 4 || pixels.shape(0) < 1 || pixels.shape(1) < 1) {
            throw Error(ErrorKind::BadInput, "pixels must be a (height, width, 4) uint8 array", {"", 0, "pixels"});
        }
        render::Image image;
        image.height = int(pixels.shape(0));
        image.width = int(pixels.shape(1));
        image.pixels.assign(pixels.data(), pixels.data() + pixels.size());
        py::gil_scoped_release release;
        render::writeImage(image, path);
    }, py::arg("pixels"), py::arg("path"), "Writes (height, width, 4) uint8 RGBA pixels as an image (atomically; format by extension).");
    m.def("render", &render, py::arg("scene"), py::arg("mesh"), py::arg("backend") = "cpu", py::arg("size") = py::none(),
          py::arg("view") = "", py::arg("debug_view") = "", py::arg("camera_position") = py::none(),
          py::arg("camera_target") = py::none(), py::arg("fov") = py::none(), py::arg("preset") = py::none(),
          py::arg("quality") = py::none(), py::arg("grid") = nullptr,
          "Renders the mesh with the scene's material, lighting and camera -> (height, width, 4) uint8 RGBA,\n"
          "top row first, as `strata generate` renders snapshot.png.\n"
          "backend: 'cpu' (the reference renderer, deterministic), 'gl' (OpenGL through EGL; GLError without one)\n"
          "or 'auto' (GL, else the CPU with a RuntimeWarning). size: (width, height), default the scene's.\n"
          "view: '' or 'orbit' (the scene's camera), 'top', 'cave' (needs grid=); debug_view: a debug view name\n"
          "('normals', 'layers', 'flow', ...); camera_position, camera_target: world metres; fov: degrees.\n"
          "GIL released.");
}

} // namespace strata::python
