// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// `strata bench noise --fastnoise-lite PATH` compiles the user's copy of
// FastNoiseLite.h at run time. FastNoiseLite is never shipped with Strata,
// so these tests compile a stand-in header with its public API whose
// GetNoise reports the settings it was given: that checks the compile, the
// load, the settings each Strata basis maps to, and the errors.

#include "FastNoiseLiteReference.h"

#include "TestDir.h"

#include <strata/Error.h>
#include <strata/terrain/NoiseThroughput.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <vector>

namespace {

using strata::terrain::detail::FastNoiseLiteReference;
using strata::terrain::detail::ReferenceBasis;

// FastNoiseLite's API as the shim uses it (names and enumerator values from
// version 1.1.1); GetNoise encodes the settings into the value it returns.
constexpr const char* STAND_IN = R"(#pragma once
class FastNoiseLite {
public:
    enum NoiseType { NoiseType_OpenSimplex2, NoiseType_OpenSimplex2S, NoiseType_Cellular, NoiseType_Perlin,
                     NoiseType_ValueCubic, NoiseType_Value };
    enum FractalType { FractalType_None, FractalType_FBm };
    enum CellularDistanceFunction { CellularDistanceFunction_Euclidean, CellularDistanceFunction_EuclideanSq };
    enum CellularReturnType { CellularReturnType_CellValue, CellularReturnType_Distance, CellularReturnType_Distance2 };
    FastNoiseLite(int seed = 1337) : mSeed(seed) {}
    void SetFrequency(float f) { mFrequency = f; }
    void SetNoiseType(NoiseType t) { mType = t; }
    void SetCellularDistanceFunction(CellularDistanceFunction d) { mDistance = d; }
    void SetCellularReturnType(CellularReturnType r) { mReturn = r; }
    void SetFractalType(FractalType t) { mFractal = t; }
    void SetFractalOctaves(int o) { mOctaves = o; }
    void SetFractalLacunarity(float l) { mLacunarity = l; }
    void SetFractalGain(float g) { mGain = g; }
    template <typename F> float GetNoise(F x, F y) const { return settings() + 0.25f * (x + y); }
    template <typename F> float GetNoise(F x, F y, F z) const { return settings() + 0.25f * (x + y + z) + 1e6f; }
private:
    float settings() const
    {
        if (mSeed != 7 || mFrequency != 1.0f || (mFractal == FractalType_FBm && (mLacunarity != 2.0f || mGain != 0.5f)))
            return -1.0f;
        return float(1000 * mType + 100 * (mFractal == FractalType_FBm ? mOctaves : 0) + 10 * mDistance + mReturn);
    }
    int mSeed; float mFrequency = 0.01f; NoiseType mType = NoiseType_OpenSimplex2; FractalType mFractal = FractalType_None;
    int mOctaves = 3; float mLacunarity = 2.0f, mGain = 0.5f;
    CellularDistanceFunction mDistance = CellularDistanceFunction_EuclideanSq; CellularReturnType mReturn = CellularReturnType_Distance;
};
)";

std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text)
{
    std::ofstream(path) << text;
    return path;
}

TEST(FastNoiseLiteReference, CompilesTheGivenHeaderAndMapsEachBasisToItsSettings)
{
    const auto dir = strata::test::freshTestDir();
    const FastNoiseLiteReference reference(writeFile(dir / "FastNoiseLite.h", STAND_IN).string());
    EXPECT_NE(reference.command().find("-O3 -march=native"), std::string::npos) << reference.command();

    const float x[2] = {0.0f, 4.0f}, y[2] = {0.0f, 8.0f}, z[2] = {0.0f, 12.0f};
    float out[2] = {};
    const auto settingsOf = [&](ReferenceBasis basis, int octaves, int dimensions) {
        reference.fill(basis, octaves, dimensions, x, y, z, 2, out);
        // The second point: the coordinates the stand-in saw, (x, z) in 2D.
        EXPECT_EQ(out[1] - out[0], dimensions == 3 ? 6.0f : 4.0f);
        return out[0] - (dimensions == 3 ? 1e6f : 0.0f);
    };
    // 1000 · type + 100 · octaves (fBm) + 10 · distance + return type; the
    // cellular settings stay at FastNoiseLite's defaults (EuclideanSq = 1,
    // Distance = 1) for the other bases.
    EXPECT_EQ(settingsOf(ReferenceBasis::GRADIENT, 1, 3), 3011.0f);  // Perlin
    EXPECT_EQ(settingsOf(ReferenceBasis::SIMPLEX, 1, 3), 11.0f);     // OpenSimplex2
    EXPECT_EQ(settingsOf(ReferenceBasis::VALUE, 5, 3), 5511.0f);     // Value, fBm 5
    EXPECT_EQ(settingsOf(ReferenceBasis::CELLULAR_F1, 1, 2), 2001.0f); // Cellular, Euclidean, Distance
    EXPECT_EQ(settingsOf(ReferenceBasis::CELLULAR_F2, 5, 2), 2502.0f); // Distance2, fBm 5
}

TEST(FastNoiseLiteReference, AMissingOrBrokenHeaderIsABadInputNamingThePath)
{
    const auto dir = strata::test::freshTestDir();
    const std::string missing = (dir / "nowhere" / "FastNoiseLite.h").string();
    try {
        FastNoiseLiteReference reference(missing);
        FAIL() << "no error for a missing header";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
    const std::string broken = writeFile(dir / "broken.h", "class NotFastNoise {};\n").string();
    try {
        FastNoiseLiteReference reference(broken);
        FAIL() << "no error for a header that is not FastNoiseLite";
    } catch (const strata::Error& e) {
        EXPECT_EQ(e.kind(), strata::ErrorKind::BadInput);
        const std::string message = e.what();
        EXPECT_NE(message.find(broken), std::string::npos) << message;
        EXPECT_NE(message.find("does not compile"), std::string::npos) << message;
        EXPECT_NE(message.find("FastNoiseLite"), std::string::npos) << message; // the compiler's complaint
    }
}

TEST(FastNoiseLiteReference, TheThroughputMeasuresItBesideTheBlockPath)
{
    const auto dir = strata::test::freshTestDir();
    strata::terrain::NoiseThroughputOptions options;
    options.seconds = 0.003;
    options.fastNoiseLite = writeFile(dir / "FastNoiseLite.h", STAND_IN).string();
    const std::vector<strata::terrain::NoiseThroughput> rows = strata::terrain::measureNoiseThroughput(options);
    ASSERT_EQ(rows.size(), 20u);
    for (const auto& row : rows) {
        EXPECT_GT(row.fastNoiseLiteRate, 0.0) << row.name << " " << row.dimensions << "D";
        EXPECT_GT(row.version2Rate, 0.0) << row.name << " " << row.dimensions << "D";
        EXPECT_GT(row.version2ScatteredRate, 0.0) << row.name << " " << row.dimensions << "D";
    }
    options.fastNoiseLite.clear();
    for (const auto& row : strata::terrain::measureNoiseThroughput(options)) EXPECT_EQ(row.fastNoiseLiteRate, 0.0);
}

} // namespace
