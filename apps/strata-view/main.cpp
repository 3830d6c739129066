// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// strata-view — the interactive viewer: loads a scene, generates its mesh,
// and shows it through GlfwContext + GlRenderer with orbit and fly cameras,
// debug views, wireframe and per-feature toggles; reloads the scene when
// the file changes. `--frames N --screenshot FILE` renders N frames, saves
// the last and exits (used under `xvfb-run -a` in the tests).

#include <strata/scene/Pipeline.h>
#include <strata/scene/Scene.h>
#include "ViewerCamera.h"

#include <strata/Error.h>
#include <strata/meshing/GridToMesh.h>
#include <strata/meshing/MeshMetrics.h>
#include <strata/render/GlRenderer.h>
#include <strata/render/GlfwContext.h>
#include <strata/terrain/SampleLevelSet.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

namespace {

using namespace strata;
using Clock = std::chrono::steady_clock;

constexpr int EXIT_BAD_INPUT = 2;

const char* const KEYS_HELP = R"(Keys and mouse:
  left drag        rotate (orbit around the target / look around)
  scroll           orbit: zoom
  W A S D          move forward/left/back/right; Q E down/up (shift: 5x faster)
  Tab              switch orbit / fly camera
  0..7             view: 0 shaded, 1 triplanar weights, 2 world normals, 3 metallic,
                   4 occlusion, 5 height, 6 smoothness, 7 albedo only
  F                wireframe on/off
  F1..F10          toggle a material feature: mask, mods, height, normal, top, detail,
                   detail-normal, emission, udn, rnm (absent features stay off)
  H                sun shadows on/off
  R                reload the scene now (it also reloads when the file changes)
  P                save a screenshot (strata-view.png)
  Esc              quit)";

struct Args
{
    std::string scenePath;
    int width = 1280;
    int height = 720;
    int samples = 4;
    int frames = 0;
    std::string screenshot;
    std::optional<std::uint64_t> seed;
    bool quiet = false;
};

/// The scene's mesh and render settings.
struct Loaded
{
    scene::Scene scene;
    meshing::TriangleMesh mesh;
    render::SnapshotOptions snapshot;
    std::filesystem::file_time_type mtime{};
    double seconds = 0.0;
};

std::filesystem::file_time_type modificationTime(const std::string& path)
{
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(path, ec);
    return ec ? std::filesystem::file_time_type{} : time;
}

/// Loads the scene and generates its mesh (sampling and meshing as
/// `strata generate` does). Throws strata::Error.
Loaded load(const Args& args, int width, int height)
{
    const auto t0 = Clock::now();
    Loaded loaded;
    loaded.mtime = args.scenePath.empty() ? std::filesystem::file_time_type{} : modificationTime(args.scenePath);
    loaded.scene = args.scenePath.empty() ? scene::defaultScene()
                                          : scene::loadScene(args.scenePath);
    const scene::Scene& scene = loaded.scene;
    // The same stages as `strata generate`, the grid and mesh in memory.
    // The scene's [quality] table applies as in `strata generate`.
    const scene::QualitySettings quality = scene::resolveQuality(scene, std::nullopt, {});
    const scene::Scene effective = scene::applyQuality(scene, quality);
    const scene::SampledTerrain terrain = scene::sampleTerrain(effective, args.seed);
    // The landform masks whenever the terrain has them: the debug views may show them.
    loaded.mesh = scene::meshTerrain(effective, quality, terrain, nullptr,
                                     {terrain.landformMasks != nullptr, terrain.rockMasks != nullptr});
    loaded.snapshot = scene::makeSnapshotOptions(scene, loaded.mesh, width, height);
    loaded.seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    return loaded;
}

/// Window state the GLFW callbacks change.
struct Input
{
    view::ViewerCamera camera;
    render::DrawOptions draw;
    std::uint32_t featureMask = render::feature::ALL;
    bool shadows = true;
    bool dragging = false;
    double lastX = 0.0;
    double lastY = 0.0;
    double scroll = 0.0;
    bool reload = false;
    bool screenshot = false;
};

