// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Reads a heightmap image (PNG, EXR, TIFF, ... through OpenImageIO) into a
/// terrain::HeightImage: channel 0 as float, 8- and 16-bit integers
/// normalised to [0, 1].

#include <strata/terrain/Heightfield.h>

#include <filesystem>

namespace strata::scene {

/// The largest heightmap, in pixels (16384 x 16384).
constexpr double MAX_HEIGHT_IMAGE_PIXELS = double(1 << 28);

/// Reads `path` as a 2D image of 2x2 to MAX_HEIGHT_IMAGE_PIXELS pixels.
/// The whole image is decoded here, so a truncated or corrupt file fails now.
/// Throws strata::Error (BadInput) whose message is the reason only, in one
/// line ("no such file", "cannot be read as an image: ...", "is 1x1 pixels:
/// ..."): the caller prefixes the scene key and the path. Library messages
/// (libpng's warnings) are captured, never printed.
terrain::HeightImage readHeightImageFile(const std::filesystem::path& path);

} // namespace strata::scene
