// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A perspective camera in world metres (double precision, so a camera far
/// from the origin stays exact until it is made relative to the mesh).

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace strata::render {

struct Camera
{
    glm::dvec3 position{0.0, 10.0, 20.0};
    glm::dvec3 target{0.0};
    glm::dvec3 up{0.0, 1.0, 0.0};
    double fovYDegrees = 50.0;
    double nearPlane = 0.1;   ///< metres, > 0
    double farPlane = 2000.0; ///< metres, > nearPlane
};

/// A camera that looks at the box [boundsMin, boundsMax] from the given
/// azimuth (degrees around +Y, 0 = looking towards −Z) and elevation
/// (degrees above the horizon), placed so that the box's projected corners
/// fill a view of `aspect` (width / height) with a 5% margin and are centred
/// in it. Near and far planes are set from the box.
///
/// Positive azimuth turns counter-clockwise seen from above; positive
/// elevation looks down. `up` is orthogonal to the view direction (well
/// defined at ±90°, where the top of the image faces the azimuth's
/// horizontal direction). The target is on the view axis, near the box centre.
Camera orbitCamera(const glm::dvec3& boundsMin, const glm::dvec3& boundsMax, double azimuthDegrees,
                   double elevationDegrees, double fovYDegrees = 50.0, double aspect = 1.0);

/// View matrix of `camera` relative to `origin`: world point p maps through
/// view · (p − origin). Computed in double, returned in float.
glm::mat4 viewMatrix(const Camera& camera, const glm::dvec3& origin);

/// OpenGL-convention projection (clip z in [−1, 1]).
glm::mat4 projectionMatrix(const Camera& camera, double aspect);

} // namespace strata::render
