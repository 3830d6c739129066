// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Spectral slopes of surfaces synthesised with a known power spectrum,
// |F(k)|² ∝ k^−β with phases from a fixed integer hash, transformed back
// with a plain separable DFT written here (independent of the library's
// FFT): β = 3 and 5 are recovered in both bands, on the periodic grid and
// on a crop that is neither periodic nor a power of two; a tilt added to the
// surface changes nothing (it is detrended); a plane and a small grid give
// NaN; the cell size scales the band's wavelengths only; the same bits on
// one thread; bad input.

#include <strata/detail/IntegerHash.h>
#include <strata/Error.h>
#include <strata/terrain/HeightSpectrum.h>

#include "TerrainTestHelpers.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace strata::terrain;
using strata::test::errorOf;
using strata::test::tiltedPlane;

using strata::detail::lowbias32;

/// An N × N periodic surface with |F(k)|² ∝ k^−β (k in cycles per cell),
/// random phases from lowbias32(), RMS scaled to `rms` metres: the real part of
/// the inverse DFT, computed row by row and then column by column (O(N³)).
std::vector<double> synthesize(int n, double beta, std::uint32_t seed, double rms)
{
    const std::size_t N = std::size_t(n);
    std::vector<double> cosines(N), sines(N);
    for (std::size_t m = 0; m < N; ++m) {
        cosines[m] = std::cos(2.0 * std::numbers::pi * double(m) / double(n));
        sines[m] = std::sin(2.0 * std::numbers::pi * double(m) / double(n));
    }
    // Spectrum F[j][i] (re, im).
    std::vector<double> fr(N * N, 0.0), fi(N * N, 0.0);
    for (std::size_t j = 0; j < N; ++j) {
        const double kz = (j <= N / 2 ? double(j) : double(j) - double(n)) / double(n);
        for (std::size_t i = 0; i < N; ++i) {
            if (i == 0 && j == 0) continue;
            const double kx = (i <= N / 2 ? double(i) : double(i) - double(n)) / double(n);
            const double amplitude = std::pow(std::hypot(kx, kz), -0.5 * beta);
            const double phase =
                2.0 * std::numbers::pi * double(lowbias32(std::uint32_t(i + N * j) ^ (seed * 0x9e3779b9u))) / 4294967296.0;
            fr[j * N + i] = amplitude * std::cos(phase);
            fi[j * N + i] = amplitude * std::sin(phase);
        }
    }
    // Along x: G[j][x] = Σ_i F[j][i] e^(2πi·ix/N).
    std::vector<double> gr(N * N, 0.0), gi(N * N, 0.0);
    for (std::size_t j = 0; j < N; ++j) {
        for (std::size_t x = 0; x < N; ++x) {
            double re = 0.0, im = 0.0;
            for (std::size_t i = 0; i < N; ++i) {
                const std::size_t m = (i * x) % N;
                re += fr[j * N + i] * cosines[m] - fi[j * N + i] * sines[m];
                im += fr[j * N + i] * sines[m] + fi[j * N + i] * cosines[m];
            }
            gr[j * N + x] = re;
            gi[j * N + x] = im;
        }
    }
    // Along z, real part only.
    std::vector<double> heights(N * N, 0.0);
    double squares = 0.0;
    for (std::size_t z = 0; z < N; ++z) {
        for (std::size_t x = 0; x < N; ++x) {
            double re = 0.0;
            for (std::size_t j = 0; j < N; ++j) {
                const std::size_t m = (j * z) % N;
                re += gr[j * N + x] * cosines[m] - gi[j * N + x] * sines[m];
            }
            heights[z * N + x] = re;
            squares += re * re;
        }
    }
    const double scale = rms / std::sqrt(squares / double(N * N));
    for (double& h : heights) h *= scale;
    return heights;
}

