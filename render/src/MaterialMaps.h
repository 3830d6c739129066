#pragma once
// Internal: the nine map slots of a material (MAP_* in TriplanarMaterial.h),
// with neutral stand-ins for absent maps and the side maps standing in for
// absent top maps, so both renderers bind/sample the same thing.

#include <strata/render/Material.h>

#include <array>

namespace strata::render::detail {

inline std::array<TexturePtr, 9> resolveMaps(const Material& m)
{
    static const TexturePtr GREY = makeConstantTexture(200, 200, 200, 255, MapKind::Albedo);
    static const TexturePtr WHITE_MASK = makeConstantTexture(255, 255, 255, 255, MapKind::Mask);
    static const TexturePtr FLAT = makeConstantTexture(128, 128, 255, 255, MapKind::Normal);
    static const TexturePtr NEUTRAL = makeConstantTexture(128, 128, 128, 255, MapKind::Detail);
    static const TexturePtr BLACK = makeConstantTexture(0, 0, 0, 255, MapKind::Emission);
    std::array<TexturePtr, 9> maps;
    maps[0] = m.albedo ? m.albedo : GREY;
    maps[1] = m.mask ? m.mask : WHITE_MASK;
    maps[2] = m.normal ? m.normal : FLAT;
    maps[3] = m.topAlbedo ? m.topAlbedo : maps[0];
    maps[4] = m.topMask ? m.topMask : maps[1];
    maps[5] = m.topNormal ? m.topNormal : maps[2];
    maps[6] = m.detail ? m.detail : NEUTRAL;
    maps[7] = m.detailNormal ? m.detailNormal : FLAT;
    maps[8] = m.emission ? m.emission : BLACK;
    return maps;
}

} // namespace strata::render::detail
