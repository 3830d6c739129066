// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

#pragma once
/// \file
/// The masks of the rock itself, readable at any world point: how hard the
/// rock is and which bed it belongs to, what texturing rules key on to
/// colour the beds of a cliff (the way the landform masks colour rivers).
/// 3D, unlike the landform masks: an overhanging ledge and the alcove under
/// it are different beds in one column.

#include <glm/vec2.hpp>

#include <cstddef>

namespace strata::terrain {

/// Implemented by nodes that know their rock (the `beds` node). The scene
/// finds one in the node tree with dynamic_cast.
class RockMasks
{
public:
    virtual ~RockMasks() = default;
    /// At n world points (x[i], y[i], z[i]), metres, into out[0, n):
    ///  - x, hardness: 0 (weathers away fastest) .. 1 (not at all), smooth
    ///    across a contact;
    ///  - y, bed: the index of the bed in the sequence as given (0 the
    ///    first, bottom bed; a repeating sequence counts again from 0).
    /// Thread-safe; a pure function of the point (the same bits on any
    /// thread count, tile or chunk).
    virtual void rockMasks(const double* x, const double* y, const double* z, std::size_t n, glm::vec2* out) const = 0;
};

} // namespace strata::terrain
