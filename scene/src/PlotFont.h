// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The bitmap font of the bench plots (ParetoPlot.h): printable ASCII in
/// fixed 8×14 cells, 4-bit coverage.

namespace strata::scene {

inline constexpr int GLYPH_WIDTH = 8;    ///< pixels per character cell, also the advance
inline constexpr int GLYPH_HEIGHT = 14;  ///< pixels per cell
inline constexpr int GLYPH_BASELINE = 11; ///< row of the baseline inside the cell

/// Coverage 0..15 of pixel (x, y) of character `c`'s cell (y down from the
/// cell's top); characters outside 32..126 draw as '?', pixels outside the
/// cell are 0.
int glyphCoverage(char c, int x, int y);

} // namespace strata::scene
