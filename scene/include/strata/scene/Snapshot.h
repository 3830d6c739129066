// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The snapshot flags shared by `strata generate` and `strata render`:
/// backend, camera (scene, flags, presets), turntable and file format.

#include <strata/scene/Scene.h>

#include <strata/meshing/MeshMetrics.h>
#include <strata/render/Camera.h>
#include <strata/render/EglContext.h>
#include <strata/render/SnapshotOptions.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace strata::scene {

struct SnapshotRequest
{
    /// "auto" (EGL, else the CPU renderer with a notice), "gl" (EGL or an
    /// error) or "cpu".
    std::string backend = "auto";
    /// "" (the scene's camera), "orbit" (the scene's orbit angles, even when
    /// the scene gives a camera position), "top" (straight down, −Z at the
    /// top of the image) or "cave" (from inside the largest cave, CaveView.h).
    std::string view;
    std::optional<glm::dvec3> cameraPosition; ///< world metres; overrides the view's
    std::optional<glm::dvec3> cameraTarget;   ///< world metres; overrides the view's
    std::optional<double> fov;                ///< vertical degrees, (0, 180); overrides the view's
    int turntable = 0; ///< 0: one image; N >= 1: N frames around the vertical axis through the target
    /// "png" or "exr"; "" = from the output name (render) or png (generate).
    std::string format;
    /// "" (the lit image) or a debug view of the material: weights, normals,
    /// metallic, occlusion, height, smoothness, albedo, layers
    /// (render::debugViewName); scene renders only.
    std::string debugView;
};

/// Throws strata::Error naming the flag and its value for a bad backend,
/// view, fov, turntable count, format, debug view, or a camera position
/// equal to its target. Cheap: call it before any work so that nothing is written.
void checkSnapshotRequest(const SnapshotRequest& request);

/// The debug view named `name` (render::debugViewName: "shaded", "weights",
/// ..., "layers"), or nothing.
std::optional<render::DebugView> debugViewFromName(const std::string& name);

/// "X,Y,Z" (three finite numbers) → vector; throws strata::Error
/// "FLAG 'TEXT' must look like X,Y,Z ..." otherwise.
glm::dvec3 parseVec3Flag(const std::string& flag, const std::string& text);
/// "X,Z" (two finite numbers, e.g. a horizontal position) → vector; throws
/// strata::Error "FLAG 'TEXT' must look like X,Z ..." otherwise.
glm::dvec2 parseVec2Flag(const std::string& flag, const std::string& text);

/// The GL context for request.backend: "cpu" → null; "gl" → a context or
/// strata::Error "--backend gl: no OpenGL context: REASON"; "auto" → a
/// context, or null after one line "strata: no OpenGL context (REASON);
/// rendering on the CPU" on `notices`. `renderer` receives the renderer's
/// description.
std::unique_ptr<render::EglContext> openBackend(const SnapshotRequest& request, std::ostream& notices,
                                                std::string& renderer);

/// The camera of a snapshot: the scene's camera or the request's view
/// preset (`cave` must hold the cave view for "cave"), then the request's
/// position, target and fov on top. `bounds` are the mesh's world bounds.
render::Camera snapshotCamera(const Scene& scene, const SnapshotRequest& request, const meshing::Bounds& bounds,
                              double aspect, const std::optional<render::Camera>& cave);

/// Frame `index` of `count` of a turntable: `camera` turned about the
/// vertical axis through its target by 360°·index/count (counter-clockwise
/// seen from above).
render::Camera turntableFrame(const render::Camera& camera, int index, int count);

/// The files a snapshot writes: `single` itself, or for a turntable of N
/// frames STEM_000.EXT … (at least three digits) beside it.
std::vector<std::filesystem::path> snapshotPaths(const std::filesystem::path& single, int turntable);

} // namespace strata::scene
