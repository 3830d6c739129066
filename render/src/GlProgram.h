// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// Internal: RAII owners of GL object names, GL error checks, and the one
// compile/link path of every GLSL program (errors name the shader file and
// line through the #line numbering of shaders/EmbedShaders.cmake, and quote
// the offending source line).

#include <epoxy/gl.h>

#include <string>
#include <vector>
#include <utility>

#include <strata/render/Texture.h>

namespace strata::render::detail {

/// Owner of one GL object name; deletes it (in the context current at
/// that time, which must be the one that created it).
class GlObject
{
public:
    using Deleter = void (*)(GLuint);

    GlObject() = default;
    GlObject(GLuint id, Deleter deleter) : mId(id), mDeleter(deleter) {}
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept : mId(std::exchange(other.mId, 0)), mDeleter(other.mDeleter) {}
    GlObject& operator=(GlObject&& other) noexcept
    {
        if (this != &other) {
            reset();
            mId = std::exchange(other.mId, 0);
            mDeleter = other.mDeleter;
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    GLuint id() const { return mId; }
    explicit operator bool() const { return mId != 0; }

    void reset()
    {
        if (mId != 0 && mDeleter) {
            mDeleter(mId);
        }
        mId = 0;
    }

private:
    GLuint mId = 0;
    Deleter mDeleter = nullptr;
};

GlObject createBuffer();
GlObject createVertexArray();
GlObject createTexture2D();
GlObject createTexture2DArray();
GlObject createRenderbuffer();
GlObject createFramebuffer();

/// Uploads a Texture's mip chain as built on the CPU (the same texels the
/// CPU sampler filters): SRGB8_ALPHA8 or RGBA8 by kind, repeating,
/// trilinear. Rows are already bottom to top. Defined in GlRenderer.cpp.
GlObject uploadTexture(const Texture& texture);

/// The same for the layers of one map slot as a 2D texture array (layer i
/// from layers[i]); all of one size, level count and colour space
/// (resolveLayerMaps() makes them so). Defined in GlRenderer.cpp.
GlObject uploadTextureArray(const std::vector<TexturePtr>& layers);

/// Throws strata::Error "OpenGL error while WHAT: GL_..." when GL has
/// recorded an error (and drains the error queue).
void checkGl(const char* what);

/// Forgets errors recorded before (bounded, for lost contexts).
void clearGlErrors();

/// Rewrites a GLSL info log into one line: "<string>:<line>(<column>)"
/// (Mesa) and "<string>(<line>)" (NVIDIA) locations become the shader file
/// name and its own line (line L of the assembled source is line
/// L % SOURCE_LINE_BASE of file L / SOURCE_LINE_BASE), and each error is
/// followed by the offending line of `source` in backquotes, found by
/// following the #line directives of `source`. Only the errors are kept
/// when there are any.
std::string describeShaderLog(const std::string& log, const std::string& source);

/// Compiles one stage. Throws strata::Error "GLSL compile error in the
/// NAME shader: FILE:LINE(COL): error: ... `source line`".
GlObject compileShader(GLenum stage, const std::string& source, const std::string& name);

/// Links two compiled stages (detached afterwards). Throws strata::Error
/// "GLSL link error in the NAME program: ..." with the log.
GlObject linkProgram(const GlObject& vertex, const GlObject& fragment, const std::string& name);

} // namespace strata::render::detail
