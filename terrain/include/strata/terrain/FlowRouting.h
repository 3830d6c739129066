// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Flow routing on a regular height grid, the way landscape evolution models
/// and geomorphometry route water: depressions filled by priority-flood with
/// an epsilon gradient (Barnes, Lehman and Mulla 2014), so every cell drains
/// to the grid's edge; D8 steepest-descent receivers on the filled surface; a
/// topological order (every cell after its receiver); drainage area.
///
/// Grids are row-major, `values[z * width + x]`, cell size `cellSize`
/// metres on both axes. The outer ring of cells is the base level: water
/// leaves the grid there. Everything here is single-threaded and exact:
/// the same input gives the same bits (ties broken by cell index).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace strata::terrain {

/// The result of routeFlow().
struct FlowRouting
{
    int width = 0, height = 0;
    /// The surface with every depression filled up to its spill level and
    /// raised by the smallest representable steps towards its outlet, so
    /// each cell not on the edge has a strictly lower neighbour: >= the input.
    std::vector<double> filled;
    /// Per cell: the index of the neighbour (of 8) it drains to, the steepest
    /// descent on `filled` (drop over distance, diagonal distance √2); edge
    /// cells drain to themselves.
    std::vector<std::uint32_t> receiver;
    /// Every cell once, each after its receiver (so a downstream-to-upstream
    /// sweep visits receivers first; the reverse visits donors first): the
    /// edge cells in index order, then the interior cells in non-decreasing
    /// `filled` order (the priority-flood's pop order).
    std::vector<std::uint32_t> order;
};

/// Fills, routes and orders `heights` (width × height cells, both >= 1,
/// at most 2³² − 1 cells; finite values; cellSize finite and > 0, metres).
/// A grid 1 or 2 cells wide or high is all edge. O(n log n) for the priority
/// queue (about 0.14 s for 1024 × 1024 cells at -O2 on one core). Throws
/// strata::Error for a bad size, a wrong number of heights, a bad cell size
/// or a non-finite height (naming the cell).
FlowRouting routeFlow(const std::vector<double>& heights, int width, int height, double cellSize);

/// The same into `into`, reusing its buffers: for loops that route a grid
/// of one size again and again (the landscape evolution routes every step).
void routeFlow(const std::vector<double>& heights, int width, int height, double cellSize, FlowRouting& into);

/// Drainage area in square metres per cell: its own cell (cellSize²) plus
/// everything that drains through it. The edge cells' areas add up to the
/// grid's area. O(n).
std::vector<double> drainageArea(const FlowRouting& routing, double cellSize);
/// The same into `area`, reusing its buffer.
void drainageArea(const FlowRouting& routing, double cellSize, std::vector<double>& area);

/// Drainage area in square metres per cell, routed in multiple flow
/// directions (Freeman 1991; Holmgren 1994): each interior cell passes its
/// area to every neighbour lower on `filled`, in proportion to
/// (drop / distance)^exponent, donors before receivers (the reverse of
/// `order`). On a plane the flow follows the true gradient instead of D8's
/// 45° steps (no staircase rivers in the masks); a larger exponent
/// concentrates it (1: Freeman's diffuse flow; 4, the default: channels
/// about two cells wide). Edge cells keep what reaches them (their areas
/// add up to the grid's area, up to rounding). O(n); the same bits for
/// the same input (fixed neighbour order, no fused multiply-adds).
/// `exponent` is 1..8.
std::vector<double> multipleFlowArea(const FlowRouting& routing, double cellSize, int exponent = 4);

/// The distance to the receiver in metres: cellSize, or cellSize·√2 on a
/// diagonal; 0 for a cell that is its own receiver.
double receiverDistance(const FlowRouting& routing, std::size_t cell, double cellSize);

} // namespace strata::terrain
