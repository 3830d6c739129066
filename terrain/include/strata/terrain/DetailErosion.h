// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// Erosion detail at the voxel scale on one patch of cells: water droplets
/// that pick up and drop sediment (H. Beyer's particle model, 2015) and
/// thermal (talus) relaxation of slopes steeper than the angle of repose.
///
/// A patch is a pure function of its heights and the world cells it covers:
/// each droplet starts at a position hashed from its world cell and the
/// seed, droplets run one after another in row order, and the talus sweeps
/// are Jacobi steps (every cell reads the previous sweep). No threads, no
/// atomics: the same bits wherever and whenever a patch is computed.
/// DetailErodedHeightfield.h tiles the world with such patches.

#include <cstdint>
#include <vector>

namespace strata::terrain {

struct DetailErosionOptions
{
    double cellSize = 1.0;        ///< metres, > 0
    double dropletsPerCell = 0.6; ///< droplets started per cell of the patch, 0..8
    int dropletSteps = 24;        ///< cells a droplet may travel, 1..256
    double inertia = 0.3;         ///< 0..1: how much a droplet keeps its direction
    double capacity = 4.0;        ///< sediment a unit of water carries per unit of drop and speed, >= 0
    double erosion = 0.3;         ///< 0..1: fraction of the spare capacity taken per step
    double deposition = 0.3;      ///< 0..1: fraction of the excess sediment dropped per step
    double evaporation = 0.04;    ///< 0..1: water lost per step
    double talusAngle = 40.0;     ///< degrees, 1..89: slopes steeper than this slide
    int talusSweeps = 8;          ///< 0..256
    double maxDepth = 1.5;        ///< metres, > 0: the change is clamped to ±maxDepth
};

/// Erodes `heights` (width × height corners, row-major; corner (i, j) is the
/// world cell (originX + i, originZ + j)) in place; the change of every
/// corner is clamped to ±maxDepth. Droplets start in every cell and stop at
/// the patch's edge (their sediment leaves with them). Throws strata::Error
/// naming the option when one is out of range.
void erodeDetail(std::vector<double>& heights, int width, int height, std::int64_t originX, std::int64_t originZ,
                 std::uint64_t seed, const DetailErosionOptions& options);

/// Throws strata::Error naming the first option out of range (keys as the
/// scene names them: droplets_per_cell, droplet_steps, ...).
void checkDetailErosionOptions(const DetailErosionOptions& options);

} // namespace strata::terrain