void onKey(GLFWwindow* window, int key, int /*scancode*/, int action, int mods)
{
    if (action != GLFW_PRESS) {
        return;
    }
    auto* input = static_cast<Input*>(glfwGetWindowUserPointer(window));
    if (key == GLFW_KEY_ESCAPE) {
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    } else if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9 && key < GLFW_KEY_0 + render::DEBUG_VIEW_COUNT) {
        input->draw.debugView = render::DebugView(key - GLFW_KEY_0);
    } else if (key == GLFW_KEY_V) {
        // Every view in turn (the digits reach the first ten): V forward, shift+V back.
        const int step = (mods & GLFW_MOD_SHIFT) != 0 ? render::DEBUG_VIEW_COUNT - 1 : 1;
        input->draw.debugView = render::DebugView((int(input->draw.debugView) + step) % render::DEBUG_VIEW_COUNT);
        std::printf("debug view: %s\n", render::debugViewName(input->draw.debugView));
    } else if (key == GLFW_KEY_F) {
        input->draw.wireframe = !input->draw.wireframe;
    } else if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F10) {
        input->featureMask ^= 1u << (key - GLFW_KEY_F1);
    } else if (key == GLFW_KEY_TAB) {
        input->camera.toggleMode();
    } else if (key == GLFW_KEY_H) {
        input->shadows = !input->shadows;
    } else if (key == GLFW_KEY_R) {
        input->reload = true;
    } else if (key == GLFW_KEY_P) {
        input->screenshot = true;
    }
}

void onMouseButton(GLFWwindow* window, int button, int action, int /*mods*/)
{
    auto* input = static_cast<Input*>(glfwGetWindowUserPointer(window));
    if (button == GLFW_MOUSE_BUTTON_LEFT) {
        input->dragging = action == GLFW_PRESS;
        glfwGetCursorPos(window, &input->lastX, &input->lastY);
    }
}

void onCursor(GLFWwindow* window, double x, double y)
{
    auto* input = static_cast<Input*>(glfwGetWindowUserPointer(window));
    if (input->dragging) {
        const double sensitivity = 0.25; // degrees per screen unit
        input->camera.rotate(-(x - input->lastX) * sensitivity, -(y - input->lastY) * sensitivity);
    }
    input->lastX = x;
    input->lastY = y;
}

void onScroll(GLFWwindow* window, double /*dx*/, double dy)
{
    static_cast<Input*>(glfwGetWindowUserPointer(window))->scroll += dy;
}

std::string title(const Input& input, const render::GlRenderer& renderer, double frameMs, const std::string& status)
{
    std::ostringstream s;
    s << "strata-view  " << std::fixed << std::setprecision(1) << frameMs << " ms";
    if (frameMs > 0.0) {
        s << " (" << std::setprecision(0) << 1000.0 / frameMs << " fps)";
    }
    s << "  |  " << render::debugViewName(input.draw.debugView) << "  |  "
      << render::featureNames(renderer.activeFeatures(input.featureMask))
      << (input.featureMask != render::feature::ALL ? " (toggled)" : "") << "  |  "
      << (input.camera.mode == view::ViewerCamera::Mode::Orbit ? "orbit" : "fly")
      << (input.draw.wireframe ? "  |  wireframe" : "") << (input.shadows ? "" : "  |  no shadows");
    const render::ProgramStats stats = renderer.stats();
    s << "  |  programs " << stats.compiled << "/" << stats.possible;
    if (!status.empty()) {
        s << "  |  " << status;
    }
    return s.str();
}

