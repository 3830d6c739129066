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
    // Bounding sphere of the box; never zero, so the planes stay valid.
    const double radius = std::max(0.5 * glm::length(boundsMax - boundsMin), 1e-3);
    const double distance = radius / std::sin(0.5 * glm::radians(fovYDegrees));

    const double az = glm::radians(azimuthDegrees);
    const double el = glm::radians(elevationDegrees);
    // Azimuth 0 looks towards −Z; positive azimuth turns counter-clockwise
    // seen from above (+Y). Positive elevation looks down.
    const glm::dvec3 forward{-std::sin(az) * std::cos(el), -std::sin(el), -std::cos(az) * std::cos(el)};
    // d(forward)/d(elevation), negated: orthogonal to forward, +Y at el = 0,
    // and still defined straight above or below.
    const glm::dvec3 up{-std::sin(az) * std::sin(el), std::cos(el), -std::cos(az) * std::sin(el)};

    Camera camera;
    camera.target = centre;
    camera.position = centre - forward * distance;
    camera.up = up;
    camera.fovYDegrees = fovYDegrees;
    camera.nearPlane = std::max((distance - radius) * 0.9, distance * 1e-4);
    camera.farPlane = (distance + radius) * 1.1;
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
