#pragma once
/// \file
/// What a snapshot renders, shared by the GL and the CPU renderer.

#include <strata/render/Camera.h>
#include <strata/render/Material.h>

namespace strata::render {

struct SnapshotOptions
{
    int width = 1280; ///< pixels, 1..16384
    int height = 720; ///< pixels, 1..16384
    int samples = 4;  ///< GL: MSAA samples (1 = off); the CPU renderer takes one sample per pixel
    /// GL: maximum anisotropic filtering (1 = plain trilinear, up to 16;
    /// clamped to what the driver offers). Trilinear is what the CPU
    /// reference sampler does; anisotropy sharpens grazing views but costs
    /// about 6× the render time on Mesa llvmpipe (measured: 0.64 s → 4.4 s
    /// at 1280×720). Ignored by the CPU renderer.
    float anisotropy = 1.0f;
    Camera camera;
    Lighting lighting;
    Material material;
};

/// Throws strata::Error "snapshot: ..." for invalid options (size, samples,
/// material ranges, camera planes).
void checkSnapshotOptions(const SnapshotOptions& options);

} // namespace strata::render
