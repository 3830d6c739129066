// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/HeightSpectrum.h>

#include "HeightGridChecks.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/Format.h>
#include <strata/IntegerMath.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace strata::terrain {

namespace {

constexpr std::size_t MAX_PADDED_CELLS = std::size_t(1) << 26;

struct Complex
{
    double re = 0.0, im = 0.0;
};

/// An in-place radix-2 decimation-in-time FFT of n = 2^m values (forward,
/// e^(−2πi·jk/n), unnormalised). Own code rather than a dependency: the
/// spectrum is a bench statistic of grids of at most a few million cells.
class Fft
{
public:
    explicit Fft(std::size_t n) : mN(n), mReverse(n), mTwiddle(n / 2)
    {
        int bits = 0;
        while ((std::size_t(1) << bits) < n) ++bits;
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t r = 0;
            for (int b = 0; b < bits; ++b) r |= ((i >> b) & 1) << (bits - 1 - b);
            mReverse[i] = r;
        }
        for (std::size_t k = 0; k < n / 2; ++k) {
            // −360°·k/n exactly (n is a power of two): exact at the quarter turns.
            dmath::sinCosDegrees(-360.0 * double(k) / double(n), mTwiddle[k].im, mTwiddle[k].re);
        }
    }

    void transform(Complex* a) const
    {
        for (std::size_t i = 0; i < mN; ++i) {
            if (i < mReverse[i]) std::swap(a[i], a[mReverse[i]]);
        }
        for (std::size_t length = 2; length <= mN; length *= 2) {
            const std::size_t half = length / 2, step = mN / length;
            for (std::size_t start = 0; start < mN; start += length) {
                for (std::size_t j = 0; j < half; ++j) {
                    const Complex w = mTwiddle[j * step];
                    Complex& u = a[start + j];
                    Complex& v = a[start + j + half];
                    const Complex t{v.re * w.re - v.im * w.im, v.re * w.im + v.im * w.re};
                    v = {u.re - t.re, u.im - t.im};
                    u = {u.re + t.re, u.im + t.im};
                }
            }
        }
    }

private:
    std::size_t mN;
    std::vector<std::size_t> mReverse;
    std::vector<Complex> mTwiddle;
};

std::size_t powerOfTwoAtLeast(std::size_t n)
{
    std::size_t p = 1;
    while (p < n) p *= 2;
    return p;
}

/// Hann window of n samples, w(i) = sin²(π(i + ½)/n): no zero weights at the ends.
std::vector<double> hann(std::size_t n)
{
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i) {
        double s = 0.0, c = 0.0;
        dmath::sinCosDegrees(180.0 * (double(i) + 0.5) / double(n), s, c);
        w[i] = s * s;
    }
    return w;
}

void checkOptions(const HeightSpectrumOptions& o)
{
    const auto bad = [](const std::string& name, double value, const std::string& range) {
        throw Error(ErrorKind::BadInput,
                    "height spectrum: " + name + " = " + formatNumber(value) + " must be " + range);
    };
    if (!(o.fineMinWavelength >= 2.0) || !std::isfinite(o.fineMinWavelength))
        bad("fineMinWavelength", o.fineMinWavelength, "a finite number of cells >= 2");
    if (!(o.fineMaxWavelength > o.fineMinWavelength) || !std::isfinite(o.fineMaxWavelength))
        bad("fineMaxWavelength", o.fineMaxWavelength, "a finite number of cells > fineMinWavelength");
    if (!(o.coarseMaxFraction > 0.0 && o.coarseMaxFraction <= 1.0))
        bad("coarseMaxFraction", o.coarseMaxFraction, "in (0, 1]");
    if (!(o.binsPerDecade >= 1.0 && o.binsPerDecade <= 100.0)) bad("binsPerDecade", o.binsPerDecade, "in [1, 100]");
}

/// The band's bins over the wavenumbers (cycles per cell) in [1/maxCells, 1/minCells].
struct BandBins
{
    double logLow = 0.0, logHigh = 0.0; ///< log k·cell at the band's ends
    int count = 0;                      ///< bins (0: an empty band)
    std::vector<double> power, logK;    ///< sums per bin
    std::vector<std::size_t> members;

    BandBins(double minCells, double maxCells, double binsPerDecade)
    {
        if (!(maxCells > minCells)) return;
        logLow = dmath::log(1.0 / maxCells);
        logHigh = dmath::log(1.0 / minCells);
        const double decades = dmath::log10(maxCells / minCells);
        count = std::max(1, ceilToInt<int>(decades * binsPerDecade - 1e-9));
        power.assign(std::size_t(count), 0.0);
        logK.assign(std::size_t(count), 0.0);
        members.assign(std::size_t(count), 0);
    }

    void add(double logKCells, double value)
    {
        if (count == 0 || logKCells < logLow || logKCells > logHigh) return;
        int b = int((logKCells - logLow) / (logHigh - logLow) * double(count));
        b = std::clamp(b, 0, count - 1);
        power[std::size_t(b)] += value;
        logK[std::size_t(b)] += logKCells;
        ++members[std::size_t(b)];
    }

