// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// An OpenGL 4.5 core context with a window, through GLFW (X11 on Linux;
/// without a display, `xvfb-run -a`).

#include <strata/render/GlContext.h>
#include <strata/render/Image.h>

#include <memory>
#include <string>

struct GLFWwindow;

namespace strata::render {

class GlfwContext final : public GlContext
{
public:
    /// Opens a window of `width` × `height` screen coordinates titled
    /// `title` with an OpenGL 4.5 core (forward-compatible) context, and
    /// makes the context current on the calling thread. `visible` = false
    /// keeps the window hidden (rendering into framebuffer objects still
    /// works). The swap interval is 0 (no vsync) so frame times measure the
    /// renderer. GLFW is initialised on the first window and terminated
    /// after the last one is destroyed; call from the main thread only.
    /// Throws strata::Error with a one-line reason when GLFW cannot be
    /// initialised (no X display: run under X or `xvfb-run -a`) or no such
    /// context can be had.
    static std::unique_ptr<GlfwContext> create(int width, int height, const std::string& title, bool visible = true);

    /// Destroys the window and its context.
    ~GlfwContext() override;

    /// Makes the window's context current on the calling thread (a no-op if it is).
    void makeCurrent() override;

    /// "GL_RENDERER (GL_VERSION) via GLFW", for logs and reports.
    const std::string& description() const override { return mDescription; }

    /// The GLFW window, for input callbacks and polling; owned by this object.
    GLFWwindow* window() const { return mWindow; }

    /// Presents the default framebuffer (glfwSwapBuffers).
    void swapBuffers();

    /// Size of the default framebuffer in pixels (may differ from the
    /// window size in screen coordinates on high-DPI screens).
    void framebufferSize(int& width, int& height) const;

    /// Reads the window's back buffer (what the next swapBuffers() shows):
    /// RGBA8 as stored, rows top to bottom, alpha set to 255. Makes the
    /// context current. Throws strata::Error on a GL error.
    Image readBackBuffer();

    /// True once the user asked to close the window.
    bool shouldClose() const;

private:
    GlfwContext() = default;
    GLFWwindow* mWindow = nullptr;
    std::string mDescription;
};

} // namespace strata::render