std::vector<double> crop(const std::vector<double>& heights, int n, int width, int height)
{
    std::vector<double> out;
    for (int z = 0; z < height; ++z)
        for (int x = 0; x < width; ++x) out.push_back(heights[std::size_t(z) * std::size_t(n) + std::size_t(x)]);
    return out;
}

constexpr int N = 256;

TEST(HeightSpectrum, RecoversTheSynthesisedSlopeInBothBands)
{
    for (const double beta : {3.0, 5.0}) {
        const std::vector<double> surface = synthesize(N, beta, 7, 40.0);
        const HeightSpectrum periodic = measureHeightSpectrum(surface, N, N, 1.0);
        EXPECT_EQ(periodic.paddedWidth, N);
        EXPECT_EQ(periodic.paddedHeight, N);
        EXPECT_NEAR(periodic.fine.beta, beta, 0.3) << "periodic, fine";
        EXPECT_NEAR(periodic.coarse.beta, beta, 0.3) << "periodic, coarse";
        EXPECT_GE(periodic.fine.fit.points, 4u);
        EXPECT_GE(periodic.coarse.fit.points, 8u);
        EXPECT_EQ(periodic.fine.minWavelength, 2.5);
        EXPECT_EQ(periodic.fine.maxWavelength, 8.0);
        EXPECT_EQ(periodic.coarse.minWavelength, 8.0);
        EXPECT_NEAR(periodic.coarse.maxWavelength, 256.0 / 3.0, 1e-12);

        // A crop: not periodic (the Hann window's job), padded to 256 x 256.
        const int cw = 200, ch = 171;
        const HeightSpectrum cropped = measureHeightSpectrum(crop(surface, N, cw, ch), cw, ch, 1.0);
        EXPECT_EQ(cropped.paddedWidth, 256);
        EXPECT_EQ(cropped.paddedHeight, 256);
        EXPECT_NEAR(cropped.fine.beta, beta, 0.3) << "crop, fine";
        EXPECT_NEAR(cropped.coarse.beta, beta, 0.3) << "crop, coarse";
        EXPECT_NEAR(cropped.coarse.maxWavelength, 171.0 / 3.0, 1e-12);
        std::cout << "beta " << beta << ": periodic fine " << periodic.fine.beta << " coarse " << periodic.coarse.beta
                  << "; crop fine " << cropped.fine.beta << " coarse " << cropped.coarse.beta << '\n';
    }
}

TEST(HeightSpectrum, TiltIsDetrendedAndTheCellScalesWavelengthsOnly)
{
    const int cw = 150, ch = 130;
    std::vector<double> surface = crop(synthesize(N, 4.0, 11, 25.0), N, cw, ch);
    const HeightSpectrum plain = measureHeightSpectrum(surface, cw, ch, 1.0);
    std::vector<double> tilted = surface;
    for (int z = 0; z < ch; ++z)
        for (int x = 0; x < cw; ++x) tilted[std::size_t(z * cw + x)] += 500.0 + 0.7 * x - 1.3 * z;
    const HeightSpectrum tilt = measureHeightSpectrum(tilted, cw, ch, 1.0);
    EXPECT_NEAR(tilt.fine.beta, plain.fine.beta, 1e-6);
    EXPECT_NEAR(tilt.coarse.beta, plain.coarse.beta, 1e-6);

    const HeightSpectrum metres = measureHeightSpectrum(surface, cw, ch, 30.0);
    EXPECT_NEAR(metres.fine.beta, plain.fine.beta, 1e-9);
    EXPECT_NEAR(metres.coarse.beta, plain.coarse.beta, 1e-9);
    EXPECT_EQ(metres.fine.minWavelength, 75.0);
    EXPECT_EQ(metres.fine.maxWavelength, 240.0);
    EXPECT_NEAR(metres.coarse.maxWavelength, 1300.0, 1e-9);
}

