// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// 8-bit RGBA images and their files, read and written through OpenImageIO.

#include <cstdint>
#include <filesystem>
#include <vector>

namespace strata::render {

/// RGBA, 8 bits per channel, rows top to bottom, no padding.
/// Colour data is sRGB-encoded unless the owner says otherwise.
struct Image
{
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels; ///< width·height·4 bytes

    std::uint8_t* at(int x, int y) { return pixels.data() + (std::size_t(y) * width + x) * 4; }
    const std::uint8_t* at(int x, int y) const { return pixels.data() + (std::size_t(y) * width + x) * 4; }
};

/// Writes PNG, TGA, TIFF, JPEG or EXR (from the extension) through
/// OpenImageIO; EXR holds 32-bit float linear RGBA (the sRGB bytes decoded). Written to a temporary file beside `path` and renamed, so a
/// failure leaves no partial file. Throws strata::Error naming the path.
void writeImage(const Image& image, const std::filesystem::path& path);

/// Reads any format OpenImageIO knows into RGBA8 (alpha kept unassociated,
/// missing channels filled: grey → RGB, no alpha → 255).
/// Throws strata::Error naming the path.
Image readImage(const std::filesystem::path& path);

/// Peak signal-to-noise ratio between `a` and `b` over the R, G and B
/// channels, in dB: 10·log10(255² / MSE); +infinity for identical images.
/// Throws strata::Error when the sizes differ. O(pixels).
double psnr(const Image& a, const Image& b);

/// Fraction (0..1) of the pixels whose R, G and B each differ by at most
/// `tolerance` (in 8-bit steps) between `a` and `b`; 1 for empty images.
/// Throws strata::Error when the sizes differ. O(pixels).
double fractionWithin(const Image& a, const Image& b, int tolerance);

} // namespace strata::render
