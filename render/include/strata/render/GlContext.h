// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The one thing the OpenGL renderer needs from a context: to make it
/// current. Implemented by EglContext (headless) and GlfwContext (a window);
/// renderer code takes a GlContext& and never knows which it runs on.

#include <string>

namespace strata::render {

/// An OpenGL 4.5 core context. Not copyable; owned by whoever created it.
/// As with any GL context, it is current on one thread at a time, and GL
/// objects created in it (a GlRenderer) must not outlive it.
class GlContext
{
public:
    virtual ~GlContext();
    GlContext() = default;
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    /// Makes the context current on the calling thread (a no-op if it is).
    /// Throws strata::Error if the window system refuses.
    virtual void makeCurrent() = 0;

    /// "GL_RENDERER (GL_VERSION) via <platform>", for logs and reports.
    virtual const std::string& description() const = 0;
};

} // namespace strata::render
