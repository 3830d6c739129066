// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Images that hold data, not colour (heightmaps, weight maps, masks):
/// 1 to 4 channels of 8-bit, 16-bit or 32-bit float samples, written and
/// read without any colour transform.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace strata::render {

enum class SampleType
{
    UInt8,
    UInt16,
    Float32,
};

/// Rows top to bottom, channels interleaved, samples in the machine's byte
/// order, no padding.
struct DataImage
{
    int width = 0;
    int height = 0;
    int channels = 1;
    SampleType type = SampleType::UInt8;
    std::vector<std::uint8_t> bytes; ///< width·height·channels samples

    std::size_t sampleBytes() const { return type == SampleType::UInt8 ? 1 : type == SampleType::UInt16 ? 2 : 4; }
};

/// Writes PNG (8 or 16 bits), EXR (32-bit float; 16-bit and 8-bit samples
/// as their values) or TIFF (from the extension) through OpenImageIO, with
/// the samples as they are (colour space "Linear", no gamma). Written to a
/// temporary file beside `path` and renamed. Throws strata::Error (Io)
/// naming the path, or (BadInput) for an image whose sizes and bytes
/// disagree or a format that cannot hold its sample type.
void writeDataImage(const DataImage& image, const std::filesystem::path& path);

/// Reads an image's samples in the file's own type (8 and 16-bit integers,
/// anything else as 32-bit float), no colour transform. Throws
/// strata::Error (BadInput) naming the path.
DataImage readDataImage(const std::filesystem::path& path);

} // namespace strata::render
