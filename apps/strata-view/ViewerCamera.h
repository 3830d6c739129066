// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The viewer's two cameras: orbit (around a target) and fly (WASD + mouse
/// look), both producing a render::Camera. Pure math, no window code.

#include <strata/render/Camera.h>

#include <glm/vec3.hpp>

namespace strata::view {

struct ViewerCamera
{
    enum class Mode
    {
        Orbit,
        Fly,
    };
    Mode mode = Mode::Orbit;
    glm::dvec3 target{0.0};   ///< orbit centre, world metres
    double distance = 100.0;  ///< orbit radius, metres, > 0
    glm::dvec3 position{0.0}; ///< fly: eye position, world metres
    double yaw = 0.0;         ///< degrees around +Y; 0 looks towards −Z, positive turns left
    double pitch = 0.0;       ///< degrees, positive looks up, clamped to ±89
    double fovYDegrees = 35.0;
    double nearPlane = 0.1;
    double farPlane = 2000.0;

    /// Starts both modes from `camera`: the orbit around its target, the fly
    /// camera at its position, looking the same way.
    static ViewerCamera from(const render::Camera& camera);

    /// The unit view direction for the current yaw and pitch.
    glm::dvec3 forward() const;

    /// The eye position (orbit: target − forward · distance).
    glm::dvec3 eye() const;

    /// Turns by mouse motion (degrees): both modes change yaw and pitch.
    void rotate(double yawDegrees, double pitchDegrees);

    /// Orbit: multiplies the distance by 0.9^steps; fly: nothing.
    void zoom(double steps);

    /// Fly: moves by `right`, `up`, `forward` metres along the view axes
    /// (up is world +Y). Orbit: moves the target in the horizontal plane.
    void move(double right, double up, double forwardMetres);

    /// Switches mode keeping the view: orbit → fly starts at the eye; fly →
    /// orbit orbits the point `distance` ahead.
    void toggleMode();

    /// The render::Camera of the current mode.
    render::Camera camera() const;
};

} // namespace strata::view
