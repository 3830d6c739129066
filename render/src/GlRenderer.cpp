#include <strata/render/GlRenderer.h>

#include <strata/Error.h>
#include <strata/render/EglContext.h>
#include <strata/shaders/EmbeddedShaders.h>

#include <epoxy/gl.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace strata::render {

namespace {

// ---------------------------------------------------------------------------
// Small RAII owner of one GL object name.

class GlObject
{
public:
    using Deleter = void (*)(GLuint);

    GlObject() = default;
    GlObject(GLuint id, Deleter deleter)
        : mId(id)
        , mDeleter(deleter)
    {
    }
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept
        : mId(std::exchange(other.mId, 0))
        , mDeleter(other.mDeleter)
    {
    }
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

GlObject createBuffer()
{
    GLuint id = 0;
    glCreateBuffers(1, &id);
    return {id, [](GLuint i) { glDeleteBuffers(1, &i); }};
}

GlObject createVertexArray()
{
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    return {id, [](GLuint i) { glDeleteVertexArrays(1, &i); }};
}

GlObject createTexture2D()
{
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    return {id, [](GLuint i) { glDeleteTextures(1, &i); }};
}

GlObject createRenderbuffer()
{
    GLuint id = 0;
    glCreateRenderbuffers(1, &id);
    return {id, [](GLuint i) { glDeleteRenderbuffers(1, &i); }};
}

GlObject createFramebuffer()
{
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    return {id, [](GLuint i) { glDeleteFramebuffers(1, &i); }};
}

// ---------------------------------------------------------------------------
// Errors.

std::string glErrorName(GLenum error)
{
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    default: return "GL error " + std::to_string(error);
    }
}

/// Throws strata::Error naming `what` when GL has recorded an error.
void checkGl(const char* what)
{
    GLenum error = glGetError();
    if (error == GL_NO_ERROR) {
        return;
    }
    std::string names = glErrorName(error);
    // Drain the queue (bounded: a lost context may report forever).
    for (int i = 0; i < 8 && (error = glGetError()) != GL_NO_ERROR; ++i) {
        names += ", " + glErrorName(error);
    }
    throw Error("OpenGL error while " + std::string(what) + ": " + names);
}

void clearGlErrors()
{
    for (int i = 0; i < 64 && glGetError() != GL_NO_ERROR; ++i) {
    }
}

/// GLSL logs locate messages as "<string>:<line>(<column>)" (Mesa) or
/// "<string>(<line>)" (NVIDIA). The embedded programs number file N's lines
/// from N·SOURCE_LINE_BASE + 1 (Mesa ignores the string number of #line), so
/// the line alone says which file: put the file names back. The log becomes
/// one line, of the errors alone when there are any.
std::string readableLog(const std::string& log)
{
    auto digitsAt = [](const std::string& s, std::size_t from) {
        std::size_t end = from;
        while (end < s.size() && s[end] >= '0' && s[end] <= '9') {
            ++end;
        }
        return end;
    };
    std::vector<std::string> errors;
    std::vector<std::string> others;
    std::size_t start = 0;
    while (start < log.size()) {
        std::size_t end = log.find('\n', start);
        if (end == std::string::npos) {
            end = log.size();
        }
        std::string line = log.substr(start, end - start);
        start = end + 1;
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) {
            line.pop_back();
        }
        if (line.empty()) {
            continue;
        }
        const std::size_t stringEnd = digitsAt(line, 0);
        if (stringEnd > 0 && stringEnd + 1 < line.size() && (line[stringEnd] == ':' || line[stringEnd] == '(')) {
            const std::size_t lineEnd = digitsAt(line, stringEnd + 1);
            if (lineEnd > stringEnd + 1 && lineEnd - stringEnd < 10) {
                const long number = std::stol(line.substr(stringEnd + 1, lineEnd - stringEnd - 1));
                const auto file = std::size_t(number / shaders::SOURCE_LINE_BASE);
                if (file < shaders::SOURCE_NAME_COUNT) {
                    line = shaders::SOURCE_NAMES[file] + line.substr(stringEnd, 1) +
                           std::to_string(number % shaders::SOURCE_LINE_BASE) + line.substr(lineEnd);
                }
            }
        }
        (line.find("error") != std::string::npos ? errors : others).push_back(line);
    }
    // Errors only, when there are any: the warnings that follow them are noise.
    std::string out;
    for (const std::string& line : errors.empty() ? others : errors) {
        out += (out.empty() ? "" : " | ") + line;
    }
    return out.empty() ? "(empty log)" : out;
}

