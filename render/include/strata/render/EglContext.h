// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// A headless OpenGL 4.5 core context through EGL, with no window system:
/// EGL device enumeration first (the NVIDIA path, also Mesa), then Mesa's
/// surfaceless platform.

#include <strata/render/GlContext.h>

#include <memory>
#include <string>

namespace strata::render {

class EglContext final : public GlContext
{
public:
    /// Creates the context and makes it current on the calling thread.
    /// Throws strata::Error with a one-line reason when no EGL display or no
    /// OpenGL 4.5 core context can be had.
    ///
    /// Tries, in order, every device from eglQueryDevicesEXT on
    /// EGL_PLATFORM_DEVICE_EXT, then EGL_PLATFORM_SURFACELESS_MESA; no window
    /// system is needed. The context is surfaceless (EGL_KHR_surfaceless_context)
    /// or, without that extension, has a 1×1 pbuffer: render into framebuffer
    /// objects. As EGL requires, a context is current on one thread at a time.
    static std::unique_ptr<EglContext> create();

    /// Destroys the context (unbinding it first if it is current on the
    /// calling thread) and its surface, if any. The EGL display stays
    /// initialised: EGL hands the same display to the whole process, and
    /// terminating it would break other users (the embedding application,
    /// another EglContext); creating a context again reuses it.
    ~EglContext() override;

    /// Makes the context current on the calling thread (a no-op if it is).
    /// Throws strata::Error if EGL refuses (e.g. it is current on another thread).
    void makeCurrent() override;

    /// "GL_RENDERER (GL_VERSION) via EGL device|surfaceless", for logs and reports.
    const std::string& description() const override { return mDescription; }

private:
    EglContext() = default;
    struct Handles;
    std::unique_ptr<Handles> mHandles;
    std::string mDescription;
};

} // namespace strata::render
