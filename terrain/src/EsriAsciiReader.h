// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// ESRI ASCII grids (.asc) as DEMs (ElevationFile.h).

#include <strata/terrain/ElevationFile.h>

#include <string>
#include <string_view>

namespace strata::terrain::detail {

/// The header (keys in any order and case) and nrows x ncols numbers, the
/// northernmost row first, as an ElevationGrid (format "asc", with its cell
/// size and lower-left corner); NODATA_value and non-finite values become
/// NaN. Throws naming `name` and the line when malformed.
ElevationGrid parseEsriAscii(std::string_view text, const std::string& name);

} // namespace strata::terrain::detail
