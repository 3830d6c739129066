// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Small DEM files for the tests, written through GDAL's GTiff driver.

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <array>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace strata::test {

struct DemSpec
{
    int width = 11;
    int height = 9;
    GDALDataType type = GDT_Float32;
    /// GDAL's geotransform: corner x, cell width, 0, corner y, 0, −cell height.
    std::optional<std::array<double, 6>> geoTransform = std::array<double, 6>{499850.0, 30.0, 0.0, 4000120.0, 0.0, -30.0};
    int epsg = 32617; ///< 0: no CRS
    std::optional<double> noData;
    std::string unit;          ///< GDALSetRasterUnitType; "" leaves it unset
    bool sparse = false;       ///< write no pixels (a huge raster stays small on disk)
    /// The value of cell (column, row).
    std::function<double(int, int)> value = [](int i, int j) { return 100.0 + 2.0 * i + 3.0 * j; };
};

/// Writes `spec` as a GeoTIFF at `path`; false when GDAL fails.
inline bool writeDem(const std::filesystem::path& path, const DemSpec& spec)
{
    GDALAllRegister();
    GDALDriverH driver = GDALGetDriverByName("GTiff");
    if (!driver) return false;
    char** options = nullptr;
    if (spec.sparse) options = CSLSetNameValue(options, "SPARSE_OK", "TRUE");
    GDALDatasetH ds = GDALCreate(driver, path.string().c_str(), spec.width, spec.height, 1, spec.type, options);
    CSLDestroy(options);
    if (!ds) return false;
    if (spec.geoTransform) {
        std::array<double, 6> gt = *spec.geoTransform;
        GDALSetGeoTransform(ds, gt.data());
    }
    if (spec.epsg) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(srs, spec.epsg);
        GDALSetSpatialRef(ds, srs);
        OSRRelease(srs);
    }
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (spec.noData) GDALSetRasterNoDataValue(band, *spec.noData);
    if (!spec.unit.empty()) GDALSetRasterUnitType(band, spec.unit.c_str());
    bool ok = true;
    if (!spec.sparse) {
        std::vector<double> values;
        for (int j = 0; j < spec.height; ++j)
            for (int i = 0; i < spec.width; ++i) values.push_back(spec.value(i, j));
        ok = GDALRasterIO(band, GF_Write, 0, 0, spec.width, spec.height, values.data(), spec.width, spec.height,
                          GDT_Float64, 0, 0) == CE_None;
    }
    GDALClose(ds);
    return ok;
}

} // namespace strata::test
