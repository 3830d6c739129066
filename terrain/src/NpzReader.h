// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
// NumPy .npz archives (zip, stored or deflated, zip64 included) as DEMs
// (ElevationFile.h).

#include <strata/terrain/ElevationFile.h>

#include <string>
#include <string_view>

namespace strata::terrain::detail {

/// The member named `elevation.npy`, else the only member holding a 2D
/// array, as an ElevationGrid (format "npz", `member` its name). Throws
/// naming `name` when the archive or the member is malformed.
ElevationGrid parseNpz(std::string_view bytes, const std::string& name);

} // namespace strata::terrain::detail
