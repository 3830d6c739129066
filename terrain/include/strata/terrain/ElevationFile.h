// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Digital elevation models read from files, to measure real land with the
/// same tools as generated terrain (LandformStatistics.h). Three formats,
/// recognised by their content (not by the file name):
///  - NumPy .npy (versions 1 to 3): a 2D array of little-endian int16,
///    int32, float32 or float64 ('<i2', '<i4', '<f4', '<f8'), C or Fortran
///    order;
///  - NumPy .npz, a zip of .npy members, stored (zip method 0, what
///    np.savez writes) or deflated (method 8: np.savez_compressed and the
///    matplotlib sample DEM; inflated with zlib), zip64 included: the member
///    named `elevation.npy`, else the only member holding a 2D array; its
///    CRC-32 is checked;
///  - ESRI ASCII grid (.asc): a header of `ncols`, `nrows`, `xllcorner` or
///    `xllcenter`, `yllcorner` or `yllcenter`, `cellsize` (or equal `dx` and
///    `dy`) and the optional `NODATA_value` (keys in any order and case), then
///    nrows × ncols numbers, the northernmost row first.
///
/// Readers never trust the bytes: every header field and size is checked
/// before use (sizes multiply without overflow and must fit the file), and
/// any malformed input gives strata::Error (ErrorKind::BadInput) naming the
/// file (and the line, for .asc) and what is wrong.

#include <glm/vec2.hpp>

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace strata::terrain {

/// A height grid read from a file, in the layout of LandformStatistics.h.
struct ElevationGrid
{
    std::string format; ///< "npy", "npz" or "asc"
    std::string member; ///< the .npz member read ("elevation.npy"); empty for the other formats
    int width = 0;      ///< columns, >= 1
    int height = 0;     ///< rows, >= 1, in file order (for .asc the first is the northernmost)
    /// width·height heights, row-major (heights[row·width + column]), in the
    /// file's units (metres for the DEMs Strata expects); NaN where the file
    /// has no data (.asc NODATA_value, non-finite floats).
    std::vector<double> heights;
    std::size_t noDataCells = 0; ///< how many heights are NaN
    /// Distance between neighbouring cells in the file's horizontal units
    /// (.asc cellsize, which is in degrees for a geographic grid); 0 when the
    /// file does not give one (.npy and .npz never do).
    double cellSize = 0.0;
    /// .asc: the outer lower-left corner of the grid (xllcorner, yllcorner,
    /// or the centre forms minus half a cell); (0, 0) otherwise.
    glm::dvec2 lowerLeft{0.0};
};

/// Reads a DEM file (format from its content, see the file comment). Throws
/// strata::Error (BadInput) naming the file when it cannot be opened or read,
/// or is malformed or unsupported.
ElevationGrid readElevationFile(const std::filesystem::path& path);

/// Parses the bytes of a DEM file; `name` is the file named in error
/// messages. What readElevationFile() does after reading the file (for
/// bytes from elsewhere, and fuzzing). Throws like it.
ElevationGrid parseElevationFile(std::string_view bytes, const std::string& name);

} // namespace strata::terrain