    /// The fit over the bins (k in cycles per metre: log k = log k·cell − log cell).
    SpectralBand fit(double minCells, double maxCells, double cellSize, bool plane) const
    {
        SpectralBand band;
        band.minWavelength = minCells * cellSize;
        band.maxWavelength = maxCells * cellSize;
        std::vector<double> x, y;
        if (!plane) {
            for (std::size_t b = 0; b < std::size_t(count); ++b) {
                if (members[b] == 0 || !(power[b] > 0.0)) continue;
                x.push_back(logK[b] / double(members[b]) - dmath::log(cellSize));
                y.push_back(dmath::log(power[b] / double(members[b])));
            }
        }
        band.fit = detail::fitLogLog(x, y);
        band.beta = -band.fit.exponent;
        return band;
    }
};

} // namespace

HeightSpectrum measureHeightSpectrum(const std::vector<double>& heights, int width, int height, double cellSize,
                                     const HeightSpectrumOptions& options)
{
    // The padded size first: it depends on the sizes only, and is refused
    // before the heights are read.
    const std::size_t W = std::size_t(std::max(width, 0)), H = std::size_t(std::max(height, 0));
    const std::size_t PW = powerOfTwoAtLeast(W), PH = powerOfTwoAtLeast(H);
    if (PW > MAX_PADDED_CELLS / PH)
        throw Error(ErrorKind::BadInput, "height spectrum: the grid of " + std::to_string(width) + " x " +
                                             std::to_string(height) + " cells pads to " + std::to_string(PW) + " x " +
                                             std::to_string(PH) + ", over 2^26 cells (1 GiB): measure a coarser grid");
    detail::checkHeightGrid("height spectrum", heights, width, height, cellSize);
    checkOptions(options);

    // 1. The least-squares plane: on a full grid the normal equations
    // separate in centred coordinates.
    double mean = 0.0, largest = 0.0;
    for (double h : heights) {
        mean += h;
        largest = std::max(largest, std::abs(h));
    }
    mean /= double(heights.size());
    const double cx = 0.5 * double(W - 1), cz = 0.5 * double(H - 1);
    double sxz = 0.0, szz = 0.0, sxx = 0.0, sz2 = 0.0;
    for (std::size_t z = 0; z < H; ++z) {
        for (std::size_t x = 0; x < W; ++x) {
            const double h = heights[z * W + x] - mean;
            sxz += (double(x) - cx) * h;
            szz += (double(z) - cz) * h;
        }
    }
    for (std::size_t x = 0; x < W; ++x) sxx += (double(x) - cx) * (double(x) - cx);
    for (std::size_t z = 0; z < H; ++z) sz2 += (double(z) - cz) * (double(z) - cz);
    const double slopeX = sxz / (sxx * double(H)), slopeZ = szz / (sz2 * double(W));

    // 2. Detrended, windowed, into the zero-padded grid.
    const std::vector<double> windowX = hann(W), windowZ = hann(H);
    std::vector<Complex> grid(PW * PH);
    double squares = 0.0;
    for (std::size_t z = 0; z < H; ++z) {
        for (std::size_t x = 0; x < W; ++x) {
            const double r = heights[z * W + x] - mean - slopeX * (double(x) - cx) - slopeZ * (double(z) - cz);
            squares += r * r;
            grid[z * PW + x].re = r * windowX[x] * windowZ[z];
        }
    }
    const bool plane = std::sqrt(squares / double(heights.size())) <= std::max(1e-9, 1e-12 * largest);

    // 3. Rows (only those holding data), then columns.
    const Fft rowFft(PW), columnFft(PH);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, H), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t z = range.begin(); z != range.end(); ++z) rowFft.transform(grid.data() + z * PW);
    });
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, PW), [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<Complex> column(PH);
        for (std::size_t x = range.begin(); x != range.end(); ++x) {
            for (std::size_t z = 0; z < PH; ++z) column[z] = grid[z * PW + x];
            columnFft.transform(column.data());
            for (std::size_t z = 0; z < PH; ++z) grid[z * PW + x] = column[z];
        }
    });

    // 4. Radial bins, in a fixed order (rows, then columns).
    const double fineMin = options.fineMinWavelength, fineMax = options.fineMaxWavelength;
    const double coarseMax = options.coarseMaxFraction * double(std::min(W, H));
    BandBins fine(fineMin, fineMax, options.binsPerDecade), coarse(fineMax, coarseMax, options.binsPerDecade);
    for (std::size_t j = 0; j < PH; ++j) {
        const double kz = (j <= PH / 2 ? double(j) : double(j) - double(PH)) / double(PH);
        for (std::size_t i = 0; i < PW; ++i) {
            if (i == 0 && j == 0) continue;
            const double kx = (i <= PW / 2 ? double(i) : double(i) - double(PW)) / double(PW);
            const double logK = dmath::log(dmath::hypot(kx, kz)); // cycles per cell
            const Complex f = grid[j * PW + i];
            const double power = f.re * f.re + f.im * f.im;
            fine.add(logK, power);
            coarse.add(logK, power);
        }
    }
    HeightSpectrum s;
    s.paddedWidth = int(PW);
    s.paddedHeight = int(PH);
    s.fine = fine.fit(fineMin, fineMax, cellSize, plane);
    s.coarse = coarse.fit(fineMax, coarseMax, cellSize, plane);
    return s;
}

} // namespace strata::terrain
