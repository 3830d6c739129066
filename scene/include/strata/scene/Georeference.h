// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Where a baked world lies on the Earth: a point on the WGS84 ellipsoid and
/// the 3D Tiles root transform that puts the tileset's local frame there
/// (`strata bake --georeference LAT,LON,HEIGHT`).
///
/// The tileset's frame is z-up: x = the scene's x, y = −(the scene's z),
/// z = the scene's y (glTF's y-up content turned by the client, see
/// Tileset.cpp). The transform makes that frame east-north-up at the point,
/// so the scene's origin lands at (latitude, longitude, height), its +x
/// points east, its −z north and its +y up.

#include <array>
#include <string>

namespace strata::scene {

struct Georeference
{
    double latitude = 0.0;  ///< degrees north, [−90, 90]
    double longitude = 0.0; ///< degrees east, [−180, 180]
    double height = 0.0;    ///< metres above the WGS84 ellipsoid, [−100 km, 10,000 km]

    bool operator==(const Georeference&) const = default;
};

/// Parses "LAT,LON,HEIGHT" (three decimal numbers, commas, no spaces
/// needed) and checks it (checkGeoreference()). Throws strata::Error
/// (BadInput) naming `flag` and the text: a missing or extra part, a part
/// that is not a number, a value that is not finite or out of range.
Georeference parseGeoreference(const std::string& text, const std::string& flag = "--georeference");

/// Throws strata::Error (BadInput) naming `what` when a value is not finite
/// or out of its range (see Georeference).
void checkGeoreference(const Georeference& point, const std::string& what);

/// The point in Earth-centred, Earth-fixed coordinates (WGS84, metres).
std::array<double, 3> ecefPosition(const Georeference& point);

/// The 3D Tiles `transform` of the tileset's root: east, north and up unit
/// vectors at the point and the point itself, in ECEF metres, as a 4 × 4
/// column-major matrix (columns east, north, up, position). O(1).
std::array<double, 16> eastNorthUpToEcef(const Georeference& point);

} // namespace strata::scene
