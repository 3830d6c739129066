#include <strata/render/GlRenderer.h>

#include <strata/Error.h>
#include <strata/render/EglContext.h>

#include "MaterialMaps.h"
#include "ShadingBridge.h"
#include <strata/shaders/EmbeddedShaders.h>

#include <epoxy/gl.h>

#include <glm/geometric.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
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
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
        return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
        return "GL_STACK_OVERFLOW";
    default:
        return "GL error " + std::to_string(error);
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

void checkOptions(const MeshView& mesh, const SnapshotOptions& options)
{
    checkSnapshotOptions(options);
    assert(mesh.indexCount % 3 == 0);
    assert(mesh.vertexCount == 0 || (mesh.positions && mesh.normals));
    assert(mesh.indexCount == 0 || mesh.indices);
    if (mesh.indexCount > std::size_t(std::numeric_limits<GLsizei>::max())) {
        throw Error("snapshot: mesh has too many indices for one draw (" + std::to_string(mesh.indexCount) + ")");
    }
    for (std::size_t i = 0; i < mesh.indexCount; ++i) {
        if (mesh.indices[i] >= mesh.vertexCount) {
            throw Error("snapshot: mesh index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", beyond the " + std::to_string(mesh.vertexCount) + " vertices");
        }
    }
}

/// Uploads a Texture's mip chain as built on the CPU (the same texels the
/// CPU sampler filters): sRGB8_ALPHA8 or RGBA8 by kind, repeating,
/// trilinear (anisotropic where asked). Rows are already bottom to top.
GlObject uploadTexture(const Texture& texture, float anisotropy)
{
    GlObject object = createTexture2D();
    const GLuint id = object.id();
    const auto levels = GLsizei(texture.levels.size());
    glTextureStorage2D(id, levels, texture.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, texture.width(), texture.height());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (GLsizei level = 0; level < levels; ++level) {
        const Texture::Level& l = texture.levels[std::size_t(level)];
        glTextureSubImage2D(id, level, 0, 0, l.width, l.height, GL_RGBA, GL_UNSIGNED_BYTE, l.texels.data());
    }
    glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
    if (anisotropy > 1.0f) {
        glTextureParameterf(id, GL_TEXTURE_MAX_ANISOTROPY_EXT, anisotropy);
    }
    checkGl("uploading a texture");
    return object;
}

/// The fragment program for one feature set: STRATA_FEATURES defined right
/// after the #version line.
std::string fragmentSource(std::uint32_t features)
{
    std::string source = shaders::TERRAIN_FRAG;
    const std::size_t lineEnd = source.find('\n');
    source.insert(lineEnd + 1, "#define STRATA_FEATURES " + std::to_string(features) + "u\n");
    return source;
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
    glNamedRenderbufferStorageMultisample(target.color.id(), samples > 1 ? samples : 0, GL_SRGB8_ALPHA8, width, height);
    glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color.id());
    if (withDepth) {
        target.depth = createRenderbuffer();
        glNamedRenderbufferStorageMultisample(target.depth.id(), samples > 1 ? samples : 0, GL_DEPTH_COMPONENT24, width,
                                              height);
        glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                       target.depth.id());
    }
    checkGl("creating the framebuffer");
    const GLenum status = glCheckNamedFramebufferStatus(target.framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("OpenGL framebuffer " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                    std::to_string(samples) + " samples is incomplete (status 0x" +
                    [status] {
                        char buffer[16];
                        std::snprintf(buffer, sizeof(buffer), "%x", unsigned(status));
                        return std::string(buffer);
                    }() +
                    ")");
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
        for (GLuint unit = 0; unit < 9; ++unit) {
            glBindTextureUnit(unit, 0);
        }
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
    const Material& material = options.material;
    const std::array<TexturePtr, 9> maps = detail::resolveMaps(material);
    const std::uint32_t features = materialFeatures(material);

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
    for (const TexturePtr& texture : maps) {
        if (texture->width() > maxTextureSize || texture->height() > maxTextureSize) {
            throw Error("snapshot: texture " + std::to_string(texture->width()) + "x" +
                        std::to_string(texture->height()) + " exceeds this OpenGL's limit of " +
                        std::to_string(maxTextureSize));
        }
    }
    const int samples = std::clamp(options.samples, 1, std::max(maxSamples, 1));

    // Program.
    const GlObject vertexShader = compileShader(GL_VERTEX_SHADER, shaders::TERRAIN_VERT, "terrain vertex");
    const std::string fragment = fragmentSource(features);
    const GlObject fragmentShader = compileShader(GL_FRAGMENT_SHADER, fragment.c_str(), "terrain fragment");
    const GlObject program = linkProgram(vertexShader, fragmentShader);
    checkGl("building the terrain program");

    // Textures: the nine slots, each texture uploaded once.
    const float anisotropy = std::min(options.anisotropy, maxAnisotropy());
    std::vector<GlObject> uploaded;
    std::vector<const Texture*> uploadedFrom;
    GLuint units[9] = {};
    for (std::size_t slot = 0; slot < 9; ++slot) {
        const auto found = std::find(uploadedFrom.begin(), uploadedFrom.end(), maps[slot].get());
        if (found != uploadedFrom.end()) {
            units[slot] = uploaded[std::size_t(found - uploadedFrom.begin())].id();
            continue;
        }
        uploaded.push_back(uploadTexture(*maps[slot], anisotropy));
        uploadedFrom.push_back(maps[slot].get());
        units[slot] = uploaded.back().id();
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
    const glm::mat4 viewProjection = projectionMatrix(options.camera, aspect) * viewMatrix(options.camera, mesh.origin);
    // Texture space is world · mapScale; the integer part of the origin's
    // share is dropped in double precision (textures repeat every unit).
    const glm::dvec3 originScaled = mesh.origin * double(material.mapScale);
    const glm::vec3 textureOffset = glm::vec3(originScaled - glm::floor(originScaled));
    const Lighting& lighting = options.lighting;
    const shading::MaterialParams mp = detail::toShading(material);
    const shading::LightingParams lp = detail::toShading(lighting);
    const glm::vec3 cameraPosition = glm::vec3(options.camera.position - mesh.origin);

    const GLuint p = program.id();
    auto location = [p](const std::string& name) { return glGetUniformLocation(p, name.c_str()); };
    auto set1f = [&](const std::string& name, float v) { glProgramUniform1f(p, location(name), v); };
    auto set3f = [&](const std::string& name, const glm::vec3& v) {
        glProgramUniform3fv(p, location(name), 1, glm::value_ptr(v));
    };
    glProgramUniformMatrix4fv(p, location("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    glProgramUniform1f(p, location("uMapScale"), material.mapScale);
    glProgramUniform3fv(p, location("uTextureOffset"), 1, glm::value_ptr(textureOffset));
    set3f("uCameraPosition", cameraPosition);
    for (int slot = 0; slot < 9; ++slot) {
        glProgramUniform1i(p, location("uMaps[" + std::to_string(slot) + "]"), slot);
    }
    set3f("uMaterial.albedoTint", mp.albedoTint);
    set1f("uMaterial.blendOffset", mp.blendOffset);
    set1f("uMaterial.blendExponent", mp.blendExponent);
    set1f("uMaterial.heightStrength", mp.heightStrength);
    set1f("uMaterial.metallic", mp.metallic);
    set1f("uMaterial.smoothness", mp.smoothness);
    set1f("uMaterial.occlusionStrength", mp.occlusionStrength);
    set1f("uMaterial.normalStrength", mp.normalStrength);
    set1f("uMaterial.detailScale", mp.detailScale);
    set1f("uMaterial.detailAlbedo", mp.detailAlbedo);
    set1f("uMaterial.detailSmoothness", mp.detailSmoothness);
    set1f("uMaterial.detailNormalStrength", mp.detailNormalStrength);
    set3f("uMaterial.emissionColor", mp.emissionColor);
    set1f("uMaterial.fresnelStrength", mp.fresnelStrength);
    for (int i = 0; i < STRATA_MAX_LIGHTS; ++i) {
        const std::string prefix = "uLighting.lights[" + std::to_string(i) + "].";
        set3f(prefix + "direction", lp.lights[i].direction);
        set3f(prefix + "color", lp.lights[i].color);
    }
    glProgramUniform1i(p, location("uLighting.lightCount"), lp.lightCount);
    set3f("uLighting.skyAmbient", lp.skyAmbient);
    set3f("uLighting.groundAmbient", lp.groundAmbient);
    set1f("uLighting.exposure", lp.exposure);
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
        for (GLuint slot = 0; slot < 9; ++slot) {
            glBindTextureUnit(slot, units[slot]);
        }
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
