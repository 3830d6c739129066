// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// A scene's density field over NumPy arrays, through the block path
// (DensityField::densities: one virtual call per node and block of 512
// points, SIMD where the node has it), blocks spread over the cores.

#include "Bindings.h"

#include <strata/Error.h>
#include <strata/terrain/DensityField.h>
#include <strata/terrain/NodeRegistry.h>
#include <strata/Format.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace strata::python {

namespace {

using terrain::DensityField;
using FieldPtr = std::shared_ptr<DensityField>;

/// The sampler's block: one 8³ leaf of voxels.
constexpr std::size_t BLOCK = 512;

template <class Body> void inArena(int threads, const Body& body)
{
    if (threads < 0) throw Error(ErrorKind::BadInput, "threads must be >= 0 (0: all cores)", {"", 0, "threads"});
    tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
    arena.execute(body);
}

/// Spreads the low 21 bits of v over every third bit (a Morton code's axis).
std::uint64_t spreadBits(std::uint64_t v)
{
    v &= 0x1fffffu;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

/// The rows in Z order (Morton order over the points' bounding box, 2^21
/// steps an axis), ties by row. Scattered points in row order make every
/// block span the whole scene, so no node can skip work for it and cached
/// structures (the worm caves' regions) are rebuilt at nearly every point;
/// in Z order a block is a small box. Values do not depend on the order:
/// each point's density is the same bits in any block.
std::vector<std::uint32_t> zOrder(const double* xyz, std::size_t count)
{
    if (count == 0) return {};
    std::array<double, 3> lo{xyz[0], xyz[1], xyz[2]}, hi = lo;
    for (std::size_t i = 0; i < count; ++i) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], xyz[3 * i + a]);
            hi[a] = std::max(hi[a], xyz[3 * i + a]);
        }
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
    const double scale = extent > 0.0 ? double((1u << 21) - 1) / extent : 0.0;
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::uint64_t key = 0;
        for (int a = 0; a < 3; ++a) key |= spreadBits(std::uint64_t((xyz[3 * i + a] - lo[a]) * scale)) << a;
        keyed[i] = {key, std::uint32_t(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    std::vector<std::uint32_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = keyed[i].second;
    return order;
}

/// Densities of rows of (x, y, z), `count` of them, into `out`, evaluated
/// in blocks of nearby points (zOrder).
void evaluateRows(const DensityField& field, const double* xyz, std::size_t count, double* out, int threads)
{
    if (count > std::size_t(UINT32_MAX)) {
        throw Error(ErrorKind::BadInput, "points: at most " + std::to_string(UINT32_MAX) + " rows a call", {"", 0, "points"});
    }
    const std::vector<std::uint32_t> order = zOrder(xyz, count);
    const std::size_t blocks = (count + BLOCK - 1) / BLOCK;
    inArena(threads, [&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, blocks), [&](const tbb::blocked_range<std::size_t>& r) {
            std::array<double, BLOCK> x, y, z, values;
            for (std::size_t b = r.begin(); b != r.end(); ++b) {
                const std::size_t first = b * BLOCK, n = std::min(BLOCK, count - first);
                for (std::size_t i = 0; i < n; ++i) {
                    const std::size_t row = order[first + i];
                    x[i] = xyz[3 * row];
                    y[i] = xyz[3 * row + 1];
                    z[i] = xyz[3 * row + 2];
                }
                terrain::PointBlock block{x.data(), y.data(), z.data(), n, {}};
                block.box = terrain::spannedBox(block);
                field.densities(block, values.data());
                for (std::size_t i = 0; i < n; ++i) out[order[first + i]] = values[i];
            }
        });
    });
}

py::array_t<double> evaluate(const FieldPtr& field, const py::array_t<double, py::array::c_style | py::array::forcecast>& points,
                             int threads)
{
    if (points.ndim() != 2 || points.shape(1) != 3) {
        throw Error(ErrorKind::BadInput,
                    "points must be an (N, 3) array of x, y, z in metres, not shape " +
                        std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(points.shape(), points.shape() + points.ndim()))))),
                    {"", 0, "points"});
    }
    const std::size_t count = std::size_t(points.shape(0));
    py::array_t<double> out(count);
    const double* in = points.data();
    // NaN reached int(NaN) in the heightfields' column lookups (undefined
    // behaviour): refuse it, and coordinates beyond any scene's, by row.
    for (std::size_t i = 0; i < 3 * count; ++i) {
        if (!(std::abs(in[i]) <= terrain::HUGE_LENGTH)) {
            const std::string at = "points[" + std::to_string(i / 3) + ", " + std::to_string(i % 3) + "]";
            throw Error(ErrorKind::BadInput,
                        at + " = " + formatNumber(in[i]) + " must be a finite number of metres within ±" +
                            formatNumber(terrain::HUGE_LENGTH),
                        {"", 0, at, formatNumber(in[i])});
        }
    }
    double* values = out.mutable_data();
    {
        py::gil_scoped_release release;
        evaluateRows(*field, in, count, values, threads);
    }
    return out;
}

