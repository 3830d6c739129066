#pragma once
/// \file
/// Deterministic, tileable procedural textures, so Strata never needs asset
/// files. Output is sRGB-encoded RGBA8 albedo; the same seed gives the same
/// bytes everywhere.

#include <strata/render/Image.h>

#include <cstdint>

namespace strata::render {

/// Grey-brown layered rock with cracks. `size` is a power of two >= 16.
Image makeRockAlbedo(int size, std::uint32_t seed);

/// Green grass with darker clumps and dry patches, for top projections.
Image makeGrassAlbedo(int size, std::uint32_t seed);

} // namespace strata::render
