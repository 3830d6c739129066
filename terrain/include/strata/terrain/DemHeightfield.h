// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Real land as a height source: a digital elevation model (a GeoTIFF or any
/// raster GDAL reads; the scene library reads it, this library does not
/// depend on GDAL) laid into the scene's frame, so that erosion, beds, caves
/// and landform masks can amplify real terrain.
///
/// The scene's frame is the georeference's east-north-up one (Georeference.h
/// in the scene library): +x east, −z north, +y up, metres. A projected DEM
/// keeps its grid (its linear unit converted to metres); a geographic one
/// (degrees) is laid out by a local equirectangular mapping at the raster's
/// centre latitude on the WGS84 ellipsoid (metres per degree from the
/// meridian and prime-vertical radii there), exact at the centre and within
/// about 0.1 % over 100 km: reproject larger areas first (gdalwarp).

#include <strata/terrain/Heightfield.h>

#include <glm/vec2.hpp>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace strata::terrain {

/// A DEM in metres, north up (rows from north to south, columns from west
/// to east), in its own coordinate reference system (CRS).
struct ElevationRaster
{
    /// width × height heights in metres above the DEM's vertical datum
    /// (its unit and scale/offset applied), row 0 the northernmost; cells
    /// without data hold the lowest valid height (see noDataCells).
    HeightImage heights;
    /// The CRS coordinates (x east, y north: easting/northing, or longitude/
    /// latitude in degrees) of the centre of cell (0, 0), the north-west one.
    glm::dvec2 firstCellCentre{0.0};
    /// CRS units from one cell centre to the next: east along a row (> 0) and
    /// north along a column (< 0: rows go south).
    glm::dvec2 cellStep{1.0, -1.0};
    /// Metres per CRS unit along x and y (1 for metres, 0.3048 for feet; for
    /// degrees, the local equirectangular scale at the centre latitude).
    glm::dvec2 metresPerUnit{1.0};
    std::string crsName;           ///< "WGS 84 / UTM zone 17N"; empty without a CRS
    bool geographic = false;       ///< the CRS is in degrees of longitude and latitude
    std::size_t noDataCells = 0;   ///< cells the file marks as having no data
    /// A CRS point → (latitude, longitude) in degrees on WGS84; empty when
    /// the file has no CRS (the DEM then has no place on the Earth).
    std::function<glm::dvec2(const glm::dvec2&)> toLatitudeLongitude;

    /// The CRS coordinates of the raster's centre (between its middle cells).
    glm::dvec2 centre() const;
};

struct DemHeightfieldOptions
{
    /// The CRS point laid at the scene's origin (x = z = 0); the raster's
    /// centre when not given.
    std::optional<glm::dvec2> origin;
    double base = 0.0;        ///< metres added to every height (scene y of the datum's zero)
    double heightScale = 1.0; ///< vertical exaggeration (1: true heights)
};

/// h(x, z) = base + heightScale · dem(x, z), bilinear between cell centres
/// and clamped at the raster's edges (as ImageHeightfield, which does the
/// work).
class DemHeightfield final : public HeightfieldBase
{
public:
    /// Throws strata::Error (BadInput) naming the key: a non-finite origin,
    /// base or height scale, a raster smaller than 2 × 2.
    DemHeightfield(const ElevationRaster& raster, const DemHeightfieldOptions& options);
    double height(double x, double z) const override { return mSurface.height(x, z); }
    void heights(const double* x, const double* z, std::size_t n, double* out) const override
    {
        mSurface.heights(x, z, n, out);
    }
    Interval heightBounds(const glm::dvec2& min, const glm::dvec2& max) const override
    {
        return mSurface.heightBounds(min, max);
    }

    /// Where the scene's origin lies on the Earth: (latitude, longitude) in
    /// degrees; empty when the file has no CRS.
    const std::optional<glm::dvec2>& originLatitudeLongitude() const { return mOriginLatLon; }
    /// The height above the DEM's datum at the scene's y = 0, metres
    /// (−base / heightScale).
    double originHeight() const { return mOriginHeight; }
    /// The world rectangle the raster's cell centres cover, (x, z) metres.
    glm::dvec2 minCorner() const { return mMin; }
    glm::dvec2 maxCorner() const { return mMax; }

private:
    ImageHeightfield mSurface;
    std::optional<glm::dvec2> mOriginLatLon;
    double mOriginHeight = 0.0;
    glm::dvec2 mMin{0.0}, mMax{0.0};
};

} // namespace strata::terrain