GlObject compileShader(GLenum stage, const char* source, const char* name)
{
    GLuint id = glCreateShader(stage);
    GlObject shader(id, [](GLuint i) { glDeleteShader(i); });
    glShaderSource(id, 1, &source, nullptr);
    glCompileShader(id);
    GLint ok = GL_FALSE;
    glGetShaderiv(id, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(id, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(id, GLsizei(log.size()), nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        throw Error(std::string("GLSL compile error in the ") + name + " shader: " + readableLog(log));
    }
    return shader;
}

GlObject linkProgram(const GlObject& vertex, const GlObject& fragment)
{
    GLuint id = glCreateProgram();
    GlObject program(id, [](GLuint i) { glDeleteProgram(i); });
    glAttachShader(id, vertex.id());
    glAttachShader(id, fragment.id());
    glLinkProgram(id);
    GLint ok = GL_FALSE;
    glGetProgramiv(id, GL_LINK_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetProgramiv(id, GL_INFO_LOG_LENGTH, &length);
        std::string log(std::size_t(std::max(length, 1)), '\0');
        glGetProgramInfoLog(id, GLsizei(log.size()), nullptr, log.data());
        log.resize(std::strlen(log.c_str()));
        throw Error("GLSL link error in the terrain program: " + readableLog(log));
    }
    glDetachShader(id, vertex.id());
    glDetachShader(id, fragment.id());
    return program;
}

// ---------------------------------------------------------------------------
// Inputs.

void checkTexture(const Image& image, const char* name)
{
    if (image.width <= 0 || image.height <= 0 ||
        image.pixels.size() != std::size_t(image.width) * std::size_t(image.height) * 4) {
        throw Error(std::string("material ") + name + " is not a valid RGBA8 image (" + std::to_string(image.width) +
                    "x" + std::to_string(image.height) + ", " + std::to_string(image.pixels.size()) + " bytes)");
    }
}

void checkOptions(const MeshView& mesh, const SnapshotOptions& options)
{
    auto require = [](bool ok, const std::string& message) {
        if (!ok) {
            throw Error("snapshot: " + message);
        }
    };
    require(options.width >= 1 && options.width <= 16384 && options.height >= 1 && options.height <= 16384,
            "size " + std::to_string(options.width) + "x" + std::to_string(options.height) + " outside 1..16384");
    require(options.samples >= 1, "samples " + std::to_string(options.samples) + " must be >= 1");
    require(options.anisotropy >= 1.0f && options.anisotropy <= 16.0f,
            "anisotropy " + std::to_string(options.anisotropy) + " outside 1..16");
    const TriplanarMaterial& m = options.material;
    require(std::isfinite(m.mapScale) && m.mapScale > 0.0f, "material mapScale must be > 0");
    require(m.blendOffset >= 0.0f && m.blendOffset <= 0.5f, "material blendOffset outside 0..0.5");
    require(m.blendExponent >= 1.0f && m.blendExponent <= 8.0f, "material blendExponent outside 1..8");
    const Camera& c = options.camera;
    require(c.nearPlane > 0.0 && c.farPlane > c.nearPlane, "camera needs 0 < near < far");
    require(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0, "camera fovYDegrees outside (0, 180)");
    require(glm::length(c.target - c.position) > 0.0, "camera position equals its target");

    assert(mesh.indexCount % 3 == 0);
    assert(mesh.vertexCount == 0 || (mesh.positions && mesh.normals));
    assert(mesh.indexCount == 0 || mesh.indices);
    require(mesh.indexCount <= std::size_t(std::numeric_limits<GLsizei>::max()),
            "mesh has too many indices for one draw (" + std::to_string(mesh.indexCount) + ")");
    for (std::size_t i = 0; i < mesh.indexCount; ++i) {
        if (mesh.indices[i] >= mesh.vertexCount) {
            throw Error("snapshot: mesh index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", beyond the " + std::to_string(mesh.vertexCount) + " vertices");
        }
    }
}

/// An sRGB, mipmapped, repeating, trilinear (anisotropic where available)
/// texture. Image rows run top to bottom; GL's run bottom to top, so the
/// rows are flipped: the image's top is at v = 1 (texture "up" is +V).
GlObject uploadTexture(const Image& image, float anisotropy)
{
    GlObject texture = createTexture2D();
    const GLuint id = texture.id();
    int levels = 1;
    while ((std::max(image.width, image.height) >> levels) > 0) {
        ++levels;
    }
    glTextureStorage2D(id, levels, GL_SRGB8_ALPHA8, image.width, image.height);
    const std::size_t rowBytes = std::size_t(image.width) * 4;
    std::vector<std::uint8_t> flipped(image.pixels.size());
    for (int y = 0; y < image.height; ++y) {
        std::memcpy(flipped.data() + std::size_t(image.height - 1 - y) * rowBytes,
                    image.pixels.data() + std::size_t(y) * rowBytes, rowBytes);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
    glGenerateTextureMipmap(id);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (anisotropy > 1.0f) {
        glTextureParameterf(id, GL_TEXTURE_MAX_ANISOTROPY_EXT, anisotropy);
    }
    checkGl("uploading a texture");
    return texture;
}

float maxAnisotropy()
{
    if (epoxy_gl_version() < 46 && !epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") &&
        !epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic")) {
        return 1.0f;
    }
    GLfloat maximum = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &maximum);
    clearGlErrors();
    return maximum;
}

struct RenderTarget
{
    GlObject framebuffer;
    GlObject color;
    GlObject depth;
};

RenderTarget createRenderTarget(int width, int height, int samples, bool withDepth)
{
    RenderTarget target;
    target.framebuffer = createFramebuffer();
    target.color = createRenderbuffer();
    glNamedRenderbufferStorageMultisample(target.color.id(), samples > 1 ? samples : 0, GL_SRGB8_ALPHA8, width,
                                          height);
    glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color.id());
    if (withDepth) {
        target.depth = createRenderbuffer();
        glNamedRenderbufferStorageMultisample(target.depth.id(), samples > 1 ? samples : 0, GL_DEPTH_COMPONENT24,
                                              width, height);
        glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                       target.depth.id());
    }
    checkGl("creating the framebuffer");
    const GLenum status = glCheckNamedFramebufferStatus(target.framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("OpenGL framebuffer " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                    std::to_string(samples) + " samples is incomplete (status 0x" + [status] {
                        char buffer[16];
                        std::snprintf(buffer, sizeof(buffer), "%x", unsigned(status));
                        return std::string(buffer);
                    }() + ")");
    }
    return target;
}

/// Restores the GL state renderSnapshot changes to GL's defaults, however
/// it leaves.
struct StateGuard
{
    ~StateGuard()
    {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glUseProgram(0);
        glBindTextureUnit(0, 0);
        glBindTextureUnit(1, 0);
        glDisable(GL_FRAMEBUFFER_SRGB);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glEnable(GL_MULTISAMPLE);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    }
};

} // namespace