TEST(HeightSpectrum, PlaneAndSmallGridsGiveNaN)
{
    constexpr int W = 40, H = 33;
    const std::vector<double> plane = tiltedPlane(W, H, 120.0, 0.3, 0.2);
    const HeightSpectrum flat = measureHeightSpectrum(plane, W, H, 2.0);
    EXPECT_TRUE(std::isnan(flat.fine.beta));
    EXPECT_TRUE(std::isnan(flat.coarse.beta));
    EXPECT_EQ(flat.fine.fit.points, 0u);

    // 20 x 20 cells: a third of the extent (6.7 cells) is under 8: no coarse band.
    const std::vector<double> small = crop(synthesize(N, 4.0, 3, 10.0), N, 20, 20);
    const HeightSpectrum s = measureHeightSpectrum(small, 20, 20, 1.0);
    EXPECT_TRUE(std::isfinite(s.fine.beta));
    EXPECT_TRUE(std::isnan(s.coarse.beta));
    EXPECT_EQ(s.coarse.fit.points, 0u);
    // 3 x 3 cells, padded to 4 x 4: the fine band (k 0.125..0.4 per cell)
    // holds k = 0.25 and 0.354, in two bins: a line, if not a meaningful one.
    const HeightSpectrum tiny = measureHeightSpectrum(crop(small, 20, 3, 3), 3, 3, 1.0);
    EXPECT_EQ(tiny.fine.fit.points, 2u);
    EXPECT_TRUE(std::isnan(tiny.coarse.beta));
    // 1 bin per decade: the fine band's half decade is one bin, fewer than 2.
    HeightSpectrumOptions options;
    options.binsPerDecade = 1.0;
    const HeightSpectrum oneBin = measureHeightSpectrum(small, 20, 20, 1.0, options);
    EXPECT_EQ(oneBin.fine.fit.points, 1u);
    EXPECT_TRUE(std::isnan(oneBin.fine.beta));
}

TEST(HeightSpectrum, SameBitsOnOneThread)
{
    const int cw = 230, ch = 190;
    const std::vector<double> surface = crop(synthesize(N, 3.5, 5, 30.0), N, cw, ch);
    const HeightSpectrum many = measureHeightSpectrum(surface, cw, ch, 4.0);
    HeightSpectrum one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = measureHeightSpectrum(surface, cw, ch, 4.0);
    }
    EXPECT_EQ(std::memcmp(&one.fine.beta, &many.fine.beta, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&one.coarse.beta, &many.coarse.beta, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&one.coarse.fit.rSquared, &many.coarse.fit.rSquared, sizeof(double)), 0);
}

TEST(HeightSpectrum, BadInputThrows)
{
    EXPECT_NE(errorOf([] { measureHeightSpectrum(std::vector<double>(6, 0.0), 2, 3, 1.0); }).find("3 x 3"),
              std::string::npos);
    std::vector<double> heights(16, 1.0);
    heights[5] = NAN;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, 1.0); }).find("(x 1, z 1)"), std::string::npos);
    heights[5] = 1.0;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, INFINITY); }).find("cell size"), std::string::npos);
    HeightSpectrumOptions options;
    options.fineMinWavelength = 1.5;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, 1.0, options); }).find("fineMinWavelength"),
              std::string::npos);
    options = {};
    options.fineMaxWavelength = 2.5;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, 1.0, options); }).find("fineMaxWavelength"),
              std::string::npos);
    options = {};
    options.coarseMaxFraction = 0.0;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, 1.0, options); }).find("coarseMaxFraction"),
              std::string::npos);
    options = {};
    options.binsPerDecade = 0.5;
    EXPECT_NE(errorOf([&] { measureHeightSpectrum(heights, 4, 4, 1.0, options); }).find("binsPerDecade"),
              std::string::npos);
    // 8193 x 8193 pads to 16384 x 16384: refused before the heights are read.
    EXPECT_NE(errorOf([&] { measureHeightSpectrum({}, 8193, 8193, 1.0); }).find("pads to 16384 x 16384, over 2^26"),
              std::string::npos);
}

} // namespace
