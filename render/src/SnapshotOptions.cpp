// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/SnapshotOptions.h>

#include <strata/Error.h>

#include <glm/geometric.hpp>

#include <string>

namespace strata::render {

const char* debugViewName(DebugView view)
{
    static const char* const NAMES[DEBUG_VIEW_COUNT] = {"shaded", "weights", "normals",    "metallic", "occlusion",
                                                        "height", "smoothness", "albedo", "layers",  "flow",
                                                        "wear",   "deposition", "water",  "hardness", "bed"};
    const int i = int(view);
    return i >= 0 && i < DEBUG_VIEW_COUNT ? NAMES[i] : "unknown";
}

void checkSnapshotOptions(const SnapshotOptions& options)
{
    auto require = [](bool ok, const std::string& message) {
        if (!ok) {
            throw Error(ErrorKind::BadInput, "snapshot: " + message);
        }
    };
    require(options.width >= 1 && options.width <= 16384 && options.height >= 1 && options.height <= 16384,
            "size " + std::to_string(options.width) + "x" + std::to_string(options.height) + " outside 1..16384");
    require(options.samples >= 1, "samples " + std::to_string(options.samples) + " must be >= 1");
    require(options.anisotropy >= 1.0f && options.anisotropy <= 16.0f,
            "anisotropy " + std::to_string(options.anisotropy) + " outside 1..16");
    try {
        checkMaterial(options.material);
    } catch (const Error& e) {
        throw Error(e.kind(), std::string("snapshot: ") + e.what());
    }
    const Camera& c = options.camera;
    require(c.nearPlane > 0.0 && c.farPlane > c.nearPlane, "camera needs 0 < near < far");
    require(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0, "camera fovYDegrees outside (0, 180)");
    require(glm::length(c.target - c.position) > 0.0, "camera position equals its target");
    require(options.lighting.extraLights.size() <= 3, "at most 3 extra lights");
    require(int(options.debugView) >= 0 && int(options.debugView) < DEBUG_VIEW_COUNT,
            "debug view " + std::to_string(int(options.debugView)) + " outside 0.." +
                std::to_string(DEBUG_VIEW_COUNT - 1));
    const ShadowOptions& shadows = options.shadows;
    require(shadows.resolution >= 16 && shadows.resolution <= 16384,
            "shadow resolution " + std::to_string(shadows.resolution) + " outside 16..16384");
    require(shadows.normalBias >= 0.0f && shadows.normalBias <= 16.0f,
            "shadow normal bias " + std::to_string(shadows.normalBias) + " outside 0..16 texels");
    require(shadows.depthBias >= 0.0f && shadows.depthBias <= 16.0f,
            "shadow depth bias " + std::to_string(shadows.depthBias) + " outside 0..16 texels");
}

} // namespace strata::render
