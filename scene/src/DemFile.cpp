// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include "DemFile.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>
#include <system_error>
#include <vector>

#ifdef STRATA_WITH_GDAL
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <memory>
#include <mutex>
#endif

namespace strata::scene {

namespace {

[[noreturn]] void bad(const std::string& why)
{
    throw Error(ErrorKind::BadInput, why);
}

#ifdef STRATA_WITH_GDAL

/// Metres per unit of a height band's unit name (GDALGetRasterUnitType); an
/// empty unit is taken as metres, the convention of every DEM product.
double metresPerHeightUnit(std::string unit)
{
    std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters") return 1.0;
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
    if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft" || unit == "foot_us") return 1200.0 / 3937.0;
    bad("its height unit '" + unit + "' is not a length unit Strata knows (m, ft, US survey foot)");
}

/// Metres per degree of longitude (x) and latitude (y) at `latitude` on an
/// ellipsoid of semi-major axis `a` and first eccentricity squared `e2`
/// (prime-vertical and meridian radii of curvature).
glm::dvec2 metresPerDegree(double latitude, double a, double e2)
{
    double s = 0.0, c = 0.0;
    dmath::sinCosDegrees(latitude, s, c);
    const double w2 = 1.0 - e2 * s * s;
    const double w = std::sqrt(w2);
    const double radians = 3.14159265358979323846 / 180.0;
    const double primeVertical = a / w;
    const double meridian = a * (1.0 - e2) / (w2 * w);
    return {primeVertical * c * radians, meridian * radians};
}

/// The drivers tried: local raster files only (see DemFile.h).
const char* const DEM_DRIVERS[] = {"GTiff", "COG", "AAIGrid", "EHdr", "HFA", "SRTMHGT", "USGSDEM", "GSAG", "GSBG",
                                   "GS7BG", "GPKG", "netCDF", "XYZ", nullptr};

/// GDAL's messages for this thread while it lives, kept instead of printed.
class CapturedErrors
{
public:
    CapturedErrors()
    {
        CPLPushErrorHandlerEx(&CapturedErrors::handle, this);
    }
    ~CapturedErrors() { CPLPopErrorHandler(); }
    CapturedErrors(const CapturedErrors&) = delete;
    CapturedErrors& operator=(const CapturedErrors&) = delete;
    /// The first failure's message, or "" when GDAL reported none.
    const std::string& message() const { return mMessage; }

private:
    static void CPL_STDCALL handle(CPLErr level, CPLErrorNum, const char* text)
    {
        auto* self = static_cast<CapturedErrors*>(CPLGetErrorHandlerUserData());
        if (self && level >= CE_Failure && self->mMessage.empty() && text) self->mMessage = text;
    }
    std::string mMessage;
};

struct DatasetCloser
{
    void operator()(void* dataset) const { GDALClose(dataset); }
};
struct SrsReleaser
{
    void operator()(void* srs) const { OSRRelease(srs); }
};
struct TransformDestroyer
{
    void operator()(void* t) const { OCTDestroyCoordinateTransformation(t); }
};
using SrsPtr = std::unique_ptr<void, SrsReleaser>;

SrsPtr srsFromWkt(const std::string& wkt)
{
    SrsPtr srs(OSRNewSpatialReference(nullptr));
    char* text = const_cast<char*>(wkt.c_str());
    if (!srs || OSRImportFromWkt(srs.get(), &text) != OGRERR_NONE) return nullptr;
    // Geotransforms and our points are (x east, y north) whatever the CRS's axis order.
    OSRSetAxisMappingStrategy(srs.get(), OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

/// A CRS point → (latitude, longitude) on WGS84, or an empty function when
/// PROJ has no transformation from the CRS (a local engineering CRS).
std::function<glm::dvec2(const glm::dvec2&)> toWgs84(const std::string& wkt)
{
    SrsPtr source = srsFromWkt(wkt);
    SrsPtr target(OSRNewSpatialReference(nullptr));
    if (!source || !target || OSRImportFromEPSG(target.get(), 4326) != OGRERR_NONE) return {};
    OSRSetAxisMappingStrategy(target.get(), OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<void, TransformDestroyer> probe(OCTNewCoordinateTransformation(source.get(), target.get()));
    if (!probe) return {};
    // A transformation is not thread-safe: each call makes its own (this runs
    // once per node build).
    return [wkt](const glm::dvec2& point) -> glm::dvec2 {
        CapturedErrors errors;
        SrsPtr from = srsFromWkt(wkt);
        SrsPtr to(OSRNewSpatialReference(nullptr));
        OSRImportFromEPSG(to.get(), 4326);
        OSRSetAxisMappingStrategy(to.get(), OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<void, TransformDestroyer> t(OCTNewCoordinateTransformation(from.get(), to.get()));
        double x = point.x, y = point.y;
        if (!t || !OCTTransform(t.get(), 1, &x, &y, nullptr) || !std::isfinite(x) || !std::isfinite(y)) {
            bad("the point (" + formatNumber(point.x) + ", " + formatNumber(point.y) +
                ") of its CRS has no place on the Earth" + (errors.message().empty() ? "" : ": " + errors.message()));
        }
        return {y, x};
    };
}

void registerDrivers()
{
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

#endif

} // namespace

terrain::ElevationRaster readDemFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) bad("no such file");
    if (!std::filesystem::is_regular_file(path, ec)) bad("is not a file");
#ifndef STRATA_WITH_GDAL
    bad("this build of Strata has no GDAL (STRATA_WITH_GDAL=OFF): it cannot read DEMs");
#else
    registerDrivers();
    CapturedErrors errors;
    const std::string name = path.string();
    if (name.rfind("/vsi", 0) == 0) bad("GDAL's virtual file systems (/vsi...) are not read: give a local file");
    std::unique_ptr<void, DatasetCloser> dataset(
        GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, DEM_DRIVERS, nullptr, nullptr));
    if (!dataset) {
        bad("cannot be read as a DEM (GeoTIFF, ESRI grid, .hgt, ... through GDAL)" +
            (errors.message().empty() ? std::string() : ": " + errors.message()));
    }
    const int width = GDALGetRasterXSize(dataset.get());
    const int height = GDALGetRasterYSize(dataset.get());
    if (GDALGetRasterCount(dataset.get()) < 1) bad("has no raster band");
    if (width < 2 || height < 2 || double(width) * double(height) > MAX_DEM_CELLS) {
        bad("is " + std::to_string(width) + "x" + std::to_string(height) +
            " cells: DEMs need 2x2 to 16384x16384 (crop larger ones with gdal_translate -srcwin)");
    }
    double gt[6];
    if (GDALGetGeoTransform(dataset.get(), gt) != CE_None) {
        bad("has no geotransform, so its cell size is unknown: give it one (gdal_edit.py -a_ullr) or use "
            "image_heightfield");
    }
    for (double v : gt)
        if (!std::isfinite(v)) bad("has a geotransform that is not finite");
    if (gt[2] != 0.0 || gt[4] != 0.0) bad("is a rotated or sheared grid: make it north up first (gdalwarp)");
    if (gt[1] == 0.0 || gt[5] == 0.0) bad("has a cell size of 0 in its geotransform");

    GDALRasterBandH band = GDALGetRasterBand(dataset.get(), 1);
    int hasNoData = 0;
    const double noData = GDALGetRasterNoDataValue(band, &hasNoData);
    int hasScale = 0, hasOffset = 0;
    double scale = GDALGetRasterScale(band, &hasScale);
    double offset = GDALGetRasterOffset(band, &hasOffset);
    if (!hasScale) scale = 1.0;
    if (!hasOffset) offset = 0.0;
    if (!std::isfinite(scale) || !std::isfinite(offset) || scale == 0.0) {
        bad("has a band scale " + formatNumber(scale) + " or offset " + formatNumber(offset) + " that is not usable");
    }
    const char* unitText = GDALGetRasterUnitType(band);
    const double metres = metresPerHeightUnit(unitText ? unitText : "");

    // North up, west to east: flip what the geotransform runs the other way.
    const bool flipColumns = gt[1] < 0.0, flipRows = gt[5] > 0.0;
    terrain::ElevationRaster raster;
    raster.heights.width = width;
    raster.heights.height = height;
    raster.heights.values.resize(std::size_t(width) * std::size_t(height));
    std::vector<double> row(static_cast<std::size_t>(width));
    std::vector<std::size_t> missing;
    double lowest = HUGE_VAL;
    for (int j = 0; j < height; ++j) {
        if (GDALRasterIO(band, GF_Read, 0, j, width, 1, row.data(), width, 1, GDT_Float64, 0, 0) != CE_None) {
            bad("cannot be read at row " + std::to_string(j) + (errors.message().empty() ? "" : ": " + errors.message()));
        }
        const int outRow = flipRows ? height - 1 - j : j;
        for (int i = 0; i < width; ++i) {
            const double raw = row[std::size_t(i)];
            const std::size_t at = std::size_t(outRow) * std::size_t(width) + std::size_t(flipColumns ? width - 1 - i : i);
            if (std::isnan(raw) || (hasNoData && raw == noData)) {
                missing.push_back(at);
                continue;
            }
            const double h = (raw * scale + offset) * metres;
            if (!std::isfinite(h) || std::abs(h) > 1e7) {
                bad("has a height " + formatNumber(h) + " m at column " + std::to_string(i) + ", row " + std::to_string(j) +
                    " (not finite or beyond 10,000 km): set its nodata value");
            }
            raster.heights.values[at] = float(h);
            lowest = std::min(lowest, double(float(h)));
        }
    }
    if (missing.size() == raster.heights.values.size()) bad("has no cell with data");
    for (std::size_t at : missing) raster.heights.values[at] = float(lowest);
    raster.noDataCells = missing.size();

    // Cell centres (GDAL's geotransform gives the corner of cell (0, 0)).
    const double x0 = gt[0] + 0.5 * gt[1], y0 = gt[3] + 0.5 * gt[5];
    raster.firstCellCentre = {flipColumns ? x0 + (width - 1) * gt[1] : x0, flipRows ? y0 + (height - 1) * gt[5] : y0};
    raster.cellStep = {std::abs(gt[1]), -std::abs(gt[5])};

    const char* wkt = GDALGetProjectionRef(dataset.get());
    SrsPtr srs = (wkt && *wkt) ? srsFromWkt(wkt) : nullptr;
    if (srs) {
        const char* crsName = OSRGetName(srs.get());
        raster.crsName = crsName ? crsName : "";
        if (OSRIsGeographic(srs.get())) {
            raster.geographic = true;
            OGRErr err = OGRERR_NONE;
            const double a = OSRGetSemiMajor(srs.get(), &err);
            const double inverseFlattening = OSRGetInvFlattening(srs.get(), &err);
            const double f = inverseFlattening > 0.0 ? 1.0 / inverseFlattening : 0.0;
            const double degreesPerUnit = OSRGetAngularUnits(srs.get(), nullptr) * 180.0 / 3.14159265358979323846;
            const double centreLatitude = raster.centre().y * degreesPerUnit;
            if (!(a > 0.0) || !(std::abs(centreLatitude) < 89.0)) {
                bad("is a geographic grid centred at latitude " + formatNumber(centreLatitude) +
                    ": only grids within 89 degrees of the equator are laid out (reproject it with gdalwarp)");
            }
            raster.metresPerUnit = metresPerDegree(centreLatitude, a, f * (2.0 - f)) * degreesPerUnit;
        } else {
            const double linear = OSRGetLinearUnits(srs.get(), nullptr);
            if (!(linear > 0.0) || !std::isfinite(linear)) bad("has a CRS whose linear unit is not a length");
            raster.metresPerUnit = glm::dvec2(linear);
        }
        raster.toLatitudeLongitude = toWgs84(wkt);
    }
    return raster;
#endif
}

} // namespace strata::scene