/// The field on a lattice: origin + spacing · (i, j, k) for i < nx, j < ny,
/// k < nz, as an (nx, ny, nz) array. Blocks are 8³ cubes of the lattice so
/// each block's box is small (the nodes share their work inside it).
py::array_t<double> evaluateLattice(const FieldPtr& field, const py::handle& originValue, const py::handle& spacingValue,
                                    const std::array<py::ssize_t, 3>& shape, int threads)
{
    const glm::dvec3 origin = toVec3(originValue, "origin");
    glm::dvec3 spacing;
    if (py::isinstance<py::float_>(spacingValue) || py::isinstance<py::int_>(spacingValue)) {
        spacing = glm::dvec3(spacingValue.cast<double>());
    } else {
        spacing = toVec3(spacingValue, "spacing");
    }
    if (!(spacing.x > 0 && spacing.y > 0 && spacing.z > 0)) {
        throw Error(ErrorKind::BadInput, "spacing must be positive", {"", 0, "spacing"});
    }
    for (py::ssize_t n : shape) {
        if (n < 0) throw Error(ErrorKind::BadInput, "shape must not be negative", {"", 0, "shape"});
    }
    py::array_t<double> out({shape[0], shape[1], shape[2]});
    double* values = out.mutable_data();
    const std::array<std::size_t, 3> n{std::size_t(shape[0]), std::size_t(shape[1]), std::size_t(shape[2])};
    const std::array<std::size_t, 3> cubes{(n[0] + 7) / 8, (n[1] + 7) / 8, (n[2] + 7) / 8};
    py::gil_scoped_release release;
    inArena(threads, [&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cubes[0] * cubes[1] * cubes[2]),
                          [&](const tbb::blocked_range<std::size_t>& r) {
            std::array<double, BLOCK> x, y, z, v;
            std::array<std::size_t, BLOCK> at;
            for (std::size_t c = r.begin(); c != r.end(); ++c) {
                const std::size_t ci = c / (cubes[1] * cubes[2]), cj = c / cubes[2] % cubes[1], ck = c % cubes[2];
                std::size_t count = 0;
                for (std::size_t i = ci * 8; i < std::min(n[0], ci * 8 + 8); ++i)
                    for (std::size_t j = cj * 8; j < std::min(n[1], cj * 8 + 8); ++j)
                        for (std::size_t k = ck * 8; k < std::min(n[2], ck * 8 + 8); ++k, ++count) {
                            x[count] = origin.x + spacing.x * double(i);
                            y[count] = origin.y + spacing.y * double(j);
                            z[count] = origin.z + spacing.z * double(k);
                            at[count] = (i * n[1] + j) * n[2] + k;
                        }
                terrain::PointBlock block{x.data(), y.data(), z.data(), count, {}};
                block.box = terrain::spannedBox(block);
                field->densities(block, v.data());
                for (std::size_t p = 0; p < count; ++p) values[at[p]] = v[p];
            }
        });
    });
    return out;
}

} // namespace

void bindField(py::module_& m)
{
    py::class_<DensityField, FieldPtr>(m, "Field",
                                       "A density field: signed, distance-like, negative inside rock, zero on the surface.")
        .def("evaluate", &evaluate, py::arg("points"), py::arg("threads") = 0,
             "Densities at an (N, 3) float64 array of points (metres) -> (N,) float64.\n"
             "The same bits as the sampler's; blocks of 512 points over `threads` cores (0: all), GIL released.")
        .def("evaluate_lattice", &evaluateLattice, py::arg("origin"), py::arg("spacing"), py::arg("shape"),
             py::arg("threads") = 0,
             "Densities on a regular lattice: origin + spacing * (i, j, k) for the (nx, ny, nz) `shape`,\n"
             "as an (nx, ny, nz) float64 array (a dense box of the field). `spacing` is a number or (sx, sy, sz).")
        .def("density", [](const DensityField& f, const py::handle& p) { return f.density(toVec3(p, "point")); },
             py::arg("point"), "The density at one point (x, y, z).")
        .def("bounds", [](const DensityField& f, const py::handle& lo, const py::handle& hi) {
            const terrain::WorldBox box{toVec3(lo, "min"), toVec3(hi, "max")};
            if (box.max.x < box.min.x || box.max.y < box.min.y || box.max.z < box.min.z) {
                throw Error(ErrorKind::BadInput, "bounds(): max must be >= min on every axis", {"", 0, "max"});
            }
            const terrain::Interval i = f.bounds(box);
            return py::make_tuple(i.lo, i.hi);
        }, py::arg("min"), py::arg("max"), "An interval (lo, hi) holding every density in the box [min, max].")
        .def_property_readonly("lipschitz", &DensityField::lipschitz, "an upper bound of the gradient's length");
}

} // namespace strata::python
