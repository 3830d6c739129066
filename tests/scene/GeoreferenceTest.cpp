// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// strata bake --georeference LAT,LON,HEIGHT: the east-north-up frame at a
// WGS84 point against hand-computed ECEF values, bad values refused naming
// the flag, and the tileset's root transform (written by bake and kept out
// of the bake's identity).

#include <strata/scene/Bake.h>
#include <strata/scene/Georeference.h>
#include <strata/scene/Scene.h>
#include "RunStrata.h"
#include "TestDir.h"

#include <strata/Error.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>

using namespace strata;
using namespace strata::scene;
namespace fs = std::filesystem;

namespace {

const char* SMALL_SCENE = R"(
seed = 5
[terrain]
root = "land"
[terrain.nodes.land]
type = "heightfield"
amplitude = 3.0
wavelength = 20.0
[region]
min = [-8.0, -4.0, -8.0]
max = [8.0, 4.0, 8.0]
[sampling]
voxel_size = 0.5
)";

nlohmann::json readJson(const fs::path& path)
{
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

std::string readText(const fs::path& path)
{
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

TEST(Georeference, EastNorthUpAtTheEquatorAndPrimeMeridianIsTheAxes)
{
    // At (0°, 0°, 0 m): east = +Y, north = +Z, up = +X, the point at (a, 0, 0).
    const std::array<double, 16> m = eastNorthUpToEcef({0.0, 0.0, 0.0});
    const std::array<double, 16> expected{0, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 6378137.0, 0, 0, 1};
    for (int i = 0; i < 16; ++i) EXPECT_NEAR(m[i], expected[i], 1e-12 * std::max(1.0, std::abs(expected[i]))) << i;
    // The North Pole lies on the semi-minor axis b = a(1 − f).
    const std::array<double, 3> pole = ecefPosition({90.0, 0.0, 0.0});
    EXPECT_NEAR(pole[2], 6356752.314245, 1e-6);
    EXPECT_NEAR(pole[0], 0.0, 1e-6);
}

TEST(Georeference, MatchesAHandComputedFrameAtAKnownPoint)
{
    // 46.5° N, 7.9° E, 1200 m: ECEF from N = a / sqrt(1 − e² sin²φ),
    // X = (N + h) cos φ cos λ, Y = (N + h) cos φ sin λ, Z = (N(1 − e²) + h) sin φ
    // (WGS84 a = 6378137 m, f = 1/298.257223563), computed by hand.
    const Georeference point{46.5, 7.9, 1200.0};
    const std::array<double, 16> m = eastNorthUpToEcef(point);
    EXPECT_NEAR(m[12], 4357249.780724, 1e-5);
    EXPECT_NEAR(m[13], 604618.370958, 1e-5);
    EXPECT_NEAR(m[14], 4604550.847891, 1e-5);
    EXPECT_EQ(m[15], 1.0);
    const double phi = 46.5 * M_PI / 180.0, lambda = 7.9 * M_PI / 180.0;
    const double east[3] = {-std::sin(lambda), std::cos(lambda), 0.0};
    const double north[3] = {-std::sin(phi) * std::cos(lambda), -std::sin(phi) * std::sin(lambda), std::cos(phi)};
    const double up[3] = {std::cos(phi) * std::cos(lambda), std::cos(phi) * std::sin(lambda), std::sin(phi)};
    for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(m[i], east[i], 1e-15);
        EXPECT_NEAR(m[4 + i], north[i], 1e-15);
        EXPECT_NEAR(m[8 + i], up[i], 1e-15);
        EXPECT_EQ(m[3 + 4 * i], 0.0);
    }
    // Up is the ellipsoid's normal there: the gradient of x²/a² + y²/a² + z²/b²
    // at the foot of the point (height 0).
    const std::array<double, 3> foot = ecefPosition({46.5, 7.9, 0.0});
    const double a2 = 6378137.0 * 6378137.0, b = 6378137.0 * (1.0 - 1.0 / 298.257223563);
    double g[3] = {foot[0] / a2, foot[1] / a2, foot[2] / (b * b)};
    const double len = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(m[8 + i], g[i] / len, 1e-12);
    // A second point, in the southern hemisphere: Cape Town.
    const std::array<double, 3> cape = ecefPosition({-33.9, 18.4, 10.0});
    EXPECT_NEAR(cape[0], 5028531.662195, 1e-5);
    EXPECT_NEAR(cape[1], 1672769.842373, 1e-5);
    EXPECT_NEAR(cape[2], -3537250.925356, 1e-5);
}

TEST(Georeference, ParsesThreeNumbersAndRefusesBadValuesNamingTheFlag)
{
    const Georeference p = parseGeoreference("-33.9,18.4,10");
    EXPECT_EQ(p.latitude, -33.9);
    EXPECT_EQ(p.longitude, 18.4);
    EXPECT_EQ(p.height, 10.0);
    const Georeference q = parseGeoreference("90, -180, -50.5");
    EXPECT_EQ(q.latitude, 90.0);
    EXPECT_EQ(q.longitude, -180.0);
    EXPECT_EQ(q.height, -50.5);
    const auto refused = [](const std::string& text, const std::string& says) {
        try {
            parseGeoreference(text);
            ADD_FAILURE() << "accepted '" << text << "'";
        } catch (const Error& e) {
            EXPECT_EQ(e.kind(), ErrorKind::BadInput);
            const std::string message = e.what();
            EXPECT_NE(message.find("--georeference"), std::string::npos) << message;
            EXPECT_NE(message.find(says), std::string::npos) << message;
            EXPECT_EQ(e.place().key, "--georeference");
        }
    };
    refused("46.5,7.9", "expected LAT,LON,HEIGHT");
    refused("46.5,7.9,1,2", "expected LAT,LON,HEIGHT");
    refused("", "expected LAT,LON,HEIGHT");
    refused("north,7.9,0", "the latitude 'north' is not a number");
    refused("46.5,7.9e,0", "the longitude '7.9e' is not a number");
    refused("46.5,7.9,nan", "the height 'nan' is not a finite number");
    refused("inf,7.9,0", "the latitude 'inf' is not a finite number");
    refused("90.5,0,0", "the latitude 90.5 is not in [-90, 90]");
    refused("0,-180.25,0", "the longitude -180.25 is not in [-180, 180]");
    refused("0,0,2e7", "the height 2e7 m is not in");
    refused("0,0,-1e6", "is not in [-100000, 10000000] m");
}

TEST(Georeference, TheBakesTilesetCarriesTheRootTransformOutsideTheBakesIdentity)
{
    const fs::path dir = test::freshTestDir();
    const Scene scene = parseScene(SMALL_SCENE, "small.toml");
    BakeOptions options;
    options.outputDir = dir;
    options.tileSize = 8.0;
    options.lods = 2;
    options.grids = false;

    // No georeference: no transform, no key in bake.json.
    bake(scene, options, planBake(scene, options));
    EXPECT_FALSE(readJson(dir / "tileset.json")["root"].contains("transform"));
    EXPECT_EQ(readText(dir / "bake.json").find("georeference"), std::string::npos);

    options.georeference = "46.5,7.9,1200";
    const BakeSummary placed = bake(scene, options, planBake(scene, options));
    EXPECT_EQ(placed.baked, 0) << "the same tiles: kept";
    const nlohmann::json transform = readJson(dir / "tileset.json")["root"]["transform"];
    ASSERT_EQ(transform.size(), 16u);
    const std::array<double, 16> expected = eastNorthUpToEcef({46.5, 7.9, 1200.0});
    for (int i = 0; i < 16; ++i) EXPECT_EQ(transform[std::size_t(i)].get<double>(), expected[std::size_t(i)]) << i;
    EXPECT_EQ(readJson(dir / "bake.json")["georeference"]["latitude"], 46.5);

    // finalize (after workers) writes it from bake.json.
    fs::remove(dir / "tileset.json");
    finalizeBake(dir);
    EXPECT_EQ(readJson(dir / "tileset.json")["root"]["transform"], transform);

    options.georeference = "46.5,7.9,abc";
    EXPECT_THROW(planBake(scene, options), Error);
}

TEST(Georeference, TheCliTakesTheFlagAndRefusesBadValuesWithExit2)
{
    STRATA_REQUIRE_PROGRAM();
    const fs::path dir = test::freshTestDir();
    {
        std::ofstream(dir / "small.toml") << SMALL_SCENE;
    }
    const std::string bakeArgs = "bake " + (dir / "small.toml").string() + " -o " + (dir / "out").string() +
                                 " --tile-size 8 --lods 2 --no-grids -q --georeference ";
    const test::CommandResult bad = test::runStrata(bakeArgs + "91,7.9,0", dir);
    EXPECT_EQ(bad.exitCode, 2) << bad.output;
    EXPECT_NE(bad.output.find("--georeference 91,7.9,0: the latitude 91 is not in [-90, 90]"), std::string::npos)
        << bad.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << "nothing written";
    // A negative latitude is a value, not a flag.
    const test::CommandResult good = test::runStrata(bakeArgs + "-33.9,18.4,10", dir);
    ASSERT_EQ(good.exitCode, 0) << good.output;
    const nlohmann::json transform = readJson(dir / "out/tileset.json")["root"]["transform"];
    EXPECT_NEAR(transform[12].get<double>(), 5028531.662195, 1e-5);
}
