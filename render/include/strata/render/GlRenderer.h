#pragma once
/// \file
/// Renders a mesh with the triplanar material through OpenGL into an image.

#include <strata/render/Camera.h>
#include <strata/render/Image.h>
#include <strata/render/Material.h>
#include <strata/render/MeshView.h>

namespace strata::render {

class EglContext;

struct SnapshotOptions
{
    int width = 1280;   ///< pixels, 1..16384
    int height = 720;   ///< pixels, 1..16384
    int samples = 4;    ///< MSAA samples (1 = off)
    Camera camera;
    Lighting lighting;
    TriplanarMaterial material;
};

/// Draws `mesh` into an off-screen framebuffer of the context (which must be
/// current) and reads it back: RGBA8, sRGB-encoded, rows top to bottom.
/// Throws strata::Error on a shader compile/link error (with the GLSL log) or
/// a GL error.
Image renderSnapshot(EglContext& context, const MeshView& mesh, const SnapshotOptions& options);

} // namespace strata::render
