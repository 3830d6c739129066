// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Landscape evolution on a regular grid: uplift, stream-power incision
/// solved implicitly in O(n) per step along the flow tree (Braun and
/// Willett 2013), depressions routed by priority-flood so lakes fill with
/// sediment and spill (Barnes et al. 2014; FlowRouting.h), and hillslope
/// diffusion. Physical units: metres, years.
///
///   ∂h/∂t = U·u(x) − K·A^m·S^n + D·∇²h
///
/// The grid's outer ring is the base level (fixed: rivers leave there).
/// Single-threaded except the diffusion sweeps, which split rows over
/// threads and write each cell once: the same bits on any thread count.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace strata::terrain {

struct StreamPowerOptions
{
    double cellSize = 8.0;       ///< metres, > 0
    double years = 1.0e6;        ///< simulated time, >= 0
    double timeStep = 2.0e4;     ///< years per implicit step, > 0 (the last step is shortened)
    double uplift = 5.0e-4;      ///< U, metres per year (times the uplift map where given)
    double erodibility = 4.0e-6; ///< K, m^(1−2m) per year
    double areaExponent = 0.45;  ///< m
    double slopeExponent = 1.0;  ///< n, > 0 (n = 1 is solved exactly, else by Newton steps)
    double diffusivity = 0.02;   ///< D, m² per year (hillslope creep), >= 0
};

/// The most implicit steps one run may take (ceil(years / timeStep)): each
/// step routes the whole grid, so more cannot finish in any sensible time,
/// and the count must fit an int. Refused before any work.
inline constexpr double MAX_EROSION_STEPS = 1e6;

/// What a run leaves, per cell (row-major, width × height).
struct StreamPowerResult
{
    int width = 0, height = 0;
    std::vector<double> heights;     ///< metres
    std::vector<double> area;        ///< drainage area at the end, m² (D8: what the law eroded with)
    /// The same water routed in multiple flow directions (multipleFlowArea,
    /// exponent 4), m²: the flow and water masks, which D8 would draw as 45°
    /// staircases.
    std::vector<double> flowArea;
    std::vector<double> wear;        ///< total depth eroded, metres (>= 0)
    std::vector<double> sediment;    ///< sediment lying on the cell at the end, metres (>= 0)
    std::vector<double> lakeDepth;   ///< depth of the filled lake at the end, metres (>= 0)
    /// Sediment budget, cubic metres: eroded = deposited + carriedOut up to
    /// rounding (diffusion moves material but is counted apart: its mass is
    /// conserved inside, and what it moves across the edge is in diffusedOut).
    double eroded = 0.0, deposited = 0.0, carriedOut = 0.0, diffusedOut = 0.0;
    int steps = 0;
};

/// Evolves `heights` (width × height cells, both >= 1). `upliftMap` is empty
/// (uniform uplift) or one factor per cell. `progress` (may be empty) gets
/// the done fraction after each step; returning false stops with
/// strata::Error("erosion interrupted"). Throws strata::Error for options out
/// of range (naming the option; more than MAX_EROSION_STEPS steps names
/// years and time_step) and for a wrong-sized input.
StreamPowerResult evolveLandscape(std::vector<double> heights, int width, int height,
                                  const std::vector<double>& upliftMap, const StreamPowerOptions& options,
                                  const std::function<bool(double)>& progress = {});

} // namespace strata::terrain
