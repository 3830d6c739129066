#pragma once
/// \file
/// A headless OpenGL 4.5 core context through EGL, with no window system:
/// EGL device enumeration first (the NVIDIA path, also Mesa), then Mesa's
/// surfaceless platform.

#include <memory>
#include <string>

namespace strata::render {

class EglContext
{
public:
    /// Creates the context and makes it current on the calling thread.
    /// Throws strata::Error with a one-line reason when no EGL display or no
    /// OpenGL 4.5 core context can be had.
    static std::unique_ptr<EglContext> create();

    ~EglContext();
    EglContext(const EglContext&) = delete;
    EglContext& operator=(const EglContext&) = delete;

    /// Makes the context current on the calling thread.
    void makeCurrent();

    /// "GL_RENDERER (GL_VERSION) via <platform>", for logs and reports.
    const std::string& description() const { return mDescription; }

private:
    EglContext() = default;
    struct Handles;
    std::unique_ptr<Handles> mHandles;
    std::string mDescription;
};

} // namespace strata::render
