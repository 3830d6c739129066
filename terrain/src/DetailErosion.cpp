// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#include <strata/terrain/DetailErosion.h>

#include "ShowValue.h"

#include <strata/DeterministicMath.h>
#include <strata/Error.h>
#include <strata/IntegerMath.h>

#include <algorithm>
#include <cmath>

namespace strata::terrain {

using detail::show;

namespace {

void check(bool ok, const char* key, double value, const char* range)
{
    if (!ok) {
        throw Error(ErrorKind::BadInput, std::string(key) + " = " + show(value) + " is out of range " + range,
                    {"", 0, key, ""});
    }
}

std::uint64_t mix(std::uint64_t h)
{
    h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
    return h ^ (h >> 31);
}

/// A hash of a world cell, a droplet number and the seed, as 64 bits.
std::uint64_t cellHash(std::int64_t x, std::int64_t z, std::uint64_t k, std::uint64_t seed)
{
    std::uint64_t h = mix(seed + 0x9E3779B97F4A7C15ull);
    h = mix(h ^ std::uint64_t(x));
    h = mix(h ^ std::uint64_t(z) * 0xD6E8FEB86659FD93ull);
    return mix(h ^ k);
}

double unit(std::uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

/// The patch as a bilinear surface over its corners.
struct Patch
{
    std::vector<double>& h;
    int w, hgt;

    double& at(int i, int j) { return h[std::size_t(j) * std::size_t(w) + std::size_t(i)]; }

    /// Height and gradient (metres per cell) at (x, z) inside [0, w−1) × [0, hgt−1).
    void sample(double x, double z, double& height, double& gx, double& gz)
    {
        const int i = int(x), j = int(z);
        const double fx = x - i, fz = z - j;
        const double h00 = at(i, j), h10 = at(i + 1, j), h01 = at(i, j + 1), h11 = at(i + 1, j + 1);
        height = (h00 * (1 - fx) + h10 * fx) * (1 - fz) + (h01 * (1 - fx) + h11 * fx) * fz;
        gx = (h10 - h00) * (1 - fz) + (h11 - h01) * fz;
        gz = (h01 - h00) * (1 - fx) + (h11 - h10) * fx;
    }

    /// Adds `amount` metres at (x, z), split over its four corners bilinearly.
    void add(double x, double z, double amount)
    {
        const int i = int(x), j = int(z);
        const double fx = x - i, fz = z - j;
        at(i, j) += amount * (1 - fx) * (1 - fz);
        at(i + 1, j) += amount * fx * (1 - fz);
        at(i, j + 1) += amount * (1 - fx) * fz;
        at(i + 1, j + 1) += amount * fx * fz;
    }

    bool inside(double x, double z) const { return x >= 0.0 && z >= 0.0 && x < w - 1 && z < hgt - 1; }
};

void runDroplet(Patch& patch, double x, double z, const DetailErosionOptions& o)
{
    double dx = 0.0, dz = 0.0, speed = 1.0, water = 1.0, sediment = 0.0;
    const double minDrop = 0.01 * o.cellSize;
    for (int step = 0; step < o.dropletSteps; ++step) {
        double h, gx, gz;
        patch.sample(x, z, h, gx, gz);
        dx = dx * o.inertia - gx * (1.0 - o.inertia);
        dz = dz * o.inertia - gz * (1.0 - o.inertia);
        const double length = dmath::hypot(dx, dz);
        if (!(length > 1e-12)) break; // a flat: the droplet soaks in
        dx /= length;
        dz /= length;
        const double nx = x + dx, nz = z + dz;
        if (!patch.inside(nx, nz)) break; // leaves the patch with its sediment
        double hn, unusedX, unusedZ;
        patch.sample(nx, nz, hn, unusedX, unusedZ);
        const double drop = h - hn; // > 0 downhill
        const double capacity = std::max(drop, minDrop) * speed * water * o.capacity;
        if (sediment > capacity || drop < 0.0) {
            // Uphill: fill the pit behind; else drop part of the excess.
            const double laid = drop < 0.0 ? std::min(-drop, sediment) : (sediment - capacity) * o.deposition;
            sediment -= laid;
            patch.add(x, z, laid);
        } else {
            const double taken = std::min((capacity - sediment) * o.erosion, drop);
            sediment += taken;
            patch.add(x, z, -taken);
        }
        speed = std::sqrt(std::max(0.0, speed * speed + 4.0 * drop / o.cellSize));
        water *= 1.0 - o.evaporation;
        x = nx;
        z = nz;
    }
}

/// Jacobi sweeps: each cell steeper than the talus slope towards a 4-neighbour
/// gives it a quarter of the excess difference, all read from the previous sweep.
void relaxTalus(std::vector<double>& h, int w, int hgt, const DetailErosionOptions& o)
{
    const double talus = dmath::tanDegrees(o.talusAngle) * o.cellSize;
    std::vector<double> change(h.size());
    for (int sweep = 0; sweep < o.talusSweeps; ++sweep) {
        std::fill(change.begin(), change.end(), 0.0);
        for (int j = 0; j < hgt; ++j) {
            for (int i = 0; i < w; ++i) {
                const std::size_t c = std::size_t(j) * std::size_t(w) + std::size_t(i);
                // Each pair once: the right and lower neighbours.
                if (i + 1 < w) {
                    const double d = h[c] - h[c + 1];
                    if (std::abs(d) > talus) {
                        const double moved = 0.25 * (std::abs(d) - talus) * (d > 0.0 ? 1.0 : -1.0);
                        change[c] -= moved;
                        change[c + 1] += moved;
                    }
                }
                if (j + 1 < hgt) {
                    const std::size_t below = c + std::size_t(w);
                    const double d = h[c] - h[below];
                    if (std::abs(d) > talus) {
                        const double moved = 0.25 * (std::abs(d) - talus) * (d > 0.0 ? 1.0 : -1.0);
                        change[c] -= moved;
                        change[below] += moved;
                    }
                }
            }
        }
        for (std::size_t c = 0; c < h.size(); ++c) h[c] += change[c];
    }
}

} // namespace

void checkDetailErosionOptions(const DetailErosionOptions& o)
{
    check(std::isfinite(o.cellSize) && o.cellSize > 0.0, "cell_size", o.cellSize, "(0, inf)");
    check(o.dropletsPerCell >= 0.0 && o.dropletsPerCell <= 8.0, "droplets_per_cell", o.dropletsPerCell, "[0, 8]");
    check(o.dropletSteps >= 1 && o.dropletSteps <= 256, "droplet_steps", o.dropletSteps, "[1, 256]");
    check(o.inertia >= 0.0 && o.inertia <= 1.0, "inertia", o.inertia, "[0, 1]");
    check(std::isfinite(o.capacity) && o.capacity >= 0.0, "capacity", o.capacity, "[0, inf)");
    check(o.erosion >= 0.0 && o.erosion <= 1.0, "erosion", o.erosion, "[0, 1]");
    check(o.deposition >= 0.0 && o.deposition <= 1.0, "deposition", o.deposition, "[0, 1]");
    check(o.evaporation >= 0.0 && o.evaporation <= 1.0, "evaporation", o.evaporation, "[0, 1]");
    check(o.talusAngle >= 1.0 && o.talusAngle <= 89.0, "talus_angle", o.talusAngle, "[1, 89]");
    check(o.talusSweeps >= 0 && o.talusSweeps <= 256, "talus_sweeps", o.talusSweeps, "[0, 256]");
    check(std::isfinite(o.maxDepth) && o.maxDepth > 0.0, "max_depth", o.maxDepth, "(0, inf)");
}

void erodeDetail(std::vector<double>& heights, int width, int height, std::int64_t originX, std::int64_t originZ,
                 std::uint64_t seed, const DetailErosionOptions& o)
{
    checkDetailErosionOptions(o);
    if (width < 2 || height < 2 || heights.size() != std::size_t(width) * std::size_t(height)) {
        throw Error(ErrorKind::BadInput, "detail erosion: " + std::to_string(heights.size()) + " heights for " + std::to_string(width) +
                    "x" + std::to_string(height) + " corners (at least 2x2)");
    }
    const std::vector<double> original = heights;
    Patch patch{heights, width, height};
    const int whole = floorToInt<int>(o.dropletsPerCell);
    const double fraction = o.dropletsPerCell - whole;
    for (int j = 0; j + 1 < height; ++j) {
        for (int i = 0; i + 1 < width; ++i) {
            const std::int64_t wx = originX + i, wz = originZ + j;
            const int count = whole + (unit(cellHash(wx, wz, 0xFFFF, seed)) < fraction ? 1 : 0);
            for (int k = 0; k < count; ++k) {
                const std::uint64_t bits = cellHash(wx, wz, std::uint64_t(k), seed);
                // i + unit() can round up to i + 1 (unit() < 1, but the sum
                // rounds to even): a droplet there would read past the row.
                const double x = std::min(i + unit(bits), std::nextafter(double(i + 1), 0.0));
                const double z = std::min(j + unit(mix(bits)), std::nextafter(double(j + 1), 0.0));
                runDroplet(patch, x, z, o);
            }
        }
    }
    relaxTalus(heights, width, height, o);
    for (std::size_t c = 0; c < heights.size(); ++c) {
        heights[c] = original[c] + std::clamp(heights[c] - original[c], -o.maxDepth, o.maxDepth);
    }
}

} // namespace strata::terrain
