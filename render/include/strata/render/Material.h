#pragma once
/// \file
/// The triplanar material and the lighting of a snapshot.

#include <strata/render/Image.h>

#include <glm/vec3.hpp>

namespace strata::render {

/// Albedo-only triplanar material. Textures repeat every 1/mapScale metres
/// in each of the three world-space projections (YZ, XZ, XY).
struct TriplanarMaterial
{
    float mapScale = 0.125f;     ///< texture repeats per metre, > 0
    float blendOffset = 0.25f;   ///< subtracted from |n| before weighting, 0..0.5
    float blendExponent = 4.0f;  ///< sharpness of the projection blend, 1..8
    Image sideAlbedo;            ///< sRGB; used by all projections (empty: plain light grey)
    Image topAlbedo;             ///< sRGB; optional, replaces the Y projection where n.y > 0
};

struct Lighting
{
    glm::vec3 sunDirection{0.45f, 0.8f, 0.35f}; ///< towards the sun, normalised by the renderer
    glm::vec3 sunColor{2.6f, 2.45f, 2.2f};      ///< linear radiance
    glm::vec3 skyAmbient{0.38f, 0.45f, 0.6f};   ///< linear, from above
    glm::vec3 groundAmbient{0.16f, 0.14f, 0.12f}; ///< linear, from below
    glm::vec3 skyColor{0.55f, 0.7f, 0.9f};      ///< background, linear
};

} // namespace strata::render
