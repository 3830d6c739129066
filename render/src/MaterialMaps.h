#pragma once
// Internal: the nine map slots of a material (MAP_* in TriplanarMaterial.h),
// with neutral stand-ins for absent maps and the side maps standing in for
// absent top maps, so both renderers bind/sample the same thing; and, for
// every layer of a layered material, the same slots sized for texture
// arrays (one size per slot across the layers).

#include <strata/render/Material.h>

#include <array>
#include <vector>

namespace strata::render::detail {

/// One material's nine slots (its layers aside).
std::array<TexturePtr, 9> resolveMaps(const Material& m);

/// Slot k of layer i is slots[k][i]; layer 0 is the base. Within a slot
/// every texture has the same size and level count, as the layers of a GL
/// texture array must: the slot takes its smallest present map's size; a
/// larger map is used from the mip level of that size on (an error names
/// the layers and sizes when it has none); absent maps become constant
/// textures of that size.
struct LayerMaps
{
    int layerCount = 1;
    std::array<std::vector<TexturePtr>, 9> slots;
};

/// Throws strata::Error "material: layer 'NAME' map KEY is WxH: ..." when
/// the maps of a slot cannot share one size, or differ in colour space.
LayerMaps resolveLayerMaps(const Material& material);

} // namespace strata::render::detail
