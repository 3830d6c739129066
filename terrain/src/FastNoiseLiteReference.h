// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Internal: FastNoiseLite (Jordan Peck's single-header noise library, the
/// usual yardstick for CPU noise) compiled from a copy the user names, so
/// `strata bench noise --fastnoise-lite PATH` measures it beside Strata's
/// noise in one run, on the same points. Nothing of it is vendored: the
/// header is compiled at run time with -O3 -march=native into a shared
/// object in a temporary folder and loaded with dlopen.

#include <cstddef>
#include <memory>
#include <string>

namespace strata::terrain::detail {

/// The bases both libraries have: Strata's gradient, simplex, value and
/// cellular F1/F2 against FastNoiseLite's Perlin, OpenSimplex2, Value and
/// Cellular (Euclidean distance, Distance / Distance2).
enum class ReferenceBasis
{
    GRADIENT,
    SIMPLEX,
    VALUE,
    CELLULAR_F1,
    CELLULAR_F2,
};

class FastNoiseLiteReference
{
public:
    /// Compiles `header` (FastNoiseLite.h, the C++ version) with the C++
    /// compiler in $CXX, else the one Strata was built with, else `c++`.
    /// Throws Error(BadInput) naming the path when the file does not exist or
    /// does not compile as FastNoiseLite (with the compiler's first lines),
    /// Error(Io) when no temporary folder or compiler can be used.
    explicit FastNoiseLiteReference(const std::string& header);
    ~FastNoiseLiteReference();
    FastNoiseLiteReference(const FastNoiseLiteReference&) = delete;
    FastNoiseLiteReference& operator=(const FastNoiseLiteReference&) = delete;

    /// FastNoiseLite's GetNoise at n points (frequency 1, seed 7; z unused in
    /// 2D, where (x, z) is the point), as 5-octave fBm (lacunarity 2, gain
    /// 0.5) when octaves > 1.
    void fill(ReferenceBasis basis, int octaves, int dimensions, const float* x, const float* y, const float* z,
              std::size_t n, float* out) const;

    /// The compiler command line that built it (for the report).
    const std::string& command() const { return mCommand; }

private:
    struct Library;
    std::unique_ptr<Library> mLibrary;
    std::string mCommand;
};

} // namespace strata::terrain::detail
