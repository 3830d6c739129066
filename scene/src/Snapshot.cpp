// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Snapshot.h>

#include <strata/Error.h>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <regex>

namespace strata::scene {

std::optional<render::DebugView> debugViewFromName(const std::string& name)
{
    for (int v = 0; v < render::DEBUG_VIEW_COUNT; ++v) {
        if (name == render::debugViewName(render::DebugView(v))) return render::DebugView(v);
    }
    return std::nullopt;
}

void checkSnapshotRequest(const SnapshotRequest& r)
{
    if (r.backend != "auto" && r.backend != "gl" && r.backend != "cpu") {
        throw Error(ErrorKind::BadInput, "--backend '" + r.backend + "' is not a backend (use auto, gl or cpu)");
    }
    if (!r.view.empty() && r.view != "orbit" && r.view != "top" && r.view != "cave") {
        throw Error(ErrorKind::BadInput, "--view '" + r.view + "' is not a view (use orbit, top or cave)");
    }
    if (r.fov && !(*r.fov > 0.0 && *r.fov < 180.0)) {
        throw Error(ErrorKind::BadInput, "--fov '" + std::to_string(*r.fov) + "' must be in (0, 180) degrees");
    }
    if (r.turntable < 0 || r.turntable > 3600) {
        throw Error(ErrorKind::BadInput, "--turntable '" + std::to_string(r.turntable) + "' must be a frame count in [1, 3600]");
    }
    if (!r.format.empty() && r.format != "png" && r.format != "exr") {
        throw Error(ErrorKind::BadInput, "--snapshot-format '" + r.format + "' is not a format (use png or exr)");
    }
    if (!r.debugView.empty() && !debugViewFromName(r.debugView)) {
        std::string names;
        for (int v = 1; v < render::DEBUG_VIEW_COUNT; ++v) {
            names += std::string(v == 1 ? "" : v + 1 == render::DEBUG_VIEW_COUNT ? " or " : ", ") +
                     render::debugViewName(render::DebugView(v));
        }
        throw Error(ErrorKind::BadInput, "--debug-view '" + r.debugView + "' is not a debug view (use " + names + ")");
    }
    if (r.cameraPosition && r.cameraTarget && glm::length(*r.cameraPosition - *r.cameraTarget) == 0.0) {
        throw Error(ErrorKind::BadInput, "--camera-position equals --camera-target");
    }
}

namespace {

/// N comma-separated finite numbers, |value| <= 1e9, for a flag whose
/// values look like `shape` ("X,Y,Z"), e.g. `example`.
template <int N>
glm::vec<N, double> parseNumbersFlag(const std::string& flag, const std::string& text, const char* shape,
                                     const char* count, const char* example)
{
    static const std::regex number(R"(\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*)");
    glm::vec<N, double> v(0.0);
    std::size_t start = 0;
    for (int i = 0; i < N; ++i) {
        const std::size_t comma = i < N - 1 ? text.find(',', start) : text.size();
        std::smatch match;
        const std::string part = comma == std::string::npos ? std::string() : text.substr(start, comma - start);
        if (comma == std::string::npos || !std::regex_match(part, match, number) ||
            (i == N - 1 && text.find(',', start) != std::string::npos)) {
            throw Error(ErrorKind::BadInput, flag + " '" + text + "' must look like " + shape + " (" + count + " numbers in metres, e.g. " +
                        example + ")");
        }
        v[i] = std::strtod(match[1].str().c_str(), nullptr); // ±HUGE_VAL on overflow, caught below
        if (!std::isfinite(v[i]) || std::abs(v[i]) > 1e9) {
            throw Error(ErrorKind::BadInput, flag + " '" + text + "' is out of range (|value| <= 1e9 metres)");
        }
        start = comma + 1;
    }
    return v;
}

} // namespace

glm::dvec3 parseVec3Flag(const std::string& flag, const std::string& text)
{
    return parseNumbersFlag<3>(flag, text, "X,Y,Z", "three", "10,40,-25");
}

glm::dvec2 parseVec2Flag(const std::string& flag, const std::string& text)
{
    return parseNumbersFlag<2>(flag, text, "X,Z", "two", "10,-25");
}

std::unique_ptr<render::EglContext> openBackend(const SnapshotRequest& request, std::ostream& notices,
                                                std::string& renderer)
{
    if (request.backend == "cpu") {
        renderer = "strata CPU reference renderer";
        return nullptr;
    }
    try {
        std::unique_ptr<render::EglContext> context = render::EglContext::create();
        renderer = context->description();
        return context;
    } catch (const Error& e) {
        if (request.backend == "gl") {
            throw Error(e.kind(), std::string("--backend gl: no OpenGL context: ") + e.what());
        }
        notices << "strata: no OpenGL context (" << e.what() << "); rendering on the CPU" << std::endl;
        renderer = "strata CPU reference renderer";
        return nullptr;
    }
}

render::Camera snapshotCamera(const Scene& scene, const SnapshotRequest& request, const meshing::Bounds& bounds,
                              double aspect, const std::optional<render::Camera>& cave)
{
    const CameraSettings& settings = scene.camera;
    const double extent = glm::length(bounds.max - bounds.min);
    render::Camera camera;
    if (request.view == "cave") {
        if (!cave) throw Error(ErrorKind::BadInput, "--view cave: no cave view was computed");
        camera = *cave;
    } else if (request.view == "top") {
        // Straight down, north (−Z) at the top of the image.
        camera = render::orbitCamera(bounds.min, bounds.max, 0.0, 90.0, request.fov.value_or(settings.fov), aspect);
    } else if (request.view == "orbit" || !settings.position) {
        camera = render::orbitCamera(bounds.min, bounds.max, settings.azimuth, settings.elevation,
                                     request.fov.value_or(settings.fov), aspect);
        if (settings.zoom != 1.0) {
            const double distance = glm::length(camera.position - camera.target) / settings.zoom;
            const double radius = 0.5 * extent;
            camera.position = camera.target + (camera.position - camera.target) / settings.zoom;
            camera.nearPlane = std::max(distance - radius, distance * 1e-3);
            camera.farPlane = distance + radius;
        }
    } else {
        camera.position = *settings.position;
        camera.target = *settings.target;
        camera.fovYDegrees = settings.fov;
        camera.nearPlane = std::max(1e-3, extent * 1e-4);
        camera.farPlane = glm::length(camera.position - camera.target) + 2.0 * extent + 1.0;
    }
    if (request.fov) camera.fovYDegrees = *request.fov;
    if (request.cameraPosition || request.cameraTarget) {
        if (request.cameraPosition) camera.position = *request.cameraPosition;
        if (request.cameraTarget) camera.target = *request.cameraTarget;
        if (glm::length(camera.position - camera.target) == 0.0) {
            throw Error(ErrorKind::BadInput, "--camera-position and --camera-target give a camera looking at its own position");
        }
        const glm::dvec3 forward = glm::normalize(camera.target - camera.position);
        camera.up = std::abs(forward.y) > 0.999 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 1.0, 0.0);
        const glm::dvec3 centre = 0.5 * (bounds.min + bounds.max);
        camera.nearPlane = std::max(1e-3, extent * 1e-4);
        camera.farPlane = glm::length(camera.position - centre) + extent + 1.0;
    }
    return camera;
}

render::Camera turntableFrame(const render::Camera& camera, int index, int count)
{
    if (count <= 1 || index == 0) return camera;
    const double angle = glm::radians(360.0 * double(index) / double(count));
    const double c = std::cos(angle), s = std::sin(angle);
    auto turn = [&](const glm::dvec3& v) { return glm::dvec3(c * v.x + s * v.z, v.y, -s * v.x + c * v.z); };
    render::Camera frame = camera;
    frame.position = camera.target + turn(camera.position - camera.target);
    frame.up = turn(camera.up);
    return frame;
}

std::vector<std::filesystem::path> snapshotPaths(const std::filesystem::path& single, int turntable)
{
    if (turntable <= 0) return {single};
    std::vector<std::filesystem::path> paths;
    for (int i = 0; i < turntable; ++i) {
        char number[16];
        std::snprintf(number, sizeof(number), "_%03d", i);
        paths.push_back(single.parent_path() / (single.stem().string() + number + single.extension().string()));
    }
    return paths;
}

} // namespace strata::scene
