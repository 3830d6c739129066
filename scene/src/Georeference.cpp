// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/scene/Georeference.h>

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>

#include <charconv>
#include <cmath>
#include <string_view>

namespace strata::scene {

namespace {

// WGS84 (NIMA TR8350.2): semi-major axis and flattening.
constexpr double WGS84_A = 6378137.0;
constexpr double WGS84_F = 1.0 / 298.257223563;
constexpr double WGS84_E2 = WGS84_F * (2.0 - WGS84_F); // first eccentricity squared

constexpr double MIN_HEIGHT = -100e3; // deeper than any ocean trench, far from the centre
constexpr double MAX_HEIGHT = 10e6;   // well past low orbit

[[noreturn]] void bad(const std::string& what, const std::string& value, const std::string& why)
{
    throw Error(ErrorKind::BadInput, what + " " + value + ": " + why, {"", 0, what, value});
}

/// The range checks, naming each value as `shown` (the user's spelling).
void checkRanges(const Georeference& p, const std::string& what, const std::string& text, const std::string shown[3])
{
    if (!std::isfinite(p.latitude) || p.latitude < -90.0 || p.latitude > 90.0)
        bad(what, text, "the latitude " + shown[0] + " is not in [-90, 90] degrees");
    if (!std::isfinite(p.longitude) || p.longitude < -180.0 || p.longitude > 180.0)
        bad(what, text, "the longitude " + shown[1] + " is not in [-180, 180] degrees");
    if (!std::isfinite(p.height) || p.height < MIN_HEIGHT || p.height > MAX_HEIGHT)
        bad(what, text, "the height " + shown[2] + " m is not in [-100000, 10000000] m above the WGS84 ellipsoid");
}

/// Sines and cosines of a point's latitude and longitude (dmath: the same
/// bits from every C library).
struct Angles
{
    double sinLat = 0.0, cosLat = 1.0, sinLon = 0.0, cosLon = 1.0;
};

Angles anglesOf(const Georeference& p)
{
    Angles a;
    // In degrees: reduced exactly, so 90° and 180° give exactly 1, 0 and −1.
    dmath::sinCosDegrees(p.latitude, a.sinLat, a.cosLat);
    dmath::sinCosDegrees(p.longitude, a.sinLon, a.cosLon);
    return a;
}

} // namespace

void checkGeoreference(const Georeference& p, const std::string& what)
{
    const std::string shown[3] = {formatNumber(p.latitude), formatNumber(p.longitude), formatNumber(p.height)};
    checkRanges(p, what, shown[0] + "," + shown[1] + "," + shown[2], shown);
}

Georeference parseGeoreference(const std::string& text, const std::string& flag)
{
    const std::string expected = "expected LAT,LON,HEIGHT: latitude and longitude in degrees, height in metres "
                                 "above the WGS84 ellipsoid (e.g. 46.5,7.9,1200)";
    double values[3] = {0.0, 0.0, 0.0};
    std::string shown[3];
    const char* const names[3] = {"latitude", "longitude", "height"};
    std::string_view rest(text);
    for (int i = 0; i < 3; ++i) {
        const std::size_t comma = rest.find(',');
        if ((comma == std::string_view::npos) != (i == 2)) bad(flag, text, expected);
        std::string_view part = rest.substr(0, comma);
        while (!part.empty() && part.front() == ' ') part.remove_prefix(1);
        while (!part.empty() && part.back() == ' ') part.remove_suffix(1);
        if (!part.empty() && part.front() == '+') part.remove_prefix(1);
        const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), values[i]);
        if (part.empty() || ec != std::errc() || end != part.data() + part.size())
            bad(flag, text, "the " + std::string(names[i]) + " '" + std::string(part) + "' is not a number; " + expected);
        if (!std::isfinite(values[i]))
            bad(flag, text, "the " + std::string(names[i]) + " '" + std::string(part) + "' is not a finite number");
        shown[i] = std::string(part);
        if (comma != std::string_view::npos) rest.remove_prefix(comma + 1);
    }
    const Georeference point{values[0], values[1], values[2]};
    checkRanges(point, flag, text, shown);
    return point;
}

std::array<double, 3> ecefPosition(const Georeference& p)
{
    const auto [sinLat, cosLat, sinLon, cosLon] = anglesOf(p);
    const double n = WGS84_A / std::sqrt(1.0 - WGS84_E2 * sinLat * sinLat); // prime vertical radius
    return {(n + p.height) * cosLat * cosLon, (n + p.height) * cosLat * sinLon,
            (n * (1.0 - WGS84_E2) + p.height) * sinLat};
}

std::array<double, 16> eastNorthUpToEcef(const Georeference& p)
{
    const auto [sinLat, cosLat, sinLon, cosLon] = anglesOf(p);
    const std::array<double, 3> o = ecefPosition(p);
    return {-sinLon,          cosLon,           0.0,    0.0,  // east
            -sinLat * cosLon, -sinLat * sinLon, cosLat, 0.0,  // north
            cosLat * cosLon,  cosLat * sinLon,  sinLat, 0.0,  // up (the ellipsoid's normal)
            o[0],             o[1],             o[2],   1.0}; // the point
}

} // namespace strata::scene
