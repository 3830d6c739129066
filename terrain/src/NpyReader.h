// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// NumPy .npy arrays as DEMs (ElevationFile.h): the header, its checked
// layout and the whole array.

#include <strata/terrain/ElevationFile.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strata::terrain::detail {

struct NpyHeader
{
    std::string descr;
    bool fortranOrder = false;
    std::vector<std::uint64_t> shape;
    std::size_t dataOffset = 0; ///< where the array's bytes start
};

constexpr std::string_view NPY_MAGIC("\x93NUMPY", 6);

/// The header of the .npy in `bytes` (which need only hold the header):
/// magic, version 1 to 3, the dict. Throws naming `name` when malformed.
NpyHeader parseNpyHeader(std::string_view bytes, const std::string& name);

/// What a .npy header says of its array, checked: a supported type, two
/// dimensions, at most MAX_DEM_CELLS cells. `prefix` needs only hold the header.
struct NpyLayout
{
    NpyHeader header;
    std::uint64_t rows = 0, columns = 0, cells = 0;
    int itemSize = 0;
    bool isFloat = false;

    /// The bytes a whole .npy of this layout has.
    std::uint64_t fileSize() const { return header.dataOffset + cells * std::uint64_t(itemSize); }
};

NpyLayout npyLayout(std::string_view prefix, const std::string& name);

/// Refuses a .npy of `size` bytes whose data is not exactly the layout's.
void checkNpySize(const NpyLayout& layout, std::uint64_t size, const std::string& name);

/// A whole .npy file as an ElevationGrid (format "npy"); non-finite values
/// become NaN no-data cells.
ElevationGrid parseNpy(std::string_view bytes, const std::string& name);

} // namespace strata::terrain::detail
