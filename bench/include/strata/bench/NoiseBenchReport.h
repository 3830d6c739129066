// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The table of `strata bench noise`: what terrain::measureNoiseThroughput
/// measured (points per second per core of each noise basis and its 5-octave
/// fBm, scalar path against block path), as Markdown after a few lines that
/// say how it was measured.

#include <strata/terrain/NoiseThroughput.h>

#include <string>
#include <vector>

namespace strata::bench {

/// The explanation and the table (M points/s), with the FastNoiseLite
/// columns when `options.fastNoiseLite` names a copy; the SIMD target in use
/// and the machine's targets are read from terrain/SimdTarget.h.
std::string formatNoiseThroughput(const std::vector<terrain::NoiseThroughput>& rows,
                                  const terrain::NoiseThroughputOptions& options);

} // namespace strata::bench
