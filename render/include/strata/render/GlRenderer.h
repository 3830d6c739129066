// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The OpenGL renderer: a persistent GlRenderer that keeps the mesh, the
/// material's textures and one compiled program per feature set on the GPU
/// between frames (the viewer, turntables, snapshot farms), and the
/// one-shot renderSnapshot() built on it.

#include <strata/render/Camera.h>
#include <strata/render/Image.h>
#include <strata/render/Material.h>
#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>

#include <glm/vec4.hpp>

#include <cstdint>
#include <memory>
#include <vector>

namespace strata::render {

class GlContext;

/// How one frame is drawn, beyond camera and lighting.
struct DrawOptions
{
    DebugView debugView = DebugView::Shaded;
    /// ANDed with the material's feature set; selects (and on first use
    /// compiles) the program variant effectiveFeatures(material, mask).
    std::uint32_t featureMask = feature::ALL;
    /// Draws the triangle edges over the surface (glPolygonMode GL_LINE,
    /// polygon offset towards the camera), in `wireColor` (linear RGBA).
    bool wireframe = false;
    glm::vec4 wireColor{0.02f, 0.02f, 0.02f, 1.0f};
    /// Clears colour (to Lighting::skyColor, then the atmosphere's sky pass when it is on) and depth first; false draws
    /// over what the framebuffer holds.
    bool clear = true;
    /// Sun shadows (shaders/Shadow.h): a depth pass from the sun into a
    /// shadow map fitted to the mesh's bounds, before the main pass. The map
    /// is kept between draws and re-created when the resolution changes.
    ShadowOptions shadows;
};

/// Program-cache counters.
struct ProgramStats
{
    int compiled = 0;                       ///< variants compiled so far (each once)
    int possible = 0;                       ///< distinct feature sets (allFeatureSets().size())
    double compileSeconds = 0.0;            ///< wall time spent compiling and linking them
    std::vector<std::uint32_t> featureSets; ///< the compiled sets, in order of first use
};

/// A renderer bound to one GL context. Construct it, setMesh(),
/// setMaterial(), then draw frames; every upload happens once:
///  - the mesh goes into one vertex buffer (positions, then normals) and an
///    index buffer;
///  - each texture of the material (and the neutral stand-ins of absent
///    maps) is uploaded once with its own mip chain (the texels the CPU
///    sampler filters), SRGB8_ALPHA8 for colour maps and RGBA8 for data,
///    trilinear (bilinear in the nearest mip level with
///    TextureFilter::Bilinear), REPEAT, and kept while a later setMaterial()
///    still uses the same Texture object;
///  - the terrain program is compiled per feature set on first use and
///    cached for the renderer's lifetime (see stats()).
///  - the sun's shadow map is kept while the mesh, the light and the
///    resolution stay the same.
/// Uniforms live in std140 uniform buffers (frame: binding 0, material: 1,
/// lighting: 2, shadow: 3); the maps use texture units 0..8, the shadow map
/// unit 9.
///
/// All methods make the context current on the calling thread first and
/// throw strata::Error on a GL error or a shader compile/link error (the
/// message names the shader file and line and quotes the line). GL state
/// they change is reset to GL's defaults before they return. Not thread
/// safe; the context must outlive the renderer.
class GlRenderer
{
public:
    /// Binds to `context` (made current) and creates the uniform buffers.
    /// Throws strata::Error on a GL error.
    explicit GlRenderer(GlContext& context);
    ~GlRenderer();
    GlRenderer(const GlRenderer&) = delete;
    GlRenderer& operator=(const GlRenderer&) = delete;

    /// Copies `mesh` to the GPU, replacing the previous one; `origin` is
    /// kept for the view matrix. Throws strata::Error for indices out of
    /// range (checked on the CPU, O(indexCount)) or more than 2³¹ indices.
    void setMesh(const MeshView& mesh);

    /// Uses `material`: uploads those of its textures not yet on the GPU
    /// and drops the ones it no longer uses; writes the material block.
    /// `anisotropy` (1..16, clamped to the driver's maximum) is the textures'
    /// maximum anisotropy. Throws strata::Error for an invalid material or a
    /// texture larger than GL_MAX_TEXTURE_SIZE. `filtering` is the maps'
    /// minification filter (GL_LINEAR_MIPMAP_LINEAR or _NEAREST).
    void setMaterial(const Material& material, float anisotropy = 1.0f,
                     TextureFilter filtering = TextureFilter::Trilinear);

    /// Draws the mesh into `framebuffer` (0 = the default framebuffer)
    /// over the viewport `width` × `height`: clears to lighting.skyColor,
    /// depth test, back faces culled, GL_FRAMEBUFFER_SRGB on (the shader
    /// writes linear values; give it an sRGB framebuffer). The framebuffer
    /// needs a depth buffer.
    void draw(const Camera& camera, const Lighting& lighting, unsigned framebuffer, int width, int height,
              const DrawOptions& options = {});

    /// Draws into the renderer's own off-screen target (SRGB8_ALPHA8 and
    /// 24-bit depth, `samples` MSAA samples clamped to GL_MAX_SAMPLES, then
    /// resolved), kept between frames of the same size and sample count.
    /// Read it with readFrame() or show it with blitFrame().
    void drawFrame(const Camera& camera, const Lighting& lighting, int width, int height, int samples,
                   const DrawOptions& options = {});

    /// Copies the last drawFrame() result's bytes unchanged into
    /// `framebuffer` (0 = default) at (0, 0), stretched to width × height:
    /// the sRGB-encoded bytes show correctly on a window's plain RGB
    /// framebuffer. No-op before the first drawFrame().
    void blitFrame(unsigned framebuffer, int width, int height);

    /// Reads the last drawFrame() result back: RGBA8, sRGB-encoded, rows top
    /// to bottom, alpha 255. Throws strata::Error before the first drawFrame().
    Image readFrame();

    /// setMaterial(options.material, options.anisotropy), drawFrame() with
    /// the snapshot's size, samples, camera, lighting, debug view and
    /// feature mask, then readFrame(). Throws strata::Error for invalid
    /// options (checkSnapshotOptions) or a size over GL's limit.
    Image renderImage(const SnapshotOptions& options);

    /// Waits until GL has finished every command issued so far (glFinish),
    /// e.g. to time frames.
    void finish();

    /// The feature set draw() compiles for the current material with `mask`.
    std::uint32_t activeFeatures(std::uint32_t mask = feature::ALL) const;

    /// Compiles (if not yet) the program of `features` (normalised first)
    /// without drawing, e.g. to warm the cache at start-up.
    void prepareProgram(std::uint32_t features);

    /// Program-cache counters.
    ProgramStats stats() const;

    /// The context this renderer draws with.
    GlContext& context() const;

private:
    struct Impl;
    std::unique_ptr<Impl> mImpl;
};

/// Draws `mesh` into an off-screen framebuffer of `context` and reads it
/// back: RGBA8, sRGB-encoded, rows top to bottom, background
/// lighting.skyColor, alpha 255. A thin wrapper: a GlRenderer for this one
/// call (program compiled, textures and mesh uploaded each time, tens of
/// milliseconds on Mesa llvmpipe); keep a GlRenderer for many frames.
/// Throws strata::Error for invalid options or mesh indices out of range,
/// a shader compile/link error (with the GLSL log, file, line and source
/// line) or a GL error.
Image renderSnapshot(GlContext& context, const MeshView& mesh, const SnapshotOptions& options);

} // namespace strata::render
