// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/GlfwContext.h>

#include <strata/Error.h>

#include <epoxy/gl.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace strata::render {

namespace {

// GLFW reports errors through a callback; keep the last one for our messages.
// GLFW itself must be used from the main thread, so one slot suffices.
std::mutex gMutex;
std::string gLastError;
int gWindows = 0; // live windows: GLFW is terminated after the last

void onGlfwError(int code, const char* description)
{
    std::lock_guard<std::mutex> lock(gMutex);
    gLastError = std::string(description ? description : "unknown error") + " (GLFW error 0x" + [code] {
        char buffer[16];
        std::snprintf(buffer, sizeof(buffer), "%x", unsigned(code));
        return std::string(buffer);
    }() + ")";
}

std::string takeLastError()
{
    std::lock_guard<std::mutex> lock(gMutex);
    std::string error = gLastError.empty() ? "no reason given" : gLastError;
    gLastError.clear();
    return error;
}

std::string glString(GLenum name)
{
    const char* s = reinterpret_cast<const char*>(glGetString(name));
    return s ? s : "?";
}

} // namespace

std::unique_ptr<GlfwContext> GlfwContext::create(int width, int height, const std::string& title, bool visible)
{
    if (width < 1 || height < 1) {
        throw Error(ErrorKind::BadInput, "window size " + std::to_string(width) + "x" + std::to_string(height) + " must be at least 1x1");
    }
    glfwSetErrorCallback(onGlfwError);
    if (gWindows == 0 && !glfwInit()) {
        throw Error(ErrorKind::Gl, "cannot open a window: GLFW initialisation failed: " + takeLastError() +
                    "; run under X (or `xvfb-run -a`), or use the headless EGL renderer");
    }
    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CLIENT_API, GLFW_OPENGL_API);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    GLFWwindow* window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!window) {
        const std::string reason = takeLastError();
        if (gWindows == 0) {
            glfwTerminate();
        }
        throw Error(ErrorKind::Gl, "cannot open a window with an OpenGL 4.5 core context: " + reason);
    }
    ++gWindows;
    std::unique_ptr<GlfwContext> context(new GlfwContext());
    context->mWindow = window;
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
    if (!epoxy_is_desktop_gl() || epoxy_gl_version() < 45) {
        const std::string version = glString(GL_VERSION);
        context.reset();
        throw Error(ErrorKind::Gl, "cannot open a window with an OpenGL 4.5 core context: got OpenGL " + version);
    }
    context->mDescription = glString(GL_RENDERER) + " (" + glString(GL_VERSION) + ") via GLFW";
    return context;
}

GlfwContext::~GlfwContext()
{
    if (mWindow) {
        if (glfwGetCurrentContext() == mWindow) {
            glfwMakeContextCurrent(nullptr);
        }
        glfwDestroyWindow(mWindow);
        if (--gWindows == 0) {
            glfwTerminate();
        }
    }
}

void GlfwContext::makeCurrent()
{
    if (glfwGetCurrentContext() != mWindow) {
        glfwMakeContextCurrent(mWindow);
        if (glfwGetCurrentContext() != mWindow) {
            throw Error(ErrorKind::Gl, "cannot make the window's OpenGL context current: " + takeLastError());
        }
    }
}

void GlfwContext::swapBuffers() { glfwSwapBuffers(mWindow); }

void GlfwContext::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(mWindow, &width, &height); }

Image GlfwContext::readBackBuffer()
{
    makeCurrent();
    int width = 0;
    int height = 0;
    framebufferSize(width, height);
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * std::size_t(height) * 4);
    std::vector<std::uint8_t> rows(image.pixels.size());
    while (glGetError() != GL_NO_ERROR) {
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
        throw Error(ErrorKind::Gl, "OpenGL error " + std::to_string(error) + " while reading the window's back buffer");
    }
    // GL rows run bottom to top: flip; the window may have no alpha.
    const std::size_t rowBytes = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y) {
        std::memcpy(image.pixels.data() + std::size_t(y) * rowBytes,
                    rows.data() + std::size_t(height - 1 - y) * rowBytes, rowBytes);
    }
    for (std::size_t i = 3; i < image.pixels.size(); i += 4) {
        image.pixels[i] = 255;
    }
    return image;
}

bool GlfwContext::shouldClose() const { return glfwWindowShouldClose(mWindow) != 0; }

} // namespace strata::render
