#pragma once
/// \file
/// Deterministic, tileable procedural textures, so Strata never needs asset
/// files. Output is sRGB-encoded RGBA8 albedo; the same seed gives the same
/// bytes everywhere.

#include <strata/render/Image.h>

#include <cstdint>

namespace strata::render {

/// Grey-brown layered rock with cracks. `size` is a power of two >= 16.
/// The layers run along the rows, so on the triplanar side projections
/// (texture up = world up) they lie horizontal. Seamlessly tileable.
/// Throws strata::Error unless size is a power of two in 16..16384.
/// O(size²), single-threaded: about 0.45 s for 1024² here.
Image makeRockAlbedo(int size, std::uint32_t seed);

/// Green grass with darker clumps and dry patches, for top projections.
/// Seamlessly tileable; same size rule, errors and cost as makeRockAlbedo.
Image makeGrassAlbedo(int size, std::uint32_t seed);

} // namespace strata::render