int run(const Args& args)
{
    if (!args.screenshot.empty() && args.frames < 1) {
        throw Error(ErrorKind::BadInput, "--screenshot needs --frames N (N >= 1)");
    }
    if (args.width < 1 || args.height < 1 || args.width > 16384 || args.height > 16384) {
        throw Error(ErrorKind::BadInput, "--size " + std::to_string(args.width) + "x" + std::to_string(args.height) + " outside 1..16384");
    }
    // The scene first (errors before a window opens), then the window.
    Loaded loaded = load(args, args.width, args.height);
    if (!args.quiet) {
        std::cout << "strata-view: " << loaded.scene.source << ": " << loaded.mesh.triangleCount()
                  << " triangles, generated in " << std::fixed << std::setprecision(2) << loaded.seconds << " s"
                  << std::endl;
    }
    auto context = render::GlfwContext::create(args.width, args.height, "strata-view");
    if (!args.quiet) {
        std::cout << "strata-view: " << context->description() << std::endl;
    }
    render::GlRenderer renderer(*context);
    renderer.setMesh(scene::meshView(loaded.mesh));
    renderer.setMaterial(loaded.snapshot.material, loaded.snapshot.anisotropy);

    Input input;
    input.camera = view::ViewerCamera::from(loaded.snapshot.camera);
    input.shadows = loaded.snapshot.shadows.enabled;
    GLFWwindow* window = context->window();
    glfwSetWindowUserPointer(window, &input);
    glfwSetKeyCallback(window, onKey);
    glfwSetMouseButtonCallback(window, onMouseButton);
    glfwSetCursorPosCallback(window, onCursor);
    glfwSetScrollCallback(window, onScroll);

    const double sceneSize = glm::length(meshing::worldBounds(loaded.mesh).max - meshing::worldBounds(loaded.mesh).min);
    auto lastFrame = Clock::now();
    auto lastPoll = lastFrame;
    auto lastTitle = lastFrame;
    double frameMs = 0.0;      // smoothed, for the title
    double firstFrameMs = 0.0; // includes the program's compile (and llvmpipe's JIT) and the shadow map
    double laterFramesMs = 0.0;
    std::string status;
    int frame = 0;
    while (!context->shouldClose()) {
        glfwPollEvents();
        const auto now = Clock::now();
        const double dt = std::chrono::duration<double>(now - lastFrame).count();
        lastFrame = now;

        // Movement: a scene's size per ~4 s at normal speed.
        const bool fast = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS;
        const double speed = sceneSize * 0.25 * dt * (fast ? 5.0 : 1.0);
        auto held = [window](int key) { return glfwGetKey(window, key) == GLFW_PRESS ? 1.0 : 0.0; };
        input.camera.move((held(GLFW_KEY_D) - held(GLFW_KEY_A)) * speed, (held(GLFW_KEY_E) - held(GLFW_KEY_Q)) * speed,
                          (held(GLFW_KEY_W) - held(GLFW_KEY_S)) * speed);
        input.camera.zoom(input.scroll);
        input.scroll = 0.0;

        // Reload when the file changed (polled twice a second) or on R.
        if (!args.scenePath.empty() && std::chrono::duration<double>(now - lastPoll).count() > 0.5) {
            lastPoll = now;
            const auto mtime = modificationTime(args.scenePath);
            if (mtime != loaded.mtime && mtime != std::filesystem::file_time_type{}) {
                input.reload = true;
            }
        }
        if (input.reload) {
            input.reload = false;
            int width = 0;
            int height = 0;
            context->framebufferSize(width, height);
            try {
                Loaded fresh = load(args, std::max(width, 1), std::max(height, 1));
                renderer.setMesh(scene::meshView(fresh.mesh));
                renderer.setMaterial(fresh.snapshot.material, fresh.snapshot.anisotropy);
                loaded = std::move(fresh);
                status = "reloaded";
                if (!args.quiet) {
                    std::cout << "strata-view: reloaded " << loaded.scene.source << " ("
                              << loaded.mesh.triangleCount() << " triangles, " << std::setprecision(2)
                              << loaded.seconds << " s)" << std::endl;
                }
            } catch (const Error& e) {
                // Keep showing the last good scene; try again when the file changes.
                loaded.mtime = modificationTime(args.scenePath);
                status = "reload failed (see terminal)";
                std::cerr << "strata-view: reload failed: " << e.what() << std::endl;
            }
        }

        int width = 0;
        int height = 0;
        context->framebufferSize(width, height);
        if (width > 0 && height > 0) {
            input.draw.featureMask = input.featureMask;
            input.draw.shadows = loaded.snapshot.shadows;
            input.draw.shadows.enabled = input.shadows;
            const auto t0 = Clock::now();
            renderer.drawFrame(input.camera.camera(), loaded.snapshot.lighting, width, height, args.samples,
                               input.draw);
            renderer.blitFrame(0, width, height);
            if (args.frames > 0 && frame + 1 >= args.frames && !args.screenshot.empty()) {
                // The last frame as the window shows it (its back buffer before
                // the swap), so the screenshot tests the window path end to end.
                // Written to a temporary sibling and renamed (writeImage).
                render::writeImage(context->readBackBuffer(), args.screenshot);
            }
            context->swapBuffers();
            const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            frameMs = frameMs == 0.0 ? ms : 0.8 * frameMs + 0.2 * ms;
            (frame == 0 ? firstFrameMs : laterFramesMs) += ms;
            ++frame;
        }
        if (input.screenshot) {
            input.screenshot = false;
            render::writeImage(renderer.readFrame(), "strata-view.png");
            status = "saved strata-view.png";
        }
        if (std::chrono::duration<double>(now - lastTitle).count() > 0.25 || frame == 1) {
            lastTitle = now;
            glfwSetWindowTitle(window, title(input, renderer, frameMs, status).c_str());
        }
        if (args.frames > 0 && frame >= args.frames) {
            if (!args.quiet) {
                std::cout << "strata-view: " << frame << " frames at " << width << "x" << height << ", "
                          << args.samples << " samples: first " << std::fixed << std::setprecision(1)
                          << firstFrameMs << " ms";
                if (frame > 1) {
                    std::cout << ", then " << laterFramesMs / (frame - 1) << " ms per frame";
                }
                std::cout << " (draw + copy to the window + swap)" << std::endl;
            }
            break;
        }
    }
    return 0;
}

} // namespace

