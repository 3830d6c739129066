// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

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
                   double elevationDegrees, double fovYDegrees, double aspect)
{
    assert(fovYDegrees > 0.0 && fovYDegrees < 180.0 && aspect > 0.0);
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

    // Place the camera so that the box's eight corners, projected, fill the
    // view (aspect × fov) with a 5% margin and are centred in it. Start far
    // enough for a square view, then refine: shift the camera sideways to
    // centre the projected corners and move it along `forward` to scale them.
    glm::dvec3 corners[8];
    for (int i = 0; i < 8; ++i) {
        corners[i] = centre + glm::dvec3(i & 1 ? half.x : -half.x, i & 2 ? half.y : -half.y, i & 4 ? half.z : -half.z);
    }
    const double tanHalfY = std::tan(0.5 * glm::radians(fovYDegrees));
    const double tanHalfX = tanHalfY * aspect;
    double distance = 1e-3;
    for (const glm::dvec3& c : corners) {
        const glm::dvec3 r = c - centre;
        const double lateral = std::max(std::abs(glm::dot(r, right)), std::abs(glm::dot(r, up)));
        distance = std::max(distance, 1.05 * lateral / std::min(tanHalfX, tanHalfY) - glm::dot(r, forward));
    }
    // For a distance along the view axis: centre the projected corners by
    // shifting the camera sideways (a few fixed-point steps), and return how
    // far they reach (1 = the edge of the view).
    auto frame = [&](double d, glm::dvec3& position) {
        position = centre - forward * d;
        for (int step = 0;; ++step) {
            double minX = 1e300, maxX = -1e300, minY = 1e300, maxY = -1e300;
            for (const glm::dvec3& c : corners) {
                const double depth = glm::dot(c - position, forward);
                if (depth <= 1e-9 * d) return 1e300; // a corner behind the camera
                const double x = glm::dot(c - position, right) / (depth * tanHalfX);
                const double y = glm::dot(c - position, up) / (depth * tanHalfY);
                minX = std::min(minX, x), maxX = std::max(maxX, x), minY = std::min(minY, y), maxY = std::max(maxY, y);
            }
            if (step == 24) return std::max(std::max(maxX, -minX), std::max(maxY, -minY));
            // Damped: near corners move more than the centre plane suggests.
            position += right * (0.5 * (minX + maxX) * d * tanHalfX * 0.5) +
                        up * (0.5 * (minY + maxY) * d * tanHalfY * 0.5);
        }
    };
    // The projected size shrinks monotonically with distance: bisect for a
    // reach of 1/1.05 between "too close" and the square-view distance.
    double lo = 0.0, hi = distance;
    glm::dvec3 position;
    for (int iteration = 0; iteration < 48; ++iteration) {
        const double mid = 0.5 * (lo + hi);
        (frame(mid, position) > 1.0 / 1.05 ? lo : hi) = mid;
    }
    frame(hi, position);
    const glm::dvec3 target = position + forward * glm::dot(centre - position, forward);
    distance = glm::length(target - position);
    // Depth range of the box from there.
    double nearest = 1e300;
    double farthest = 0.0;
    for (const glm::dvec3& c : corners) {
        nearest = std::min(nearest, glm::dot(c - position, forward));
        farthest = std::max(farthest, glm::dot(c - position, forward));
    }

    Camera camera;
    camera.target = target;
    camera.position = position;
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
