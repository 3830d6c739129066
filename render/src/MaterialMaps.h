// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

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

/// How one slot's layers fit one texture array: each layer's own map (null:
/// the stand-in), the array's size and level count, and the level of each
/// map that has that size. levels = 0: no layer has a map of this slot.
struct SlotPlan
{
    std::vector<TexturePtr> textures;
    std::vector<std::size_t> first;
    int width = 0;
    int height = 0;
    std::size_t levels = 0;
};

/// The plans of the nine slots, without building anything (checkMaterial()
/// runs it). Throws strata::Error "material: layer 'NAME' map KEY is WxH:
/// ..." when the maps of a slot cannot share one size, or differ in colour
/// space.
std::array<SlotPlan, 9> planLayerSlots(const Material& material);

/// The slots' textures as planLayerSlots() plans them (copies of the levels
/// only where a map starts below its top level). Throws as planLayerSlots().
LayerMaps resolveLayerMaps(const Material& material);

} // namespace strata::render::detail