int main(int argc, char** argv)
{
    Args args;
    CLI::App app{"strata-view: look at a Strata scene. Generates the scene's terrain mesh and shows it with the\n"
                 "triplanar material; reloads when the scene file changes."};
    app.footer(KEYS_HELP);
    app.add_option("scene", args.scenePath, "Scene file (TOML); the built-in default scene when omitted")
        ->check(CLI::ExistingFile);
    std::string size;
    app.add_option("--size", size, "Window size WxH (default 1280x720)");
    app.add_option("--samples", args.samples, "MSAA samples (default 4, 1 = off)")->check(CLI::Range(1, 64));
    app.add_option("--frames", args.frames, "Render N frames, then exit")->check(CLI::Range(1, 1 << 30));
    app.add_option("--screenshot", args.screenshot, "With --frames: save the last frame (PNG, EXR, ...)");
    app.add_option("--seed", args.seed, "Override the scene's seed");
    app.add_flag("-q,--quiet", args.quiet, "No terminal output");
    try {
        app.parse(argc, argv);
        if (!size.empty()) {
            const auto x = size.find('x');
            std::size_t used = 0;
            try {
                if (x == std::string::npos) throw std::invalid_argument(size);
                args.width = std::stoi(size.substr(0, x), &used);
                if (used != x) throw std::invalid_argument(size);
                args.height = std::stoi(size.substr(x + 1), &used);
                if (used != size.size() - x - 1) throw std::invalid_argument(size);
            } catch (const std::logic_error&) {
                throw CLI::ValidationError("--size", "'" + size + "' is not WxH (e.g. 1280x720)");
            }
        }
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? 0 : EXIT_BAD_INPUT;
    }
    try {
        return run(args);
    } catch (const Error& e) {
        std::cerr << "strata-view: error: " << e.what() << std::endl;
        return EXIT_BAD_INPUT;
    } catch (const std::exception& e) {
        std::cerr << "strata-view: internal error: " << e.what() << std::endl;
        return 1;
    }
}
