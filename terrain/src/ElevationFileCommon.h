// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// What the DEM readers (NpyReader, NpzReader, EsriAsciiReader) share: the
// size limits, the error they throw and bounds-checked little-endian fields.
// Defined in ElevationFile.cpp.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>

namespace strata::terrain::detail {

constexpr std::uint64_t MAX_DEM_DIMENSION = std::uint64_t(std::numeric_limits<int>::max());
/// The most cells a DEM may have: 2^28, a 16384 x 16384 grid, 2 GiB of
/// heights as doubles. Larger grids (or a few bytes claiming one) are
/// refused before anything is allocated for them.
constexpr std::uint64_t MAX_DEM_CELLS = std::uint64_t(1) << 28;

/// Throws strata::Error (BadInput) "name[:line]: what", placed at the file
/// (and the line when > 0).
[[noreturn]] void failDem(const std::string& name, const std::string& what, int line = 0);

/// rows * columns (each <= MAX_DEM_DIMENSION, so no overflow); throws when
/// more than MAX_DEM_CELLS.
std::uint64_t demGridCells(std::uint64_t rows, std::uint64_t columns, const std::string& name);

/// The `size`-byte little-endian field at `offset` (bounds-checked by the callers).
inline std::uint64_t readLittle(std::string_view bytes, std::size_t offset, int size)
{
    std::uint64_t value = 0;
    for (int i = size - 1; i >= 0; --i) value = (value << 8) | std::uint8_t(bytes[offset + std::size_t(i)]);
    return value;
}

/// True when [offset, offset + size) lies inside `bytes` (no overflow).
inline bool fitsIn(std::string_view bytes, std::uint64_t offset, std::uint64_t size)
{
    return offset <= bytes.size() && size <= bytes.size() - offset;
}

} // namespace strata::terrain::detail
