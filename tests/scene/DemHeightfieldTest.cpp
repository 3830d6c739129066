// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// The dem_heightfield node (issue 38, real land in): GeoTIFFs written here
// through GDAL are laid into the scene's frame (east +x, north −z, metres),
// their heights converted to metres, cells without data filled; a DEM with
// a CRS places the scene on the Earth, which the bake's tileset takes; bad
// files are refused naming the key and the file.

#include "DemTestFiles.h"
#include "TestDir.h"

#include <strata/Error.h>
#include <strata/scene/Bake.h>
#include <strata/scene/Scene.h>
#include <strata/terrain/DemHeightfield.h>
#include <strata/terrain/ElevationFile.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

using strata::scene::Scene;
using strata::terrain::DemHeightfield;
namespace fs = std::filesystem;

namespace {

const double PI = 3.14159265358979323846;
const double WGS84_A = 6378137.0;
const double WGS84_F = 1.0 / 298.257223563;
const double WGS84_E2 = WGS84_F * (2.0 - WGS84_F);

Scene demScene(const fs::path& dir, const std::string& keys, const std::string& terrainKeys = "")
{
    std::ofstream(dir / "scene.toml") << "[terrain]\nroot = \"land\"\n" << terrainKeys
                                      << "[terrain.nodes.land]\ntype = \"dem_heightfield\"\nfile = \"dem.tif\"\n"
                                      << keys << "[region]\nmin = [-160, 0, -130]\nmax = [160, 200, 130]\n"
                                      << "[sampling]\nvoxel_size = 4\n";
    return strata::scene::loadScene(dir / "scene.toml");
}

const DemHeightfield& dem(const Scene& scene)
{
    const auto* field = dynamic_cast<const DemHeightfield*>(scene.field.get());
    if (!field) throw std::runtime_error("the root is not a dem_heightfield");
    return *field;
}

std::string loadError(const fs::path& dir)
{
    try {
        demScene(dir, "");
    } catch (const strata::Error& e) {
        return e.what();
    }
    return "no error";
}

/// The latitude whose meridian arc (WGS84) times UTM's scale 0.9996 is
/// `northing`: a point on a zone's central meridian (bisection on the
/// arc's series, independent of GDAL and PROJ).
double utmLatitudeOnCentralMeridian(double northing)
{
    const double e2 = WGS84_E2, e4 = e2 * e2, e6 = e4 * e2;
    const auto arc = [&](double phi) {
        return WGS84_A * ((1 - e2 / 4 - 3 * e4 / 64 - 5 * e6 / 256) * phi -
                          (3 * e2 / 8 + 3 * e4 / 32 + 45 * e6 / 1024) * std::sin(2 * phi) +
                          (15 * e4 / 256 + 45 * e6 / 1024) * std::sin(4 * phi) - (35 * e6 / 3072) * std::sin(6 * phi));
    };
    double lo = 0.0, hi = PI / 2;
    for (int i = 0; i < 200; ++i) {
        const double mid = 0.5 * (lo + hi);
        (0.9996 * arc(mid) < northing ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi) * 180.0 / PI;
}

} // namespace

// A UTM GeoTIFF (metres): cell centres where the geotransform puts them,
// around the raster's centre; bilinear between them; a nodata cell filled
// with the lowest height.
TEST(DemHeightfield, AUtmGeoTiffLiesEastAndNorthOfItsCentreInMetres)
{
    const auto dir = strata::test::freshTestDir();
    strata::test::DemSpec spec;
    spec.noData = -9999.0;
    spec.value = [](int i, int j) { return i == 10 && j == 8 ? -9999.0 : 100.0 + 2.0 * i + 3.0 * j; };
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", spec));
    const Scene scene = demScene(dir, "");
    const DemHeightfield& land = dem(scene);
    // Centre (500015, 3999985); cell (0, 0)'s centre (499865, 4000105).
    EXPECT_DOUBLE_EQ(land.minCorner().x, -150.0);
    EXPECT_DOUBLE_EQ(land.minCorner().y, -120.0); // north is −z
    EXPECT_DOUBLE_EQ(land.maxCorner().x, 150.0);
    EXPECT_DOUBLE_EQ(land.maxCorner().y, 120.0);
    EXPECT_NEAR(land.height(-150.0, -120.0), 100.0, 1e-9);     // cell (0, 0), the north-west one
    EXPECT_NEAR(land.height(-30.0, -60.0), 114.0, 1e-9);       // cell (4, 2)
    EXPECT_NEAR(land.height(-15.0, -45.0), 116.5, 1e-9);       // between cells 4, 5 and rows 2, 3
    EXPECT_NEAR(land.height(150.0, 120.0), 100.0, 1e-9);       // cell (10, 8): no data, the lowest height
    EXPECT_NEAR(land.height(120.0, 120.0), 100.0 + 18 + 24, 1e-9);
    // The file is one of the scene's inputs (the bake hashes its bytes).
    ASSERT_EQ(scene.inputFiles.size(), 1u);
    EXPECT_EQ(scene.inputFiles[0].filename(), "dem.tif");
}

// The CRS places the scene's origin on the Earth: origin given on zone
// 17N's central meridian (81° W) at northing 4,000,000 m, and base shifts
// the datum's zero to y = −100 (so the origin is 100 m above it).
TEST(DemHeightfield, ItsCrsPlacesTheSceneOnTheEarth)
{
    const auto dir = strata::test::freshTestDir();
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", {}));
    const Scene scene = demScene(dir, "origin = [500000, 4000000]\nbase = -100\n");
    ASSERT_TRUE(scene.georeference);
    EXPECT_NEAR(scene.georeference->longitude, -81.0, 1e-9);
    EXPECT_NEAR(scene.georeference->latitude, utmLatitudeOnCentralMeridian(4000000.0), 1e-7); // 1 cm
    EXPECT_DOUBLE_EQ(scene.georeference->height, 100.0);
    // The origin moves the grid: the centre is now 15 m east and south.
    EXPECT_DOUBLE_EQ(dem(scene).minCorner().x, -150.0 + 15.0);
    EXPECT_DOUBLE_EQ(dem(scene).minCorner().y, -120.0 + 15.0);

    // The bake's tileset goes there unless --georeference says otherwise.
    strata::scene::BakeOptions options;
    options.outputDir = dir / "bake";
    options.tileSize = 128.0;
    strata::scene::BakePlan plan = strata::scene::planBake(scene, options);
    ASSERT_TRUE(plan.georeference);
    EXPECT_EQ(plan.georeference->latitude, scene.georeference->latitude);
    options.georeference = "none";
    EXPECT_FALSE(strata::scene::planBake(scene, options).georeference);
    options.georeference = "10,20,30";
    plan = strata::scene::planBake(scene, options);
    ASSERT_TRUE(plan.georeference);
    EXPECT_EQ(plan.georeference->latitude, 10.0);
}

// A geographic DEM (degrees, 3 arc-seconds, heights in feet as integers
// with a nodata value) is laid out in metres by the ellipsoid's radii at its
// centre latitude; its georeference is the centre itself.
TEST(DemHeightfield, AGeographicDemInFeetIsLaidOutInMetres)
{
    const auto dir = strata::test::freshTestDir();
    strata::test::DemSpec spec;
    spec.width = 13;
    spec.height = 7;
    spec.type = GDT_Int16;
    const double step = 1.0 / 1200.0;
    // Centre at (10° E, 45° N).
    spec.geoTransform = std::array<double, 6>{10.0 - 6.5 * step, step, 0.0, 45.0 + 3.5 * step, 0.0, -step};
    spec.epsg = 4326;
    spec.noData = -32768;
    spec.unit = "ft";
    spec.value = [](int i, int j) { return i == 0 && j == 0 ? -32768.0 : 1000.0 + 10.0 * i; };
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", spec));
    const Scene scene = demScene(dir, "");
    const DemHeightfield& land = dem(scene);
    // Metres per degree at 45° on WGS84: 78,846.835 east, 111,131.777 north.
    const double s = std::sin(45.0 * PI / 180.0), w = std::sqrt(1.0 - WGS84_E2 * s * s);
    const double east = WGS84_A / w * std::cos(45.0 * PI / 180.0) * PI / 180.0;
    const double north = WGS84_A * (1.0 - WGS84_E2) / (w * w * w) * PI / 180.0;
    EXPECT_NEAR(east, 78846.835, 1e-3);
    EXPECT_NEAR(north, 111131.777, 1e-3);
    EXPECT_NEAR(land.minCorner().x, -6.0 * step * east, 1e-6);
    EXPECT_NEAR(land.maxCorner().x, 6.0 * step * east, 1e-6);
    EXPECT_NEAR(land.minCorner().y, -3.0 * step * north, 1e-6);
    EXPECT_NEAR(land.maxCorner().y, 3.0 * step * north, 1e-6);
    // Column 6 (the centre column): 1060 ft; cell (0, 0) has no data: the
    // lowest height, column 0's 1000 ft.
    EXPECT_NEAR(land.height(0.0, 0.0), 1060.0 * 0.3048, 1e-3);
    EXPECT_NEAR(land.height(land.minCorner().x, land.minCorner().y), 1000.0 * 0.3048, 1e-3);
    ASSERT_TRUE(scene.georeference);
    EXPECT_NEAR(scene.georeference->latitude, 45.0, 1e-9);
    EXPECT_NEAR(scene.georeference->longitude, 10.0, 1e-9);
}

// A grid stored south up and east to west reads as the same land.
TEST(DemHeightfield, SouthUpAndWestwardGridsAreTurnedNorthUp)
{
    const auto dir = strata::test::freshTestDir();
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", {}));
    const Scene northUp = demScene(dir, "");
    strata::test::DemSpec flipped;
    // Column i of the file is column 10 − i of the land, row j is row 8 − j.
    flipped.geoTransform = std::array<double, 6>{500180.0, -30.0, 0.0, 3999850.0, 0.0, 30.0};
    flipped.value = [](int i, int j) { return 100.0 + 2.0 * (10 - i) + 3.0 * (8 - j); };
    fs::remove(dir / "dem.tif");
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", flipped));
    const Scene turned = demScene(dir, "");
    for (double x = -150.0; x <= 150.0; x += 17.0)
        for (double z = -120.0; z <= 120.0; z += 13.0)
            EXPECT_EQ(dem(turned).height(x, z), dem(northUp).height(x, z)) << x << ", " << z;
}

// Without a CRS the grid is taken as metres and the scene has no place.
TEST(DemHeightfield, WithoutACrsTheSceneHasNoPlace)
{
    const auto dir = strata::test::freshTestDir();
    strata::test::DemSpec spec;
    spec.epsg = 0;
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", spec));
    const Scene scene = demScene(dir, "height_scale = 2\n");
    EXPECT_FALSE(scene.georeference);
    EXPECT_NEAR(dem(scene).height(-150.0, -120.0), 200.0, 1e-9);
}

// Files that are not usable DEMs: each refused naming the key, the file and why.
TEST(DemHeightfield, BadFilesAreRefusedNamingTheKeyAndWhy)
{
    const auto dir = strata::test::freshTestDir();
    const auto expectRefused = [&](const strata::test::DemSpec& spec, const std::string& why) {
        fs::remove(dir / "dem.tif");
        ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", spec));
        const std::string error = loadError(dir);
        EXPECT_NE(error.find("terrain.nodes.land.file"), std::string::npos) << error;
        EXPECT_NE(error.find("dem.tif"), std::string::npos) << error;
        EXPECT_NE(error.find(why), std::string::npos) << error;
    };
    strata::test::DemSpec spec;
    spec.geoTransform.reset();
    spec.epsg = 0;
    expectRefused(spec, "no geotransform");
    spec = {};
    spec.geoTransform = std::array<double, 6>{0.0, 30.0, 5.0, 0.0, 0.0, -30.0};
    expectRefused(spec, "rotated or sheared");
    spec = {};
    spec.noData = 7.0;
    spec.value = [](int, int) { return 7.0; };
    expectRefused(spec, "no cell with data");
    spec = {};
    spec.unit = "degC";
    expectRefused(spec, "height unit 'degc'");
    spec = {};
    spec.width = 1;
    expectRefused(spec, "DEMs need 2x2");
    // 40000 × 40000 cells claimed in a few kilobytes: refused before reading.
    spec = {};
    spec.width = spec.height = 40000;
    spec.sparse = true;
    expectRefused(spec, "DEMs need 2x2 to 16384x16384");
    EXPECT_LT(fs::file_size(dir / "dem.tif"), 1u << 20);

    std::ofstream(dir / "dem.tif", std::ios::trunc) << "not a raster\n";
    EXPECT_NE(loadError(dir).find("cannot be read as a DEM"), std::string::npos) << loadError(dir);
    fs::remove(dir / "dem.tif");
    EXPECT_NE(loadError(dir).find("no such file"), std::string::npos) << loadError(dir);
}

// Two georeferenced DEMs: the scene names the one that places it.
TEST(DemHeightfield, TwoPlacedDemsNeedTheSceneToNameOne)
{
    const auto dir = strata::test::freshTestDir();
    ASSERT_TRUE(strata::test::writeDem(dir / "dem.tif", {}));
    const std::string two = "[terrain]\nroot = \"both\"\n[terrain.nodes.both]\ntype = \"height_max\"\n"
                            "children = [\"a\", \"b\"]\n[terrain.nodes.a]\ntype = \"dem_heightfield\"\nfile = \"dem.tif\"\n"
                            "[terrain.nodes.b]\ntype = \"dem_heightfield\"\nfile = \"dem.tif\"\norigin = [500000, 4000000]\n";
    std::ofstream(dir / "two.toml") << two;
    try {
        strata::scene::loadScene(dir / "two.toml");
        ADD_FAILURE() << "two placed DEMs were accepted without terrain.georeference";
    } catch (const strata::Error& e) {
        EXPECT_NE(std::string(e.what()).find("terrain.georeference is required"), std::string::npos) << e.what();
    }
    std::ofstream(dir / "two.toml") << "[terrain]\ngeoreference = \"b\"\n" << two.substr(std::string("[terrain]\n").size());
    const Scene scene = strata::scene::loadScene(dir / "two.toml");
    ASSERT_TRUE(scene.georeference);
    EXPECT_NEAR(scene.georeference->longitude, -81.0, 1e-9);
}

// Real land: the 3 arc-second DEM of the Jacksboro fault (Tennessee) that
// Debian's python-matplotlib-data ships as .npz (scripts/install-deps.sh),
// written here as an ESRI ASCII grid with a WGS84 .prj (the form USGS
// distributes), read back through GDAL: every cell where its geographic
// position puts it, 74.573 m east and 92.475 m north apart at its centre,
// 36.5896° N (WGS84's radii there; 1/1200° each).
TEST(DemHeightfield, TheJacksboroDemLiesWhereItsCoordinatesSay)
{
    const fs::path npz = "/usr/share/matplotlib/mpl-data/sample_data/jacksboro_fault_dem.npz";
    ASSERT_TRUE(fs::exists(npz)) << npz << " is missing (apt-get install python-matplotlib-data)";
    const strata::terrain::ElevationGrid grid = strata::terrain::readElevationFile(npz);
    ASSERT_EQ(grid.width, 403);
    ASSERT_EQ(grid.height, 344);
    // The archive's own corners (its xmin, ymax members; ymax is the south).
    const double west = -84.41375, south = 36.44625, cell = 1.0 / 1200.0;
    const auto dir = strata::test::freshTestDir();
    {
        std::ofstream asc(dir / "dem.asc");
        asc.precision(17);
        asc << "ncols 403\nnrows 344\nxllcorner " << west << "\nyllcorner " << south << "\ncellsize " << cell
            << "\nNODATA_value -9999\n";
        for (int j = 0; j < grid.height; ++j) {
            for (int i = 0; i < grid.width; ++i) asc << grid.heights[std::size_t(j) * 403 + std::size_t(i)] << ' ';
            asc << '\n';
        }
        std::ofstream(dir / "dem.prj") << "GEOGCS[\"WGS 84\",DATUM[\"WGS_1984\",SPHEROID[\"WGS 84\",6378137,298.257223563]],"
                                          "PRIMEM[\"Greenwich\",0],UNIT[\"degree\",0.0174532925199433]]";
    }
    std::ofstream(dir / "scene.toml") << "[terrain]\nroot = \"land\"\n[terrain.nodes.land]\ntype = \"dem_heightfield\"\n"
                                         "file = \"dem.asc\"\nbase = -600\n";
    const Scene scene = strata::scene::loadScene(dir / "scene.toml");
    const DemHeightfield& land = dem(scene);
    const double centreLon = west + 201.5 * cell, centreLat = south + 172.0 * cell;
    ASSERT_TRUE(scene.georeference);
    EXPECT_NEAR(scene.georeference->longitude, centreLon, 1e-9);
    EXPECT_NEAR(scene.georeference->latitude, centreLat, 1e-9);
    EXPECT_DOUBLE_EQ(scene.georeference->height, 600.0);
    const double east = (land.maxCorner().x - land.minCorner().x) / 402.0;
    const double north = (land.maxCorner().y - land.minCorner().y) / 343.0;
    EXPECT_NEAR(east, 74.5732, 1e-3);
    EXPECT_NEAR(north, 92.4750, 1e-3);
    // Cell centres hold the file's heights (integers: exact), minus 600.
    for (int j = 0; j < grid.height; j += 7) {
        for (int i = 0; i < grid.width; i += 11) {
            const double lon = west + (i + 0.5) * cell, lat = south + (343 - j + 0.5) * cell;
            const double x = (lon - centreLon) / cell * east, z = -(lat - centreLat) / cell * north;
            EXPECT_NEAR(land.height(x, z), grid.heights[std::size_t(j) * 403 + std::size_t(i)] - 600.0, 1e-6)
                << "cell " << i << ", " << j;
        }
    }
}
