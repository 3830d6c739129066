#pragma once
/// \file
/// Renders a mesh with the triplanar material through OpenGL into an image.

#include <strata/render/Camera.h>
#include <strata/render/Image.h>
#include <strata/render/Material.h>
#include <strata/render/MeshView.h>
#include <strata/render/SnapshotOptions.h>

namespace strata::render {

class EglContext;

/// Draws `mesh` into an off-screen framebuffer of the context (which must be
/// current) and reads it back: RGBA8, sRGB-encoded, rows top to bottom.
/// Throws strata::Error on a shader compile/link error (with the GLSL log) or
/// a GL error.
///
/// Details:
///  - the context is made current on the calling thread if it is not;
///  - `samples` is clamped to GL_MAX_SAMPLES; the multisampled image is
///    resolved with glBlitFramebuffer;
///  - back faces are culled (front faces are counter-clockwise);
///  - the fragment program is the shared material (shaders/TriplanarMaterial.h)
///    compiled for the material's feature set (materialFeatures()); absent
///    maps are neutral (no albedo: plain light grey); each Texture's own mip
///    chain is uploaded (the texels the CPU sampler filters), sampled with
///    textureGrad and explicit UV derivatives; texture images have their
///    top row at v = 1 (texture "up" is +V,
///    which the triplanar side projections map to world +Y);
///  - the background is lighting.skyColor; alpha is 255 everywhere;
///  - also throws strata::Error for invalid options (size, samples, material
///    ranges, camera planes), invalid texture images, and mesh indices out
///    of range (checked on the CPU, O(indexCount));
///  - the program is compiled and the textures uploaded on every call: on
///    Mesa llvmpipe this costs tens of milliseconds, small beside drawing.
Image renderSnapshot(EglContext& context, const MeshView& mesh, const SnapshotOptions& options);

} // namespace strata::render
