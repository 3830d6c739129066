#include <strata/scene/SceneOffset.h>

#include <strata/Error.h>
#include <strata/terrain/Transforms.h>

#include <cmath>
#include <sstream>

namespace strata::scene {

Scene offsetScene(Scene scene, const glm::dvec3& offset)
{
    for (int axis = 0; axis < 3; ++axis) {
        if (!std::isfinite(offset[axis]) || std::abs(offset[axis]) > 1e9) {
            std::ostringstream text;
            text << "--offset '" << offset.x << "," << offset.y << "," << offset.z
                 << "' is out of range (finite, |value| <= 1e9 metres)";
            throw Error(text.str());
        }
    }
    if (offset == glm::dvec3(0.0)) return scene;
    if (scene.field) scene.field = std::make_shared<terrain::TranslateField>(scene.field, offset);
    if (scene.buildField) {
        scene.buildField = [build = scene.buildField, offset](std::uint64_t seed) -> terrain::DensityFieldPtr {
            return std::make_shared<terrain::TranslateField>(build(seed), offset);
        };
    }
    scene.region.min += offset;
    scene.region.max += offset;
    if (scene.camera.position) *scene.camera.position += offset;
    if (scene.camera.target) *scene.camera.target += offset;
    return scene;
}

void offsetRequest(SnapshotRequest& request, const glm::dvec3& offset)
{
    if (request.cameraPosition) *request.cameraPosition += offset;
    if (request.cameraTarget) *request.cameraTarget += offset;
}

} // namespace strata::scene
