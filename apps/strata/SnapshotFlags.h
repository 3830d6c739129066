// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// The snapshot flags of `strata generate` and `strata render` (see
// Snapshot.h), registered the same way on both.

#include <strata/scene/Snapshot.h>

#include <strata/Error.h>

#include <CLI/CLI.hpp>

#include <optional>
#include <regex>
#include <string>
#include <utility>

namespace strata::app {

/// "--size 1280x720" → {1280, 720}; throws strata::Error naming the flag
/// and its value otherwise.
inline std::pair<int, int> parseSizeFlag(const std::string& text)
{
    static const std::regex pattern(R"((\d{1,5})[xX](\d{1,5}))");
    std::smatch match;
    if (!std::regex_match(text, match, pattern)) {
        throw Error(ErrorKind::BadInput, "--size '" + text + "' must look like WIDTHxHEIGHT, e.g. 1280x720",
                    {"", 0, "--size", text});
    }
    const int width = std::stoi(match[1]), height = std::stoi(match[2]);
    if (width < 1 || height < 1 || width > 16384 || height > 16384) {
        throw Error(ErrorKind::BadInput, "--size '" + text + "': width and height must be in [1, 16384]",
                    {"", 0, "--size", text});
    }
    return {width, height};
}

struct SnapshotFlags
{
    std::string backend = "auto";
    std::string view;
    std::string cameraPosition;
    std::string cameraTarget;
    std::optional<double> fov;
    int turntable = 0;
    std::string format;
    std::string debugView;

    void add(CLI::App* command)
    {
        command->add_option("--backend", backend,
                            "Renderer: auto (OpenGL through EGL, else the CPU renderer with a notice; default), "
                            "gl (OpenGL, an error without it) or cpu (the reference renderer)");
        command->add_option(
            "--view", view,
            "Camera preset: orbit (the scene's orbit angles), top (straight down), cave (from "
            "inside the largest cave, looking towards its nearest opening); default: the scene's camera");
        command->add_option("--camera-position", cameraPosition,
                            "Camera position X,Y,Z in world metres (overrides the view's)");
        command->add_option("--camera-target", cameraTarget, "Point the camera looks at, X,Y,Z in world metres");
        command->add_option("--fov", fov, "Vertical field of view in degrees, (0, 180)");
        turntableOption = command->add_option(
            "--turntable", turntable,
            "Render N frames around the vertical axis through the target: NAME_000.EXT, NAME_001.EXT, ...");
        command->add_option("--snapshot-format", format, "png (8-bit sRGB) or exr (linear float through OpenImageIO)");
        command->add_option("--debug-view", debugView,
                            "Show what the material computed instead of the lit image: weights, normals, metallic, "
                            "occlusion, height, smoothness, albedo, layers (each terrain layer a colour), an erode "
                            "node's flow, wear, deposition or water, or a beds node's hardness or bed");
    }

    /// The request; throws strata::Error naming the flag and value.
    SnapshotRequest request() const
    {
        SnapshotRequest r;
        r.backend = backend;
        r.view = view;
        if (!cameraPosition.empty()) r.cameraPosition = parseVec3Flag("--camera-position", cameraPosition);
        if (!cameraTarget.empty()) r.cameraTarget = parseVec3Flag("--camera-target", cameraTarget);
        r.fov = fov;
        r.turntable = turntable;
        if (turntableOption && turntableOption->count() > 0 && !(turntable >= 1 && turntable <= 3600)) {
            throw Error(ErrorKind::BadInput, "--turntable '" + std::to_string(turntable) + "' must be a frame count in [1, 3600]");
        }
        r.format = format;
        r.debugView = debugView;
        checkSnapshotRequest(r);
        return r;
    }

    CLI::Option* turntableOption = nullptr;
};

} // namespace strata::app
