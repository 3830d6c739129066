// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "ViewerCamera.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace strata::view {

namespace {

constexpr double DEGREES = 3.14159265358979323846 / 180.0;

} // namespace

ViewerCamera ViewerCamera::from(const render::Camera& camera)
{
    ViewerCamera v;
    const glm::dvec3 d = camera.target - camera.position;
    const double length = glm::length(d);
    const glm::dvec3 f = length > 0.0 ? d / length : glm::dvec3(0.0, 0.0, -1.0);
    v.target = camera.target;
    v.distance = length > 0.0 ? length : 1.0;
    v.position = camera.position;
    v.pitch = std::asin(std::clamp(f.y, -1.0, 1.0)) / DEGREES;
    v.yaw = std::atan2(-f.x, -f.z) / DEGREES;
    v.pitch = std::clamp(v.pitch, -89.0, 89.0);
    v.fovYDegrees = camera.fovYDegrees;
    v.nearPlane = camera.nearPlane;
    v.farPlane = camera.farPlane;
    return v;
}

glm::dvec3 ViewerCamera::forward() const
{
    const double cp = std::cos(pitch * DEGREES);
    return {-std::sin(yaw * DEGREES) * cp, std::sin(pitch * DEGREES), -std::cos(yaw * DEGREES) * cp};
}

glm::dvec3 ViewerCamera::eye() const { return mode == Mode::Orbit ? target - forward() * distance : position; }

void ViewerCamera::rotate(double yawDegrees, double pitchDegrees)
{
    yaw = std::fmod(yaw + yawDegrees, 360.0);
    pitch = std::clamp(pitch + pitchDegrees, -89.0, 89.0);
}

void ViewerCamera::zoom(double steps)
{
    if (mode == Mode::Orbit) {
        distance = std::clamp(distance * std::pow(0.9, steps), 1e-2, 1e6);
    }
}

void ViewerCamera::move(double right, double up, double forwardMetres)
{
    const glm::dvec3 f = forward();
    const glm::dvec3 r = glm::normalize(glm::cross(f, glm::dvec3(0.0, 1.0, 0.0)));
    if (mode == Mode::Fly) {
        position += r * right + glm::dvec3(0.0, up, 0.0) + f * forwardMetres;
    } else {
        const glm::dvec3 flat = glm::normalize(glm::dvec3(f.x, 0.0, f.z) + glm::dvec3(1e-12, 0.0, 0.0));
        target += r * right + glm::dvec3(0.0, up, 0.0) + flat * forwardMetres;
    }
}

void ViewerCamera::toggleMode()
{
    if (mode == Mode::Orbit) {
        position = eye();
        mode = Mode::Fly;
    } else {
        target = position + forward() * distance;
        mode = Mode::Orbit;
    }
}

render::Camera ViewerCamera::camera() const
{
    render::Camera c;
    c.position = eye();
    c.target = c.position + forward();
    c.up = glm::dvec3(0.0, 1.0, 0.0);
    c.fovYDegrees = fovYDegrees;
    // Keep the depth range useful wherever the user flies: far covers the
    // scene from here, near a fixed fraction of it.
    c.farPlane = farPlane + (mode == Mode::Orbit ? distance : glm::length(position - target));
    c.nearPlane = std::max(nearPlane, c.farPlane * 1e-5);
    return c;
}

} // namespace strata::view
