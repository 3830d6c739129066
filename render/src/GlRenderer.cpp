// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/render/GlRenderer.h>

#include <strata/Error.h>
#include <strata/render/GlContext.h>

#include "AtmosphereSetup.h"
#include "GlProgram.h"
#include "LayerSetup.h"
#include "MaterialMaps.h"
#include "ShadingBridge.h"
#include "ShadowSetup.h"
#include "UniformBlocks.h"
#include <strata/shaders/EmbeddedShaders.h>

#include <epoxy/gl.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace strata::render {

using detail::GlObject;

static_assert(int(DebugView::Shaded) == shading::DEBUG_VIEW_SHADED);
static_assert(int(DebugView::TriplanarWeights) == shading::DEBUG_VIEW_WEIGHTS);
static_assert(int(DebugView::WorldNormals) == shading::DEBUG_VIEW_NORMALS);
static_assert(int(DebugView::Metallic) == shading::DEBUG_VIEW_METALLIC);
static_assert(int(DebugView::Occlusion) == shading::DEBUG_VIEW_OCCLUSION);
static_assert(int(DebugView::Height) == shading::DEBUG_VIEW_HEIGHT);
static_assert(int(DebugView::Smoothness) == shading::DEBUG_VIEW_SMOOTHNESS);
static_assert(int(DebugView::Albedo) == shading::DEBUG_VIEW_ALBEDO);
static_assert(int(DebugView::Layers) == shading::DEBUG_VIEW_LAYERS);
static_assert(int(DebugView::Flow) == shading::DEBUG_VIEW_FLOW);
static_assert(int(DebugView::Wear) == shading::DEBUG_VIEW_WEAR);
static_assert(int(DebugView::Deposition) == shading::DEBUG_VIEW_DEPOSITION);
static_assert(int(DebugView::Water) == shading::DEBUG_VIEW_WATER);
static_assert(int(DebugView::Bed) == shading::DEBUG_VIEW_BED);
static_assert(DEBUG_VIEW_COUNT == shading::DEBUG_VIEW_COUNT);
static_assert(detail::MATERIAL_MAP_UNITS == STRATA_MAP_COUNT);

namespace {

float driverMaxAnisotropy()
{
    if (epoxy_gl_version() < 46 && !epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic") &&
        !epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic")) {
        return 1.0f;
    }
    GLfloat maximum = 1.0f;
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT, &maximum);
    detail::clearGlErrors();
    return std::max(maximum, 1.0f);
}


/// The fragment program for one feature set: STRATA_FEATURES defined right
/// after the #version line; layered programs also get their layer count, so
/// the layer loop unrolls to exactly that many copies of the material
/// (llvmpipe runs both sides of every branch: a loop to the uniform count
/// measured 4.6× the single material's frame time with two layers).
std::string fragmentSource(std::uint32_t features, int layerCount)
{
    std::string source = shaders::TERRAIN_FRAG;
    const std::size_t lineEnd = source.find('\n');
    std::string defines = "#define STRATA_FEATURES " + std::to_string(features) + "u\n";
    if (features & feature::LAYERS) {
        defines += "#define STRATA_LAYERED 1\n#define STRATA_LAYER_COUNT " + std::to_string(layerCount) + "\n";
    }
    source.insert(lineEnd + 1, defines);
    return source;
}

std::string hex(unsigned value)
{
    char buffer[16];
    std::snprintf(buffer, sizeof(buffer), "%x", value);
    return buffer;
}

struct RenderTarget
{
    GlObject framebuffer;
    GlObject color;
    GlObject depth;
    int width = 0;
    int height = 0;
    int samples = 0;
};

RenderTarget createRenderTarget(int width, int height, int samples, bool withDepth)
{
    RenderTarget target;
    target.width = width;
    target.height = height;
    target.samples = samples;
    target.framebuffer = detail::createFramebuffer();
    target.color = detail::createRenderbuffer();
    glNamedRenderbufferStorageMultisample(target.color.id(), samples > 1 ? samples : 0, GL_SRGB8_ALPHA8, width, height);
    glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target.color.id());
    if (withDepth) {
        target.depth = detail::createRenderbuffer();
        glNamedRenderbufferStorageMultisample(target.depth.id(), samples > 1 ? samples : 0, GL_DEPTH_COMPONENT24, width,
                                              height);
        glNamedFramebufferRenderbuffer(target.framebuffer.id(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                                       target.depth.id());
    }
    detail::checkGl("creating the framebuffer");
    const GLenum status = glCheckNamedFramebufferStatus(target.framebuffer.id(), GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        throw Error(ErrorKind::Gl, "OpenGL framebuffer " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                    std::to_string(samples) + " samples is incomplete (status 0x" + hex(status) + ")");
    }
    return target;
}

