// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Reads a digital elevation model through GDAL (GeoTIFF and Cloud Optimized
/// GeoTIFF, ESRI ASCII and binary grids, ERDAS Imagine, SRTM .hgt, USGS DEM,
/// Surfer grids, GeoPackage rasters, netCDF) into a terrain::ElevationRaster:
/// band 1 in metres (its scale, offset and unit applied), north up, cells
/// without data filled, its CRS mapped to metres and to WGS84.
///
/// Only those local-file drivers are tried: no VRT (it may name other files
/// or network sources), no /vsi paths. A build without GDAL (the option
/// STRATA_WITH_GDAL=OFF, used by the determinism cross builds) refuses every
/// DEM with that reason.

#include <strata/terrain/DemHeightfield.h>

#include <filesystem>

namespace strata::scene {

/// The largest DEM, in cells (16384 × 16384, 1 GiB of heights).
constexpr double MAX_DEM_CELLS = double(1 << 28);

/// Reads `path`. Throws strata::Error (BadInput) whose message is the reason
/// only, in one line (the caller prefixes the scene key and the path): no
/// such file, not a raster GDAL reads, fewer than 2 × 2 or more than
/// MAX_DEM_CELLS cells, no geotransform (the cell size is unknown), a rotated
/// or sheared grid, a height unit that is not a length, no valid cell, a
/// non-finite height. GDAL's messages are captured, never printed.
terrain::ElevationRaster readDemFile(const std::filesystem::path& path);

} // namespace strata::scene