Image renderSnapshot(EglContext& context, const MeshView& mesh, const SnapshotOptions& options)
{
    checkOptions(mesh, options);
    const TriplanarMaterial& material = options.material;
    const bool hasSide = material.sideAlbedo.width > 0 || !material.sideAlbedo.pixels.empty();
    const bool hasTop = material.topAlbedo.width > 0 || !material.topAlbedo.pixels.empty();
    if (hasSide) {
        checkTexture(material.sideAlbedo, "sideAlbedo");
    }
    if (hasTop) {
        checkTexture(material.topAlbedo, "topAlbedo");
    }

    context.makeCurrent();
    clearGlErrors();
    StateGuard guard;

    const int width = options.width;
    const int height = options.height;
    GLint maxSamples = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
    GLint maxRenderbufferSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbufferSize);
    GLint maxTextureSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
    if (width > maxRenderbufferSize || height > maxRenderbufferSize) {
        throw Error("snapshot: size " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds this OpenGL's limit of " + std::to_string(maxRenderbufferSize));
    }
    for (const Image* image : {&material.sideAlbedo, &material.topAlbedo}) {
        if (image->width > maxTextureSize || image->height > maxTextureSize) {
            throw Error("snapshot: texture " + std::to_string(image->width) + "x" + std::to_string(image->height) +
                        " exceeds this OpenGL's limit of " + std::to_string(maxTextureSize));
        }
    }
    const int samples = std::clamp(options.samples, 1, std::max(maxSamples, 1));

    // Program.
    const GlObject vertexShader = compileShader(GL_VERTEX_SHADER, shaders::TERRAIN_VERT, "terrain vertex");
    const GlObject fragmentShader = compileShader(GL_FRAGMENT_SHADER, shaders::TERRAIN_FRAG, "terrain fragment");
    const GlObject program = linkProgram(vertexShader, fragmentShader);
    checkGl("building the terrain program");

    // Textures. Without a side map the material is a plain light grey.
    const float anisotropy = std::min(options.anisotropy, maxAnisotropy());
    Image fallback;
    if (!hasSide) {
        fallback.width = 1;
        fallback.height = 1;
        fallback.pixels = {180, 180, 180, 255};
    }
    const GlObject sideTexture = uploadTexture(hasSide ? material.sideAlbedo : fallback, anisotropy);
    GlObject topTexture;
    if (hasTop) {
        topTexture = uploadTexture(material.topAlbedo, anisotropy);
    }

    // Mesh: positions then normals in one buffer, indices in another.
    const GlObject vertexArray = createVertexArray();
    const GlObject vertexBuffer = createBuffer();
    const GlObject indexBuffer = createBuffer();
    const std::size_t arrayBytes = mesh.vertexCount * sizeof(glm::vec3);
    if (mesh.vertexCount > 0 && mesh.indexCount > 0) {
        glNamedBufferStorage(vertexBuffer.id(), GLsizeiptr(2 * arrayBytes), nullptr, GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferSubData(vertexBuffer.id(), 0, GLsizeiptr(arrayBytes), mesh.positions);
        glNamedBufferSubData(vertexBuffer.id(), GLintptr(arrayBytes), GLsizeiptr(arrayBytes), mesh.normals);
        glNamedBufferStorage(indexBuffer.id(), GLsizeiptr(mesh.indexCount * sizeof(std::uint32_t)), mesh.indices, 0);
        glVertexArrayVertexBuffer(vertexArray.id(), 0, vertexBuffer.id(), 0, sizeof(glm::vec3));
        glVertexArrayVertexBuffer(vertexArray.id(), 1, vertexBuffer.id(), GLintptr(arrayBytes), sizeof(glm::vec3));
        glVertexArrayElementBuffer(vertexArray.id(), indexBuffer.id());
        for (GLuint attribute = 0; attribute < 2; ++attribute) {
            glEnableVertexArrayAttrib(vertexArray.id(), attribute);
            glVertexArrayAttribFormat(vertexArray.id(), attribute, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(vertexArray.id(), attribute, attribute);
        }
        checkGl("uploading the mesh");
    }

    // Framebuffers: multisampled target, resolved into a single-sample one.
    const RenderTarget resolved = createRenderTarget(width, height, 1, samples == 1);
    RenderTarget multisampled;
    if (samples > 1) {
        multisampled = createRenderTarget(width, height, samples, true);
    }
    const GLuint drawFramebuffer = samples > 1 ? multisampled.framebuffer.id() : resolved.framebuffer.id();

    // Uniforms.
    const double aspect = double(width) / double(height);
    const glm::mat4 viewProjection =
        projectionMatrix(options.camera, aspect) * viewMatrix(options.camera, mesh.origin);
    // Texture space is world · mapScale; the integer part of the origin's
    // share is dropped in double precision (textures repeat every unit).
    const glm::dvec3 originScaled = mesh.origin * double(material.mapScale);
    const glm::vec3 textureOffset = glm::vec3(originScaled - glm::floor(originScaled));
    const Lighting& lighting = options.lighting;
    glm::vec3 sun = lighting.sunDirection;
    sun = glm::length(sun) > 0.0f ? glm::normalize(sun) : glm::vec3(0.0f, 1.0f, 0.0f);

    const GLuint p = program.id();
    auto location = [p](const char* name) { return glGetUniformLocation(p, name); };
    glProgramUniformMatrix4fv(p, location("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    glProgramUniform1f(p, location("uMapScale"), material.mapScale);
    glProgramUniform3fv(p, location("uTextureOffset"), 1, glm::value_ptr(textureOffset));
    glProgramUniform1i(p, location("uSideAlbedo"), 0);
    glProgramUniform1i(p, location("uTopAlbedo"), 1);
    glProgramUniform1i(p, location("uHasTopAlbedo"), hasTop ? 1 : 0);
    glProgramUniform1f(p, location("uBlendOffset"), material.blendOffset);
    glProgramUniform1f(p, location("uBlendExponent"), material.blendExponent);
    glProgramUniform3fv(p, location("uSunDirection"), 1, glm::value_ptr(sun));
    glProgramUniform3fv(p, location("uSunColor"), 1, glm::value_ptr(lighting.sunColor));
    glProgramUniform3fv(p, location("uSkyAmbient"), 1, glm::value_ptr(lighting.skyAmbient));
    glProgramUniform3fv(p, location("uGroundAmbient"), 1, glm::value_ptr(lighting.groundAmbient));
    checkGl("setting the uniforms");

    // Draw. The framebuffer is sRGB and GL_FRAMEBUFFER_SRGB is on: the
    // shader and the clear colour are linear, the stored bytes sRGB-encoded.
    glBindFramebuffer(GL_FRAMEBUFFER, drawFramebuffer);
    glViewport(0, 0, width, height);
    glEnable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    const glm::vec3 sky = lighting.skyColor;
    glClearColor(sky.r, sky.g, sky.b, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (mesh.vertexCount > 0 && mesh.indexCount > 0) {
        glUseProgram(p);
        glBindVertexArray(vertexArray.id());
        glBindTextureUnit(0, sideTexture.id());
        glBindTextureUnit(1, hasTop ? topTexture.id() : sideTexture.id());
        glDrawElements(GL_TRIANGLES, GLsizei(mesh.indexCount), GL_UNSIGNED_INT, nullptr);
    }
    checkGl("drawing the mesh");

    if (samples > 1) {
        glBlitNamedFramebuffer(multisampled.framebuffer.id(), resolved.framebuffer.id(), 0, 0, width, height, 0, 0,
                               width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        checkGl("resolving the multisampled framebuffer");
    }

    // Read back (GL rows run bottom to top) and flip.
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * std::size_t(height) * 4);
    std::vector<std::uint8_t> rows(image.pixels.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved.framebuffer.id());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    checkGl("reading the image back");
    const std::size_t rowBytes = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y) {
        std::memcpy(image.pixels.data() + std::size_t(y) * rowBytes,
                    rows.data() + std::size_t(height - 1 - y) * rowBytes, rowBytes);
    }
    return image;
}

} // namespace strata::render