/// Restores the GL state the renderer changes to GL's defaults, however
/// it leaves.
struct StateGuard
{
    ~StateGuard()
    {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glBindVertexArray(0);
        glUseProgram(0);
        for (GLuint unit = 0; unit < detail::MATERIAL_MAP_UNITS; ++unit) {
            glBindTextureUnit(unit, 0);
        }
        glBindTextureUnit(detail::SHADOW_MAP_UNIT, 0);
        for (GLuint binding : {detail::FRAME_BLOCK_BINDING, detail::MATERIAL_BLOCK_BINDING,
                               detail::LIGHTING_BLOCK_BINDING, detail::SHADOW_BLOCK_BINDING,
                               detail::LAYER_BLOCK_BINDING}) {
            glBindBufferBase(GL_UNIFORM_BUFFER, binding, 0);
        }
        glDisable(GL_FRAMEBUFFER_SRGB);
        glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDisable(GL_CULL_FACE);
        glEnable(GL_MULTISAMPLE);
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        glDisable(GL_POLYGON_OFFSET_LINE);
        glPolygonOffset(0.0f, 0.0f);
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    }
};

void checkCamera(const Camera& c)
{
    if (!(c.nearPlane > 0.0 && c.farPlane > c.nearPlane)) {
        throw Error(ErrorKind::BadInput, "render: camera needs 0 < near < far");
    }
    if (!(c.fovYDegrees > 0.0 && c.fovYDegrees < 180.0)) {
        throw Error(ErrorKind::BadInput, "render: camera fovYDegrees outside (0, 180)");
    }
    if (!(glm::length(c.target - c.position) > 0.0)) {
        throw Error(ErrorKind::BadInput, "render: camera position equals its target");
    }
}

/// One map slot's texture array on the GPU, keyed by its layers' textures.
struct ResidentTexture
{
    std::vector<TexturePtr> sources; // keep the pointers valid as the key
    GlObject object;
};

} // namespace

namespace {

/// The sampling state of a material map: its mip chain, trilinear, repeating.
void setMapSampling(GLuint id, GLsizei levels)
{
    glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_REPEAT);
}

} // namespace

