// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Scatter plots with axes, ticks, labels and the Pareto front, drawn into
/// an 8-bit image with the built-in bitmap font (PlotFont.h): the
/// pareto.png of `strata bench`.

#include <strata/render/Image.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::scene {

struct PlotPoint
{
    double x = 0.0, y = 0.0;            ///< data units; non-finite points are skipped
    std::string label;                  ///< drawn beside the marker ("" = none)
    std::array<std::uint8_t, 3> color{40, 90, 200}; ///< sRGB marker colour
    bool large = false;                 ///< a larger marker (presets)
};

struct PlotPanel
{
    std::string title, xLabel, yLabel;
    bool logX = false, logY = false;    ///< log10 axes (values <= 0 are skipped)
    bool higherIsBetter = false;        ///< y: the front maximises (PSNR) instead of minimising (error)
    std::vector<PlotPoint> points;
};

/// Draws the panels side by side, each `panelWidth` × `height` pixels, on
/// white: frame, ticks with values (1-2-5 steps, or decades on log axes),
/// axis labels, title, markers with labels, and the Pareto front (points no
/// other point beats on both time (x, lower better) and y) as a line.
/// Deterministic. O(points² + pixels).
render::Image drawPlot(const std::vector<PlotPanel>& panels, int panelWidth, int height);

/// The indices of the Pareto-optimal points of `panel` (lower x, and lower
/// or higher y per higherIsBetter), sorted by x.
std::vector<std::size_t> paretoFront(const PlotPanel& panel);

} // namespace strata::scene
