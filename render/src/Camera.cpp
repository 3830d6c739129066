#include <strata/render/Camera.h>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace strata::render {

Camera orbitCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax, double azimuthDegrees,
                   double elevationDegrees, double fovYDegrees)
{
    assert(fovYDegrees > 0.0 && fovYDegrees < 180.0);
    const glm::dvec3 centre = 0.5 * (boundsMin + boundsMax);
    const glm::dvec3 half = 0.5 * glm::abs(boundsMax - boundsMin);

    const double az = glm::radians(azimuthDegrees);
    const double el = glm::radians(elevationDegrees);
    // Azimuth 0 looks towards −Z; positive azimuth turns counter-clockwise
    // seen from above (+Y). Positive elevation looks down.
    const glm::dvec3 forward{-std::sin(az) * std::cos(el), -std::sin(el), -std::cos(az) * std::cos(el)};
    // d(forward)/d(elevation), negated: orthogonal to forward, +Y at el = 0,
    // and still defined straight above or below.
    const glm::dvec3 up{-std::sin(az) * std::sin(el), std::cos(el), -std::cos(az) * std::sin(el)};
    const glm::dvec3 right = glm::cross(forward, up);

    // The nearest distance at which every corner of the box lies inside a
    // square view of the vertical field of view (so also inside any wider
    // one), with a 5% margin: corner c needs max(|c·right|, |c·up|) <=
    // tan(fov/2)·(distance + c·forward).
    glm::dvec3 corners[8];
    for (int i = 0; i < 8; ++i) {
        corners[i] = glm::dvec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z);
    }
    const double tanHalf = std::tan(0.5 * glm::radians(fovYDegrees)) / 1.05;
    double distance = 1e-3;
    for (const glm::dvec3& c : corners) {
        const double lateral = std::max(std::abs(glm::dot(c, right)), std::abs(glm::dot(c, up)));
        distance = std::max(distance, lateral / tanHalf - glm::dot(c, forward));
    }
    // Depth range of the box from there.
    double nearest = distance;
    double farthest = distance;
    for (const glm::dvec3& c : corners) {
        nearest = std::min(nearest, distance + glm::dot(c, forward));
        farthest = std::max(farthest, distance + glm::dot(c, forward));
    }

    Camera camera;
    camera.target = centre;
    camera.position = centre - forward * distance;
    camera.up = up;
    camera.fovYDegrees = fovYDegrees;
    camera.nearPlane = std::max(nearest * 0.9, distance * 1e-3);
    camera.farPlane = farthest * 1.1;
    return camera;
}

glm::mat4 viewMatrix(const Camera& camera, const glm::dvec3& origin)
{
    const glm::dmat4 view = glm::lookAtRH(camera.position - origin, camera.target - origin, camera.up);
    return glm::mat4(view);
}

glm::mat4 projectionMatrix(const Camera& camera, double aspect)
{
    assert(aspect > 0.0 && camera.nearPlane > 0.0 && camera.farPlane > camera.nearPlane);
    const glm::dmat4 projection =
        glm::perspectiveRH_NO(glm::radians(camera.fovYDegrees), aspect, camera.nearPlane, camera.farPlane);
    return glm::mat4(projection);
}

} // namespace strata::render
