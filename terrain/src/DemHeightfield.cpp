// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/DemHeightfield.h>

#include "NodeRegistrations.h"

#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/terrain/NodeRegistry.h>

#include <cmath>
#include <string>

namespace strata::terrain {

glm::dvec2 ElevationRaster::centre() const
{
    return firstCellCentre + 0.5 * glm::dvec2(heights.width - 1, heights.height - 1) * cellStep;
}

namespace {

void requireFinite(double value, const char* key)
{
    if (!std::isfinite(value)) throw Error(ErrorKind::BadInput, std::string(key) + " = " + formatNumber(value) + " must be finite", {"", 0, key, ""});
}

/// The raster laid into the scene's frame: cell centres from x = min.x (west)
/// to max.x (east) and z = min.y (north, −z) to max.y (south).
ImageHeightfieldOptions surfaceOptions(const ElevationRaster& raster, const DemHeightfieldOptions& options,
                                       glm::dvec2 origin)
{
    const glm::dvec2 last = raster.firstCellCentre +
                            glm::dvec2(raster.heights.width - 1, raster.heights.height - 1) * raster.cellStep;
    ImageHeightfieldOptions o;
    o.min = {(raster.firstCellCentre.x - origin.x) * raster.metresPerUnit.x,
             -(raster.firstCellCentre.y - origin.y) * raster.metresPerUnit.y};
    o.max = {(last.x - origin.x) * raster.metresPerUnit.x, -(last.y - origin.y) * raster.metresPerUnit.y};
    o.base = options.base;
    o.heightScale = options.heightScale;
    return o;
}

} // namespace

DemHeightfield::DemHeightfield(const ElevationRaster& raster, const DemHeightfieldOptions& options)
    : mSurface(raster.heights, surfaceOptions(raster, options, options.origin.value_or(raster.centre())))
{
    const glm::dvec2 origin = options.origin.value_or(raster.centre());
    requireFinite(origin.x, "origin");
    requireFinite(origin.y, "origin");
    requireFinite(options.base, "base");
    requireFinite(options.heightScale, "height_scale");
    if (options.heightScale == 0.0) {
        throw Error(ErrorKind::BadInput, "height_scale = 0 flattens the DEM: give a non-zero scale", {"", 0, "height_scale", ""});
    }
    const ImageHeightfieldOptions o = surfaceOptions(raster, options, origin);
    mMin = o.min;
    mMax = o.max;
    setSlopeBound(mSurface.slopeBound());
    if (raster.toLatitudeLongitude) mOriginLatLon = raster.toLatitudeLongitude(origin);
    mOriginHeight = -options.base / options.heightScale;
}

void registerDemNodes(NodeRegistry& registry)
{
    const DemHeightfieldOptions d;
    NodeType dem{"dem_heightfield",
                 "a digital elevation model (GeoTIFF or any raster GDAL reads) in metres, laid east (+x) and north (-z) "
                 "around origin; a CRS gives the scene its place on the Earth (bake --georeference)",
                 {},
                 {}};
    dem.keys = {elevationKey("file", "the DEM; relative paths from the scene's folder"),
                vec2Key("origin", glm::dvec2(0.0), HUGE_LENGTH, "CRS units",
                        "the DEM point (easting, northing or longitude, latitude) at the scene's origin; default: "
                        "the raster's centre"),
                numberKey("base", d.base, -HUGE_LENGTH, HUGE_LENGTH, "m", "scene height of the DEM's zero"),
                numberKey("height_scale", d.heightScale, -1e3, 1e3, "", "vertical exaggeration (1: true heights)")};
    dem.build = [](const NodeArgs& a) -> DensityFieldPtr {
        DemHeightfieldOptions o;
        if (a.given("origin")) o.origin = a.vec2("origin");
        o.base = a.number("base");
        o.heightScale = a.number("height_scale");
        if (o.heightScale == 0.0) a.fail("height_scale", "= 0 flattens the DEM: give a non-zero scale");
        return std::make_shared<DemHeightfield>(a.elevation("file"), o);
    };
    registry.add(std::move(dem));
}

} // namespace strata::terrain
