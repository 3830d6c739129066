// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Deterministic, tileable procedural textures, so Strata never needs asset
/// files. Output is sRGB-encoded RGBA8 albedo; the same seed gives the same
/// bytes everywhere.

#include <strata/render/Image.h>

#include <cstdint>
#include <optional>
#include <string>

namespace strata::render {

/// Grey-brown layered rock with cracks. `size` is a power of two >= 16.
/// The layers run along the rows, so on the triplanar side projections
/// (texture up = world up) they lie horizontal. Seamlessly tileable.
/// Throws strata::Error unless size is a power of two in 16..16384.
/// O(size²), rows in parallel (TBB; the bytes do not depend on the thread
/// count): about 0.45 s for 1024² on one core here.
Image makeRockAlbedo(int size, std::uint32_t seed);

/// Green grass with darker clumps and dry patches, for top projections.
/// Seamlessly tileable; same size rule, errors and cost as makeRockAlbedo.
Image makeGrassAlbedo(int size, std::uint32_t seed);

/// The built-in texture sets: every map of a material, so no asset is
/// ever required.
enum class BuiltinSet
{
    Rock,
    Grass,
    Soil,
    Sand,
    Snow,
    Circuitry,
};

/// "rock", "grass", "soil", "sand", "snow", "circuitry".
const char* builtinSetName(BuiltinSet set);

/// The set named `name` (as builtinSetName spells it), or none.
std::optional<BuiltinSet> builtinSetFromName(const std::string& name);

/// The maps of one set, as images (rows top to bottom).
struct TextureSetImages
{
    Image albedo;   ///< sRGB
    Image mohs;     ///< linear: metallic, occlusion, height, smoothness
    Image normal;   ///< linear, OpenGL (+Y) convention, derived from the height
    Image detail;   ///< linear: R albedo and B smoothness modulation, 0.5 neutral
    Image emission; ///< sRGB; black except for the circuitry's lights
};

/// Builds every map of `set` at `size`² (a power of two in 16..16384),
/// deterministically from `seed`, seamlessly tileable. Throws strata::Error
/// for a bad size. O(size²), rows in parallel with TBB.
TextureSetImages makeBuiltinSet(BuiltinSet set, int size, std::uint32_t seed);

} // namespace strata::render
