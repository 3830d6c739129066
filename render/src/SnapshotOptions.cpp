#include <strata/render/SnapshotOptions.h>

#include <strata/Error.h>

#include <glm/geometric.hpp>

#include <string>

namespace strata::render {

void checkSnapshotOptions(const SnapshotOptions& options)
{
    auto require = [](bool ok, const std::string& message) {
        if (!ok) {
            throw Error("snapshot: " + message);
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
        throw Error(std::string("snapshot: ") + e.what());
    }
    const Camera& c = options.camera;
    require(c.nearPlane > 0.0 && c.farPlane > c.nearPlane, "camera needs 0 < near < far");
    require(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0, "camera fovYDegrees outside (0, 180)");
    require(glm::length(c.target - c.position) > 0.0, "camera position equals its target");
    require(options.lighting.extraLights.size() <= 3, "at most 3 extra lights");
}

} // namespace strata::render