detail::GlObject detail::uploadTexture(const Texture& texture)
{
    GlObject object = detail::createTexture2D();
    const GLuint id = object.id();
    const auto levels = GLsizei(texture.levels.size());
    glTextureStorage2D(id, levels, texture.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, texture.width(), texture.height());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (GLsizei level = 0; level < levels; ++level) {
        const Texture::Level& l = texture.levels[std::size_t(level)];
        glTextureSubImage2D(id, level, 0, 0, l.width, l.height, GL_RGBA, GL_UNSIGNED_BYTE, l.texels.data());
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    setMapSampling(id, levels);
    detail::checkGl("uploading a texture");
    return object;
}

detail::GlObject detail::uploadTextureArray(const std::vector<TexturePtr>& layers)
{
    const Texture& first = *layers.front();
    GlObject object = detail::createTexture2DArray();
    const GLuint id = object.id();
    const auto levels = GLsizei(first.levels.size());
    glTextureStorage3D(id, levels, first.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, first.width(), first.height(),
                       GLsizei(layers.size()));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (std::size_t layer = 0; layer < layers.size(); ++layer) {
        for (GLsizei level = 0; level < levels; ++level) {
            const Texture::Level& l = layers[layer]->levels[std::size_t(level)];
            glTextureSubImage3D(id, level, 0, 0, GLint(layer), l.width, l.height, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                                l.texels.data());
        }
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    setMapSampling(id, levels);
    detail::checkGl("uploading a texture array");
    return object;
}

struct GlRenderer::Impl
{
    explicit Impl(GlContext& c) : context(c) {}

    GlContext& context;
    GLint maxSamples = 1;
    GLint maxRenderbufferSize = 0;
    GLint maxTextureSize = 0;
    float maxAnisotropy = 1.0f;

    // Uniform buffers (std140).
    GlObject frameBuffer;
    GlObject materialBuffer;
    GlObject lightingBuffer;
    GlObject atmosphereBuffer;
    GlObject layerBuffer; // LayerSetBlock (binding 5), layered materials

    // The sky pass (atmosphere on): its program and an empty vertex array
    // (the full-viewport triangle comes from gl_VertexID).
    GlObject skyProgram;
    GlObject skyVertexArray;

    // Mesh.
    GlObject vertexArray;
    GlObject vertexBuffer;
    GlObject indexBuffer;
    GLsizei indexCount = 0;
    glm::dvec3 origin{0.0};
    detail::MeshBounds bounds; // of the vertices, mesh-relative (fits the shadow map)

    // Sun shadows: depth map, its framebuffer, the depth-pass program, the
    // depth pass's FrameBlock and the ShadowBlock (binding 3).
    GlObject shadowMap;
    GlObject shadowFramebuffer;
    GlObject shadowProgram;
    GlObject shadowFrameBuffer;
    GlObject shadowBuffer;
    int shadowResolution = 0;
    // The light view the map holds (valid while shadowCurrent): a frame with
    // the same mesh, light and resolution reuses it (the viewer's frames).
    glm::mat4 shadowDrawnView{1.0f};
    bool shadowCurrent = false;

    // Material.
    bool haveMaterial = false;
    Material material;
    float anisotropy = 1.0f;
    std::vector<ResidentTexture> textures;
    std::array<GLuint, STRATA_MAP_COUNT> units{};

    // Programs, one per feature set.
    GlObject vertexShader;
    std::map<std::uint64_t, GlObject> programs; // by features and, layered, the layer count
    ProgramStats stats;

    // Off-screen target of drawFrame().
    RenderTarget multisampled;
    RenderTarget resolved;
    bool haveFrame = false;

    GLuint program(std::uint32_t features)
    {
        features = normalizeFeatures(features);
        const int layerCount = (features & feature::LAYERS) ? 1 + int(material.layers.size()) : 1;
        const std::uint64_t key = std::uint64_t(features) | (std::uint64_t(layerCount) << 32);
        const auto found = programs.find(key);
        if (found != programs.end()) {
            return found->second.id();
        }
        const auto t0 = std::chrono::steady_clock::now();
        if (!vertexShader) {
            vertexShader = detail::compileShader(GL_VERTEX_SHADER, shaders::TERRAIN_VERT, "terrain vertex");
        }
        const std::string names = featureNames(features);
        const GlObject fragment =
            detail::compileShader(GL_FRAGMENT_SHADER, fragmentSource(features, layerCount), "terrain fragment (" + names + ")");
        GlObject linked = detail::linkProgram(vertexShader, fragment, "terrain (" + names + ")");
        detail::checkGl("building the terrain program");
        const GLuint id = linked.id();
        programs.emplace(key, std::move(linked));
        stats.compiled = int(programs.size());
        stats.featureSets.push_back(features);
        stats.compileSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return id;
    }

    /// The sun's depth map (shaders/Shadow.h, step 1) for `sp` into
    /// shadowMap, and the ShadowBlock; with shadows off or no mesh only the
    /// block (enabled = 0). Needs the terrain vertex shader (program() first).
    /// Leaves the framebuffer, viewport and FrameBlock binding to the caller.
    void renderShadowMap(const shading::ShadowParams& sp)
    {
        if (!shadowBuffer) {
            shadowBuffer = detail::createBuffer();
            glNamedBufferStorage(shadowBuffer.id(), sizeof(shading::ShadowParams), nullptr, GL_DYNAMIC_STORAGE_BIT);
            shadowFrameBuffer = detail::createBuffer();
            glNamedBufferStorage(shadowFrameBuffer.id(), sizeof(detail::FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
        }
        glNamedBufferSubData(shadowBuffer.id(), 0, sizeof(sp), &sp);
        glBindBufferBase(GL_UNIFORM_BUFFER, detail::SHADOW_BLOCK_BINDING, shadowBuffer.id());
        if (sp.enabled == 0 || indexCount == 0) {
            return;
        }
        if (sp.resolution > maxTextureSize) {
            throw Error(ErrorKind::BadInput, "render: shadow resolution " + std::to_string(sp.resolution) +
                        " exceeds this OpenGL's texture limit of " + std::to_string(maxTextureSize));
        }
        if (!shadowProgram) {
            const GlObject fragment =
                detail::compileShader(GL_FRAGMENT_SHADER, shaders::SHADOW_DEPTH_FRAG, "shadow depth fragment");
            shadowProgram = detail::linkProgram(vertexShader, fragment, "shadow depth");
        }
        if (shadowResolution != sp.resolution) {
            shadowFramebuffer = GlObject();
            shadowMap = detail::createTexture2D();
            glTextureStorage2D(shadowMap.id(), 1, GL_DEPTH_COMPONENT32F, sp.resolution, sp.resolution);
            glTextureParameteri(shadowMap.id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(shadowMap.id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            glTextureParameteri(shadowMap.id(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
            glTextureParameteri(shadowMap.id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
            glTextureParameteri(shadowMap.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
            shadowFramebuffer = detail::createFramebuffer();
            glNamedFramebufferTexture(shadowFramebuffer.id(), GL_DEPTH_ATTACHMENT, shadowMap.id(), 0);
            glNamedFramebufferDrawBuffer(shadowFramebuffer.id(), GL_NONE);
            glNamedFramebufferReadBuffer(shadowFramebuffer.id(), GL_NONE);
            const GLenum status = glCheckNamedFramebufferStatus(shadowFramebuffer.id(), GL_FRAMEBUFFER);
            if (status != GL_FRAMEBUFFER_COMPLETE) {
                throw Error(ErrorKind::Gl, "OpenGL shadow-map framebuffer " + std::to_string(sp.resolution) + "² is incomplete (status 0x" +
                            hex(status) + ")");
            }
            shadowResolution = sp.resolution;
            shadowCurrent = false;
        }
        if (shadowCurrent && shadowDrawnView == sp.lightViewProjection) {
            return; // the map already holds this mesh from this light
        }
        detail::FrameBlock frame{};
        frame.viewProjection = sp.lightViewProjection;
        glNamedBufferSubData(shadowFrameBuffer.id(), 0, sizeof(frame), &frame);
        glBindBufferBase(GL_UNIFORM_BUFFER, detail::FRAME_BLOCK_BINDING, shadowFrameBuffer.id());
        // Same rules as the CPU's shadow pass: both windings, GL_LESS, cleared to 1.
        glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer.id());
        glViewport(0, 0, sp.resolution, sp.resolution);
        glDisable(GL_FRAMEBUFFER_SRGB);
        glDisable(GL_CULL_FACE);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glClearDepth(1.0);
        glClear(GL_DEPTH_BUFFER_BIT);
        glUseProgram(shadowProgram.id());
        glBindVertexArray(vertexArray.id());
        glDrawElements(GL_TRIANGLES, indexCount, GL_UNSIGNED_INT, nullptr);
        detail::checkGl("drawing the shadow map");
        shadowDrawnView = sp.lightViewProjection;
        shadowCurrent = true;
    }

    /// The sky pass (sky.frag) over the whole viewport: no depth test or
    /// write, so the terrain then draws over it. Needs the lighting and
    /// atmosphere blocks bound; restores the depth and cull state draw() set.
    void drawSky()
    {
        if (!skyProgram) {
            const GlObject vertex = detail::compileShader(GL_VERTEX_SHADER, shaders::FULLSCREEN_VERT, "sky vertex");
            const GlObject fragment = detail::compileShader(GL_FRAGMENT_SHADER, shaders::SKY_FRAG, "sky fragment");
            skyProgram = detail::linkProgram(vertex, fragment, "sky");
        }
        glDisable(GL_DEPTH_TEST);
        glDepthMask(GL_FALSE);
        glDisable(GL_CULL_FACE);
        glUseProgram(skyProgram.id());
        glBindVertexArray(skyVertexArray.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glEnable(GL_CULL_FACE);
        detail::checkGl("drawing the sky");
    }

    void ensureMaterial()
    {
        if (!haveMaterial) {
            throw Error(ErrorKind::BadInput, "render: no material set (call GlRenderer::setMaterial first)");
        }
    }
};

GlRenderer::GlRenderer(GlContext& context) : mImpl(std::make_unique<Impl>(context))
{
    Impl& r = *mImpl;
    context.makeCurrent();
    detail::clearGlErrors();
    glGetIntegerv(GL_MAX_SAMPLES, &r.maxSamples);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &r.maxRenderbufferSize);
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &r.maxTextureSize);
    r.maxAnisotropy = driverMaxAnisotropy();
    r.frameBuffer = detail::createBuffer();
    r.materialBuffer = detail::createBuffer();
    r.lightingBuffer = detail::createBuffer();
    glNamedBufferStorage(r.frameBuffer.id(), sizeof(detail::FrameBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(r.materialBuffer.id(), sizeof(detail::MaterialBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferStorage(r.lightingBuffer.id(), sizeof(detail::LightingBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    r.atmosphereBuffer = detail::createBuffer();
    glNamedBufferStorage(r.atmosphereBuffer.id(), sizeof(shading::AtmosphereParams), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    r.layerBuffer = detail::createBuffer();
    glNamedBufferStorage(r.layerBuffer.id(), sizeof(detail::LayerSetBlock), nullptr, GL_DYNAMIC_STORAGE_BIT);
    r.vertexArray = detail::createVertexArray();
    r.skyVertexArray = detail::createVertexArray();
    r.stats.possible = int(allFeatureSets().size());
    detail::checkGl("creating the renderer");
}

GlRenderer::~GlRenderer()
{
    // GL names are deleted in the context that made them.
    try {
        mImpl->context.makeCurrent();
    } catch (const Error&) {
        // The context is gone or elsewhere: nothing sensible to delete in.
    }
}

GlContext& GlRenderer::context() const { return mImpl->context; }

void GlRenderer::setMesh(const MeshView& mesh)
{
    Impl& r = *mImpl;
    assert(mesh.indexCount % 3 == 0);
    assert(mesh.vertexCount == 0 || (mesh.positions && mesh.normals));
    assert(mesh.indexCount == 0 || mesh.indices);
    if (mesh.indexCount > std::size_t(std::numeric_limits<GLsizei>::max())) {
        throw Error(ErrorKind::BadInput, "render: mesh has too many indices for one draw (" + std::to_string(mesh.indexCount) + ")");
    }
    for (std::size_t i = 0; i < mesh.indexCount; ++i) {
        if (mesh.indices[i] >= mesh.vertexCount) {
            throw Error(ErrorKind::BadInput, "snapshot: mesh index " + std::to_string(i) + " is " + std::to_string(mesh.indices[i]) +
                        ", beyond the " + std::to_string(mesh.vertexCount) + " vertices");
        }
    }
    r.context.makeCurrent();
    detail::clearGlErrors();
    // Fresh buffers: immutable storage cannot be resized.
    r.vertexArray = detail::createVertexArray();
    r.vertexBuffer = GlObject();
    r.indexBuffer = GlObject();
    r.indexCount = 0;
    r.shadowCurrent = false; // the shadow map shows the old mesh
    r.origin = mesh.origin;
    r.bounds = detail::meshBounds(mesh);
    if (mesh.vertexCount == 0 || mesh.indexCount == 0) {
        return;
    }
    r.vertexBuffer = detail::createBuffer();
    r.indexBuffer = detail::createBuffer();
    // Positions, normals, then the optional surface attributes (cavity,
    // cover), landform masks (flow, wear, deposition, water) and rock masks
    // (hardness, bed).
    const std::size_t arrayBytes = mesh.vertexCount * sizeof(glm::vec3);
    const std::size_t surfaceBytes = mesh.surface ? mesh.vertexCount * sizeof(glm::vec2) : 0;
    const std::size_t landformBytes = mesh.landform ? mesh.vertexCount * sizeof(glm::vec4) : 0;
    const std::size_t rockBytes = mesh.rock ? mesh.vertexCount * sizeof(glm::vec2) : 0;
    glNamedBufferStorage(r.vertexBuffer.id(), GLsizeiptr(2 * arrayBytes + surfaceBytes + landformBytes + rockBytes),
                         nullptr, GL_DYNAMIC_STORAGE_BIT);
    glNamedBufferSubData(r.vertexBuffer.id(), 0, GLsizeiptr(arrayBytes), mesh.positions);
    glNamedBufferSubData(r.vertexBuffer.id(), GLintptr(arrayBytes), GLsizeiptr(arrayBytes), mesh.normals);
    glNamedBufferStorage(r.indexBuffer.id(), GLsizeiptr(mesh.indexCount * sizeof(std::uint32_t)), mesh.indices, 0);
    const GLuint vao = r.vertexArray.id();
    glVertexArrayElementBuffer(vao, r.indexBuffer.id());
    // Attribute k reads binding k, `components` floats per vertex from `offset`.
    auto attribute = [&](GLuint k, GLint components, std::size_t offset) {
        glVertexArrayVertexBuffer(vao, k, r.vertexBuffer.id(), GLintptr(offset), GLsizei(components * sizeof(float)));
        glEnableVertexArrayAttrib(vao, k);
        glVertexArrayAttribFormat(vao, k, components, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, k, k);
    };
    attribute(0, 3, 0);
    attribute(1, 3, arrayBytes);
    // Absent attributes stay disabled and read the constants draw() sets.
    if (mesh.surface) {
        glNamedBufferSubData(r.vertexBuffer.id(), GLintptr(2 * arrayBytes), GLsizeiptr(surfaceBytes), mesh.surface);
        attribute(2, 2, 2 * arrayBytes);
    }
    if (mesh.landform) {
        const std::size_t offset = 2 * arrayBytes + surfaceBytes;
        glNamedBufferSubData(r.vertexBuffer.id(), GLintptr(offset), GLsizeiptr(landformBytes), mesh.landform);
        attribute(3, 4, offset);
    }
    if (mesh.rock) {
        const std::size_t offset = 2 * arrayBytes + surfaceBytes + landformBytes;
        glNamedBufferSubData(r.vertexBuffer.id(), GLintptr(offset), GLsizeiptr(rockBytes), mesh.rock);
        attribute(4, 2, offset);
    }
    detail::checkGl("uploading the mesh");
    r.indexCount = GLsizei(mesh.indexCount);
}

void GlRenderer::setMaterial(const Material& material, float anisotropy, TextureFilter filtering)
{
    Impl& r = *mImpl;
    checkMaterial(material);
    if (!(anisotropy >= 1.0f && anisotropy <= 16.0f)) {
        throw Error(ErrorKind::BadInput, "render: anisotropy " + std::to_string(anisotropy) + " outside 1..16");
    }
    const detail::LayerMaps maps = detail::resolveLayerMaps(material);
    r.context.makeCurrent();
    detail::clearGlErrors();
    for (const std::vector<TexturePtr>& slot : maps.slots) {
        const TexturePtr& texture = slot.front();
        if (texture->width() > r.maxTextureSize || texture->height() > r.maxTextureSize) {
            throw Error(ErrorKind::BadInput, "render: texture " + std::to_string(texture->width()) + "x" +
                        std::to_string(texture->height()) + " exceeds this OpenGL's limit of " +
                        std::to_string(r.maxTextureSize));
        }
    }
    const float applied = std::min(anisotropy, r.maxAnisotropy);
    std::vector<ResidentTexture> kept;
    for (std::size_t slot = 0; slot < maps.slots.size(); ++slot) {
        const std::vector<TexturePtr>& layers = maps.slots[slot];
        auto sameSources = [&layers](const ResidentTexture& t) { return t.sources == layers; };
        auto found = std::find_if(kept.begin(), kept.end(), sameSources);
        if (found == kept.end()) {
            auto old = std::find_if(r.textures.begin(), r.textures.end(), sameSources);
            if (old != r.textures.end()) {
                kept.push_back(std::move(*old));
                r.textures.erase(old);
            } else {
                kept.push_back({layers, detail::uploadTextureArray(layers)});
            }
            found = kept.end() - 1;
            if (applied > 1.0f || r.maxAnisotropy > 1.0f) {
                glTextureParameterf(found->object.id(), GL_TEXTURE_MAX_ANISOTROPY_EXT, applied);
            }
            glTextureParameteri(found->object.id(), GL_TEXTURE_MIN_FILTER,
                                filtering == TextureFilter::Bilinear ? GL_LINEAR_MIPMAP_NEAREST
                                                                     : GL_LINEAR_MIPMAP_LINEAR);
        }
        r.units[slot] = found->object.id();
    }
    r.textures = std::move(kept); // textures no longer used are deleted here
    const detail::MaterialBlock block = detail::toBlock(detail::toShading(material));
    glNamedBufferSubData(r.materialBuffer.id(), 0, sizeof(block), &block);
    detail::checkGl("setting the material");
    r.material = material;
    r.anisotropy = applied;
    r.haveMaterial = true;
}

std::uint32_t GlRenderer::activeFeatures(std::uint32_t mask) const
{
    return mImpl->haveMaterial ? effectiveFeatures(mImpl->material, mask) : normalizeFeatures(0u);
}

void GlRenderer::prepareProgram(std::uint32_t features)
{
    mImpl->context.makeCurrent();
    detail::clearGlErrors();
    mImpl->program(features);
}

ProgramStats GlRenderer::stats() const { return mImpl->stats; }

void GlRenderer::finish()
{
    mImpl->context.makeCurrent();
    glFinish();
}

void GlRenderer::draw(const Camera& camera, const Lighting& lighting, unsigned framebuffer, int width, int height,
                      const DrawOptions& options)
{
    Impl& r = *mImpl;
    r.ensureMaterial();
    checkCamera(camera);
    if (width < 1 || height < 1) {
        throw Error(ErrorKind::BadInput, "render: viewport " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
    }
    if (int(options.debugView) < 0 || int(options.debugView) >= DEBUG_VIEW_COUNT) {
        throw Error(ErrorKind::BadInput, "render: debug view " + std::to_string(int(options.debugView)) + " outside 0.." +
                    std::to_string(DEBUG_VIEW_COUNT - 1));
    }
    if (lighting.extraLights.size() > 3) {
        throw Error(ErrorKind::BadInput, "render: at most 3 extra lights");
    }
    r.context.makeCurrent();
    detail::clearGlErrors();
    StateGuard guard;

    const std::uint32_t features = effectiveFeatures(r.material, options.featureMask);
    const GLuint program = r.program(features);

    // Uniform blocks.
    const double aspect = double(width) / double(height);
    detail::FrameBlock frame{};
    frame.viewProjection = projectionMatrix(camera, aspect) * viewMatrix(camera, r.origin);
    frame.cameraPosition = glm::vec4(glm::vec3(camera.position - r.origin), 1.0f);
    // Texture space is world · mapScale with the origin's whole repeats
    // dropped in double precision (detail maps and the anti-tiling lattice
    // keep track of what was dropped).
    const detail::TextureRebase rebase =
        detail::rebaseTextures(r.material.mapScale, r.material.detailScale, r.origin);
    frame.textureOffset = glm::vec4(rebase.textureOffset, 0.0f);
    frame.detailOffset = glm::vec4(rebase.detailOffset, 0.0f);
    frame.tileOffset = glm::vec4(rebase.tileOffset, 0.0f);
    frame.wireColor = options.wireColor;
    frame.mapScale = r.material.mapScale;
    frame.debugView = int(options.debugView);
    frame.wireframePass = 0;
    // Without anisotropic filtering the shader picks each map's mip level
    // itself, with the CPU reference's formula, so a GPU's own approximation
    // of the level of detail (NVIDIA's differs from llvmpipe's) no longer
    // decides it; anisotropic filtering needs the GPU's gradient path.
    frame.explicitLod = r.anisotropy > 1.0f ? 0 : 1;
    glNamedBufferSubData(r.frameBuffer.id(), 0, sizeof(frame), &frame);
    const detail::LightingBlock lightingBlock = detail::toBlock(detail::toShading(lighting));
    glNamedBufferSubData(r.lightingBuffer.id(), 0, sizeof(lightingBlock), &lightingBlock);
    const shading::AtmosphereParams atmosphere = detail::makeAtmosphereParams(lighting, camera, r.origin, width, height);
    glNamedBufferSubData(r.atmosphereBuffer.id(), 0, sizeof(atmosphere), &atmosphere);
    glBindBufferBase(GL_UNIFORM_BUFFER, detail::ATMOSPHERE_BLOCK_BINDING, r.atmosphereBuffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, detail::FRAME_BLOCK_BINDING, r.frameBuffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, detail::MATERIAL_BLOCK_BINDING, r.materialBuffer.id());
    glBindBufferBase(GL_UNIFORM_BUFFER, detail::LIGHTING_BLOCK_BINDING, r.lightingBuffer.id());
    if (features & feature::LAYERS) {
        const detail::LayerSetBlock layers =
            detail::toBlock(detail::makeLayerSet(r.material, r.origin, options.featureMask));
        glNamedBufferSubData(r.layerBuffer.id(), 0, sizeof(layers), &layers);
        glBindBufferBase(GL_UNIFORM_BUFFER, detail::LAYER_BLOCK_BINDING, r.layerBuffer.id());
    }
    detail::checkGl("setting the uniform blocks");

    // Sun shadows: the depth pass into the shadow map, then the main pass
    // reads it on unit SHADOW_MAP_UNIT with the ShadowBlock.
    r.renderShadowMap(detail::makeShadowParams(r.bounds, lighting, options.shadows));
    glBindBufferBase(GL_UNIFORM_BUFFER, detail::FRAME_BLOCK_BINDING, r.frameBuffer.id());
    glBindTextureUnit(detail::SHADOW_MAP_UNIT, r.shadowMap.id());

    // The framebuffer is sRGB and GL_FRAMEBUFFER_SRGB is on: the shader and
    // the clear colour are linear, the stored bytes sRGB-encoded.
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
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
    if (options.clear) {
        const glm::vec3 sky = lighting.skyColor;
        glClearColor(sky.r, sky.g, sky.b, 1.0f);
        glClearDepth(1.0);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        if (atmosphere.enabled != 0) {
            r.drawSky();
        }
    }
    if (r.indexCount > 0) {
        glUseProgram(program);
        glBindVertexArray(r.vertexArray.id());
        // The values of disabled (absent) attributes are context state, not
        // the vertex array's: set them each draw. GL's default (0, 0, 0, 1)
        // would give the landform water 1.
        glVertexAttrib4f(2, 0.0f, 0.0f, 0.0f, 0.0f);
        glVertexAttrib4f(3, 0.0f, 0.0f, 0.0f, 0.0f);
        glVertexAttrib4f(4, 0.0f, 0.0f, 0.0f, 0.0f);
        glBindTextures(0, GLsizei(r.units.size()), r.units.data());
        glDrawElements(GL_TRIANGLES, r.indexCount, GL_UNSIGNED_INT, nullptr);
        if (options.wireframe) {
            frame.wireframePass = 1;
            glNamedBufferSubData(r.frameBuffer.id(), 0, sizeof(frame), &frame);
            glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
            glEnable(GL_POLYGON_OFFSET_LINE);
            glPolygonOffset(-1.0f, -1.0f);
            glDepthFunc(GL_LEQUAL);
            glDrawElements(GL_TRIANGLES, r.indexCount, GL_UNSIGNED_INT, nullptr);
        }
    }
    detail::checkGl("drawing the mesh");
}

void GlRenderer::drawFrame(const Camera& camera, const Lighting& lighting, int width, int height, int samples,
                           const DrawOptions& options)
{
    Impl& r = *mImpl;
    if (width < 1 || height < 1) {
        throw Error(ErrorKind::BadInput, "render: size " + std::to_string(width) + "x" + std::to_string(height) + " is empty");
    }
    r.context.makeCurrent();
    if (width > r.maxRenderbufferSize || height > r.maxRenderbufferSize) {
        throw Error(ErrorKind::BadInput, "snapshot: size " + std::to_string(width) + "x" + std::to_string(height) +
                    " exceeds this OpenGL's limit of " + std::to_string(r.maxRenderbufferSize));
    }
    samples = std::clamp(samples, 1, std::max(r.maxSamples, 1));
    detail::clearGlErrors();
    if (r.resolved.width != width || r.resolved.height != height || r.resolved.samples != samples) {
        r.haveFrame = false;
        r.multisampled = RenderTarget();
        r.resolved = createRenderTarget(width, height, 1, samples == 1);
        r.resolved.samples = samples; // the key: which multisampled target it resolves
        if (samples > 1) {
            r.multisampled = createRenderTarget(width, height, samples, true);
        }
    }
    const GLuint target = samples > 1 ? r.multisampled.framebuffer.id() : r.resolved.framebuffer.id();
    draw(camera, lighting, target, width, height, options);
    if (samples > 1) {
        glBlitNamedFramebuffer(r.multisampled.framebuffer.id(), r.resolved.framebuffer.id(), 0, 0, width, height, 0, 0,
                               width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        detail::checkGl("resolving the multisampled framebuffer");
    }
    r.haveFrame = true;
}

void GlRenderer::blitFrame(unsigned framebuffer, int width, int height)
{
    Impl& r = *mImpl;
    if (!r.haveFrame || width < 1 || height < 1) {
        return;
    }
    r.context.makeCurrent();
    detail::clearGlErrors();
    glDisable(GL_FRAMEBUFFER_SRGB);
    const bool same = width == r.resolved.width && height == r.resolved.height;
    glBlitNamedFramebuffer(r.resolved.framebuffer.id(), framebuffer, 0, 0, r.resolved.width, r.resolved.height, 0, 0,
                           width, height, GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
    detail::checkGl("copying the frame to the window");
}

Image GlRenderer::readFrame()
{
    Impl& r = *mImpl;
    if (!r.haveFrame) {
        throw Error(ErrorKind::BadInput, "render: no frame to read (call GlRenderer::drawFrame first)");
    }
    r.context.makeCurrent();
    detail::clearGlErrors();
    StateGuard guard;
    const int width = r.resolved.width;
    const int height = r.resolved.height;
    Image image;
    image.width = width;
    image.height = height;
    image.pixels.resize(std::size_t(width) * std::size_t(height) * 4);
    std::vector<std::uint8_t> rows(image.pixels.size());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r.resolved.framebuffer.id());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    detail::checkGl("reading the image back");
    // GL rows run bottom to top: flip.
    const std::size_t rowBytes = std::size_t(width) * 4;
    for (int y = 0; y < height; ++y) {
        std::memcpy(image.pixels.data() + std::size_t(y) * rowBytes,
                    rows.data() + std::size_t(height - 1 - y) * rowBytes, rowBytes);
    }
    return image;
}

Image GlRenderer::renderImage(const SnapshotOptions& options)
{
    checkSnapshotOptions(options);
    setMaterial(options.material, options.anisotropy, options.filtering);
    DrawOptions draw;
    draw.debugView = options.debugView;
    draw.featureMask = options.featureMask;
    draw.shadows = options.shadows;
    drawFrame(options.camera, options.lighting, options.width, options.height, options.samples, draw);
    return readFrame();
}

Image renderSnapshot(GlContext& context, const MeshView& mesh, const SnapshotOptions& options)
{
    checkSnapshotOptions(options);
    GlRenderer renderer(context);
    renderer.setMesh(mesh);
    return renderer.renderImage(options);
}

} // namespace strata::render
